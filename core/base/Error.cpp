#include "base/Error.h"

#include <charconv>

namespace bl {

void throwAt(const std::string& file, int line, const std::string& message) {
    std::string text = file;
    if (line > 0) {
        text.append(":").append(std::to_string(line));
    }
    text.append(": ").append(message);
    throw Error(text);
}

std::string formatNumber(double value) {
    char buffer[64];
    auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
    return std::string(buffer, result.ptr);
}

std::string formatNumber(float value) {
    char buffer[64];
    auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
    return std::string(buffer, result.ptr);
}

} // namespace bl
