// Line-oriented parsing for the text mesh formats (OBJ, MTL, ASCII PLY), with file:line messages.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace bl {

class TextLines {
public:
    // Reads the whole file; throws bl::Error if it cannot.
    explicit TextLines(const std::string& path);
    // Continues over a buffer that starts at `firstLine` (for ASCII PLY bodies).
    TextLines(std::string path, std::string content, int firstLine);

    // Next line without its '#' comment, split on whitespace; false at the end.
    bool next(std::vector<std::string_view>& tokens);
    int lineNumber() const { return mLine; }
    const std::string& path() const { return mPath; }

    [[noreturn]] void fail(const std::string& message) const;
    float toFloat(std::string_view token) const;        // finite, or an error naming the value
    long long toInteger(std::string_view token) const;

private:
    std::string mPath;
    std::string mContent;
    std::size_t mPos = 0;
    int mLine = 0;
};

std::string readWholeFile(const std::string& path);

} // namespace bl
