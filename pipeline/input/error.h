// InputError: bad input (a preset, a scene, a command-line value), reported as one line per
// problem naming the source, the JSON pointer, what was expected and what was found.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

namespace pleinair {

struct Problem {
    std::string pointer;  // JSON pointer ("/trunk/taper/base"), or empty for the whole source
    std::string message;  // "must be in [0, 1], got 1.7"
};

class InputError : public std::runtime_error {
  public:
    InputError(std::string source, std::vector<Problem> problems);
    InputError(std::string source, std::string pointer, std::string message);

    const std::string& source() const { return source_; }
    const std::vector<Problem>& problems() const { return problems_; }

  private:
    std::string source_;
    std::vector<Problem> problems_;
};

// A key as one token of a JSON pointer (RFC 6901): "~" as "~0" and "/" as "~1", so a key
// holding a slash is not read as two keys.
std::string pointer_token(const std::string& key);

// A library's message cut to its first line (trailing spaces dropped): libraries report one
// failure on several lines, and a problem is one.
std::string first_line(std::string message);

// "source: pointer: message" lines, the form every command prints on stderr. Control
// characters (a key holding a newline) are printed escaped, so each problem stays one line.
std::string format_problems(const std::string& source, const std::vector<Problem>& problems);

}  // namespace pleinair
