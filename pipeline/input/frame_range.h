// Frame ranges and frame file names as render farms and Blender write them: "A-B", "A-BxSTEP"
// or one frame "N"; an output pattern whose run of '#' (or a printf "%0Nd") is the frame
// number, zero-padded.
#pragma once

#include <string>
#include <vector>

namespace pleinair {

struct FrameRange {
    int first = 1, last = 1, step = 1;
    std::vector<int> frames() const;  // first, first + step, ... up to last
};

// Throws InputError naming `option` for anything but A, A-B or A-BxSTEP with 0 <= A <= B and
// STEP >= 1 (so "10-1", "x", "1-" and "1-10x0" are errors).
FrameRange parse_frame_range(const std::string& text, const std::string& option = "--frames");

// An output pattern: the last run of '#' or a "%d" / "%0Nd" stands for the frame number.
struct FramePattern {
    std::string head, tail;
    int width = 0;  // zero padding
    std::string path(int frame) const;
};

// Throws InputError naming `option` when the pattern has no frame number, more than one, one
// padded to over 12 digits, or one in a folder's name.
FramePattern parse_frame_pattern(const std::string& pattern, const std::string& option = "-o");

}  // namespace pleinair
