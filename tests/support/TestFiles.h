// Temporary files for tests, and paths to the repository's data.
#pragma once

#include <string>

namespace bl::test {

// Writes `content` to a fresh file named `name` in a per-test temporary directory; returns its path.
std::string writeTempFile(const std::string& name, const std::string& content);
std::string tempDir();

std::string sourcePath(const std::string& relative); // relative to the repository root
std::string sharedPath(const std::string& relative); // relative to ../shared

// Whether ../shared (the seed papers' scenes, environment maps and independent reference renders,
// kept beside the repository, not in it) holds `relative`. A test that needs it starts with
// BL_SKIP_WITHOUT_SHARED("data/..."): in a clone without ../shared it is skipped with the missing
// path named instead of failing on a file the clone cannot have.
bool sharedHas(const std::string& relative);
std::string sharedMissingMessage(const std::string& relative);
// (Each expands to one if-else statement, so an `else` after it cannot attach to it.)
#define BL_SKIP_WITHOUT_SHARED(relative)                                                                               \
    if (::bl::test::sharedHas(relative)) {                                                                             \
    } else                                                                                                             \
        GTEST_SKIP() << ::bl::test::sharedMissingMessage(relative)

// The first file that the repository's scene `sceneRelative` (a path from the repository root)
// reads from ../shared and that is missing, "" when all are there; BL_SKIP_WITHOUT_SCENE_FILES
// skips a test on such a scene with that path named.
std::string missingSharedFileOf(const std::string& sceneRelative);
#define BL_SKIP_WITHOUT_SCENE_FILES(sceneRelative)                                                                     \
    if (const std::string blMissingShared = ::bl::test::missingSharedFileOf(sceneRelative); blMissingShared.empty()) { \
    } else                                                                                                             \
        GTEST_SKIP() << "needs " << blMissingShared                                                                     \
                     << ", which is not here (../shared, beside the repository, holds the seed papers' scenes)"

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
