// parse_frame_range and parse_frame_pattern.
#include "pipeline/input/frame_range.h"

#include <regex>

#include "pipeline/input/error.h"

namespace pleinair {

std::vector<int> FrameRange::frames() const {
    std::vector<int> out;
    for (long f = first; f <= last; f += step) out.push_back(static_cast<int>(f));
    return out;
}

FrameRange parse_frame_range(const std::string& text, const std::string& option) {
    static const std::regex form(R"(^(\d{1,9})(?:-(\d{1,9})(?:x(\d{1,9}))?)?$)");
    std::smatch m;
    const std::string expected =
        "expected a frame N or a range A-B or A-BxSTEP (A <= B, STEP >= 1), got \"" + text + "\"";
    if (!std::regex_match(text, m, form)) throw InputError(option, "", expected);
    FrameRange r;
    r.first = std::stoi(m[1]);
    r.last = m[2].matched ? std::stoi(m[2]) : r.first;
    r.step = m[3].matched ? std::stoi(m[3]) : 1;
    if (r.last < r.first || r.step < 1) throw InputError(option, "", expected);
    return r;
}

std::string FramePattern::path(int frame) const {
    std::string digits = std::to_string(frame);
    if (static_cast<int>(digits.size()) < width)
        digits.insert(0, static_cast<size_t>(width) - digits.size(), '0');
    return head + digits + tail;
}

FramePattern parse_frame_pattern(const std::string& pattern, const std::string& option) {
    static const std::regex number(R"(#+|%0?(\d*)d)");
    auto begin = std::sregex_iterator(pattern.begin(), pattern.end(), number);
    const auto end = std::sregex_iterator();
    const auto count = std::distance(begin, end);
    if (count != 1)
        throw InputError(option, "",
                         std::string(count == 0 ? "expected" : "expected only one") +
                             " frame number in the output name (a run of # such as "
                             "frame_####.png, or %04d), got \"" +
                             pattern + "\"");
    const std::smatch& m = *begin;
    FramePattern p;
    p.head = pattern.substr(0, static_cast<size_t>(m.position(0)));
    p.tail = pattern.substr(static_cast<size_t>(m.position(0) + m.length(0)));
    // Frame numbers have at most 9 digits (--frames): padding wider than 12 is a typo.
    const size_t width = m.str(0)[0] == '#'  ? static_cast<size_t>(m.length(0))
                         : m[1].length() > 2 ? 99
                         : m[1].length()     ? std::stoul(m[1])
                                             : 0;
    if (width > 12)
        throw InputError(option, "",
                         "expected at most 12 digits of frame number, got \"" + pattern + "\"");
    p.width = static_cast<int>(width);
    if (p.tail.find('/') != std::string::npos)
        throw InputError(
            option, "",
            "expected the frame number in the file name, not in a folder, got \"" + pattern + "\"");
    return p;
}

}  // namespace pleinair
