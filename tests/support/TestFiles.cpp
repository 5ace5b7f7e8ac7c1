#include "support/TestFiles.h"

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <gtest/gtest.h>
#include <unistd.h>

namespace fs = std::filesystem;

namespace bl::test {

std::string tempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = info ? std::string(info->test_suite_name()) + "." + info->name() : "global";
    fs::path dir = fs::temp_directory_path() / ("bundlelab-test-" + std::to_string(::getpid())) / name;
    fs::create_directories(dir);
    return dir.string();
}

std::string writeTempFile(const std::string& name, const std::string& content) {
    fs::path path = fs::path(tempDir()) / name;
    fs::create_directories(path.parent_path());
    std::ofstream(path, std::ios::binary) << content;
    return path.string();
}

std::string sourcePath(const std::string& relative) { return (fs::path(BL_SOURCE_DIR) / relative).string(); }
std::string sharedPath(const std::string& relative) { return (fs::path(BL_SHARED_DIR) / relative).string(); }

bool sharedHas(const std::string& relative) { return fs::exists(sharedPath(relative)); }

std::string sharedMissingMessage(const std::string& relative) {
    return "needs " + fs::path(sharedPath(relative)).lexically_normal().string() +
           ", which is not here (../shared, beside the repository, holds the seed papers' scenes and references)";
}

} // namespace bl::test

namespace bl::test {

std::string missingSharedFileOf(const std::string& sceneRelative) {
    const fs::path scene = sourcePath(sceneRelative);
    std::ifstream in(scene);
    std::stringstream text;
    text << in.rdbuf();
    const std::string content = text.str();
    // Every quoted path that leads into the shared folder (scenes name them relative to themselves).
    static const std::regex quoted("\"([^\"\n]*shared/[^\"\n]*)\"");
    for (std::sregex_iterator it(content.begin(), content.end(), quoted), end; it != end; ++it) {
        const fs::path file = (scene.parent_path() / (*it)[1].str()).lexically_normal();
        if (!fs::exists(file)) return file.string();
    }
    return "";
}

} // namespace bl::test
