#include "support/MovedScenes.h"

#include "support/TestFiles.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <stdexcept>

namespace fs = std::filesystem;

namespace bl::test {

namespace {

std::string number(double v) {
    char buf[40];
    std::snprintf(buf, sizeof(buf), "%.17e", v);
    return buf;
}

std::string vector(const glm::dvec3& v) {
    return "[" + number(v.x) + ", " + number(v.y) + ", " + number(v.z) + "]";
}

} // namespace

std::string writeMovedScene(const std::string& relative, const glm::dvec3& offset, double scale,
                            const std::string& name) {
    const fs::path source = sourcePath(relative);
    std::ifstream in(source);
    if (!in)
        throw std::runtime_error("cannot read " + source.string());
    // Only the forms the repository's scene files use: `key = [x, y, z]` on one line.
    const std::regex file(R"(^(\s*file\s*=\s*")([^"]+)(".*)$)");
    const std::regex point(R"(^(\s*(position|target)\s*=\s*)\[([^\]]*)\](.*)$)");
    const std::regex intensity(R"(^(\s*intensity\s*=\s*)\[([^\]]*)\](.*)$)");
    const std::regex forbidden(R"(^\s*(translate|scale|rotate)\s*=)");
    std::ostringstream out;
    std::string line;
    std::smatch m;
    auto parse = [](const std::string& list) {
        glm::dvec3 v;
        if (std::sscanf(list.c_str(), "%lf , %lf , %lf", &v.x, &v.y, &v.z) != 3) {
            throw std::runtime_error("not a vector: " + list);
        }
        return v;
    };
    while (std::getline(in, line)) {
        if (std::regex_search(line, forbidden)) {
            throw std::runtime_error(relative + " has its own transform: " + line);
        } else if (std::regex_match(line, m, file)) {
            out << m[1] << (source.parent_path() / m[2].str()).string() << m[3] << "\n"
                << "translate = " << vector(offset) << "\nscale = " << number(scale) << "\n";
        } else if (std::regex_match(line, m, point)) {
            out << m[1] << vector(scale * parse(m[3]) + offset) << m[4] << "\n";
        } else if (std::regex_match(line, m, intensity)) {
            out << m[1] << vector(scale * scale * parse(m[2])) << m[3] << "\n";
        } else {
            out << line << "\n";
        }
    }
    return writeTempFile(name, out.str());
}

} // namespace bl::test
