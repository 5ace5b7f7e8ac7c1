#include "support/TestFiles.h"

#include <filesystem>
#include <fstream>
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

} // namespace bl::test
