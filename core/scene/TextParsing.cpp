#include "scene/TextParsing.h"

#include "base/Error.h"

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

namespace bl {

std::string readWholeFile(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        throw Error(path + ": file not found or unreadable");
    }
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

TextLines::TextLines(const std::string& path) : mPath(path), mContent(readWholeFile(path)) {}

TextLines::TextLines(std::string path, std::string content, int firstLine)
    : mPath(std::move(path)), mContent(std::move(content)), mLine(firstLine - 1) {}

bool TextLines::next(std::vector<std::string_view>& tokens) {
    tokens.clear();
    if (mPos >= mContent.size()) {
        return false;
    }
    std::size_t end = mContent.find('\n', mPos);
    if (end == std::string::npos) {
        end = mContent.size();
    }
    std::string_view line(mContent.data() + mPos, end - mPos);
    mPos = end + 1;
    ++mLine;
    if (auto hash = line.find('#'); hash != std::string_view::npos) {
        line = line.substr(0, hash);
    }
    std::size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) {
            ++i;
        }
        std::size_t j = i;
        while (j < line.size() && !std::isspace(static_cast<unsigned char>(line[j]))) {
            ++j;
        }
        if (j > i) {
            tokens.push_back(line.substr(i, j - i));
        }
        i = j;
    }
    return true;
}

void TextLines::fail(const std::string& message) const { throwAt(mPath, mLine, message); }

float TextLines::toFloat(std::string_view token) const {
    double v = 0.0;
    auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), v);
    if (ec != std::errc() || ptr != token.data() + token.size()) {
        fail("expected a number, got '" + std::string(token) + "'");
    }
    if (!std::isfinite(v) || std::abs(v) > 3.0e38) {
        fail("value '" + std::string(token) + "' is not finite");
    }
    return static_cast<float>(v);
}

long long TextLines::toInteger(std::string_view token) const {
    long long v = 0;
    auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), v);
    if (ec != std::errc() || ptr != token.data() + token.size()) {
        fail("expected an integer, got '" + std::string(token) + "'");
    }
    return v;
}

} // namespace bl
