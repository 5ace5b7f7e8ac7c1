// The one exception type of bundlelab. Messages name what a user needs to fix the problem: the
// file, the line where known, and the offending key or value.
#pragma once

#include <stdexcept>
#include <string>

namespace bl {

class Error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// "file:line: message" (line <= 0 leaves the line out).
[[noreturn]] void throwAt(const std::string& file, int line, const std::string& message);

// Formats a float the way a user typed it (shortest round-trip form).
std::string formatNumber(double value);
// A float in its own shortest form (1.2f prints as 1.2, not 1.2000000476837158).
std::string formatNumber(float value);

} // namespace bl
