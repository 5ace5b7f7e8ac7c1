// Temporary files for tests, and paths to the repository's data.
#pragma once

#include <string>

namespace bl::test {

// Writes `content` to a fresh file named `name` in a per-test temporary directory; returns its path.
std::string writeTempFile(const std::string& name, const std::string& content);
std::string tempDir();

std::string sourcePath(const std::string& relative); // relative to the repository root
std::string sharedPath(const std::string& relative); // relative to ../shared

// The message of the bl::Error that `f` throws ("" if it throws none).
template <typename F> std::string errorOf(F&& f) {
    try {
        f();
    } catch (const std::exception& e) {
        return e.what();
    }
    return "";
}

} // namespace bl::test
