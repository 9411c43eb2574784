// InputError and its one-line-per-problem format.
#include "pipeline/input/error.h"

#include <algorithm>

namespace pleinair {

std::string pointer_token(const std::string& key) {
    std::string t;
    for (char c : key) {
        if (c == '~')
            t += "~0";
        else if (c == '/')
            t += "~1";
        else
            t += c;
    }
    return t;
}

namespace {

// `text` with control characters as C escapes (\n, \t, \x1b).
std::string printable(const std::string& text) {
    std::string s;
    for (unsigned char c : text) {
        if (c == '\n') {
            s += "\\n";
        } else if (c == '\t') {
            s += "\\t";
        } else if (c == '\r') {
            s += "\\r";
        } else if (c < 0x20 || c == 0x7f) {
            static const char* kHex = "0123456789abcdef";
            s += "\\x";
            s += kHex[c >> 4];
            s += kHex[c & 15];
        } else {
            s += static_cast<char>(c);
        }
    }
    return s;
}

// One line a key: a value that breaks two rules (out of range and not whole) is told by the
// first rule found broken; other keys keep their own lines.
std::vector<Problem> first_per_key(std::vector<Problem> problems) {
    std::vector<Problem> out;
    for (Problem& p : problems) {
        const bool told = !p.pointer.empty() && std::any_of(out.begin(), out.end(), [&](auto& q) {
            return q.pointer == p.pointer;
        });
        if (!told) out.push_back(std::move(p));
    }
    return out;
}

}  // namespace

std::string first_line(std::string s) {
    if (const size_t eol = s.find('\n'); eol != std::string::npos) s.resize(eol);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\r')) s.pop_back();
    return s;
}

std::string format_problems(const std::string& source, const std::vector<Problem>& problems) {
    std::string s;
    for (const auto& p : problems) {
        if (!s.empty()) s += '\n';
        s.append(printable(source));
        if (!p.pointer.empty()) s.append(": ").append(printable(p.pointer));
        s.append(": ").append(printable(p.message));
    }
    return s;
}

InputError::InputError(std::string source, std::vector<Problem> problems)
    : std::runtime_error(format_problems(source, first_per_key(problems))),
      source_(std::move(source)),
      problems_(first_per_key(std::move(problems))) {}

InputError::InputError(std::string source, std::string pointer, std::string message)
    : InputError(std::move(source),
                 std::vector<Problem>{{std::move(pointer), std::move(message)}}) {}

}  // namespace pleinair
