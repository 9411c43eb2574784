// InputError and its one-line-per-problem format.
#include "pipeline/error.h"

namespace pleinair {

std::string format_problems(const std::string& source, const std::vector<Problem>& problems) {
    std::string s;
    for (const auto& p : problems) {
        if (!s.empty()) s += '\n';
        s.append(source);
        if (!p.pointer.empty()) s.append(": ").append(p.pointer);
        s.append(": ").append(p.message);
    }
    return s;
}

InputError::InputError(std::string source, std::vector<Problem> problems)
    : std::runtime_error(format_problems(source, problems)),
      source_(std::move(source)),
      problems_(std::move(problems)) {}

InputError::InputError(std::string source, std::string pointer, std::string message)
    : InputError(std::move(source),
                 std::vector<Problem>{{std::move(pointer), std::move(message)}}) {}

}  // namespace pleinair
