#include "config/StrictToml.h"
#include "support/TestFiles.h"

#include <gtest/gtest.h>

using namespace bl;
using bl::test::errorOf;
using bl::test::writeTempFile;

TEST(StrictToml, ReadsTypedValues) {
    std::string path = writeTempFile("a.toml", "x = 1.5\nn = 3\ns = \"hi\"\nb = true\nv = [1, 2.5, 3]\n[t]\ny = 2\n");
    TomlDocument doc(path);
    StrictTable root = doc.root();
    EXPECT_DOUBLE_EQ(root.number("x"), 1.5);
    EXPECT_EQ(root.integer("n"), 3);
    EXPECT_DOUBLE_EQ(root.number("n"), 3.0); // integers are numbers
    EXPECT_EQ(root.string("s"), "hi");
    EXPECT_TRUE(root.boolean("b"));
    EXPECT_EQ(root.vec3("v"), glm::vec3(1.0f, 2.5f, 3.0f));
    EXPECT_DOUBLE_EQ(root.number("absent", 7.0), 7.0);
    auto t = root.table("t");
    ASSERT_TRUE(t);
    EXPECT_DOUBLE_EQ(t->number("y"), 2.0);
    t->finish();
    root.finish();
}

TEST(StrictToml, UnknownKeyNamesFileLineAndKey) {
    std::string path = writeTempFile("b.toml", "x = 1\n\nfov_axsi = \"x\"\n");
    TomlDocument doc(path);
    StrictTable root = doc.root();
    root.number("x");
    std::string e = errorOf([&] { root.finish(); });
    EXPECT_NE(e.find(path + ":3"), std::string::npos) << e;
    EXPECT_NE(e.find("unknown key 'fov_axsi'"), std::string::npos) << e;
}

TEST(StrictToml, WrongTypeAndNonFiniteAreErrors) {
    std::string path = writeTempFile("c.toml", "a = \"text\"\nb = nan\nc = [1, 2]\nd = inf\n");
    TomlDocument doc(path);
    StrictTable root = doc.root();
    std::string e = errorOf([&] { root.number("a"); });
    EXPECT_NE(e.find(":1: a: expected a number"), std::string::npos) << e;
    e = errorOf([&] { root.number("b"); });
    EXPECT_NE(e.find(":2: b: value nan is not finite"), std::string::npos) << e;
    e = errorOf([&] { root.vec3("c"); });
    EXPECT_NE(e.find(":3: c: expected an array of 3 numbers"), std::string::npos) << e;
    e = errorOf([&] { root.vec3("d", glm::vec3(0)); });
    EXPECT_NE(e.find("expected an array"), std::string::npos) << e;
}

TEST(StrictToml, SyntaxErrorAndMissingFile) {
    std::string path = writeTempFile("d.toml", "x = [1, 2\n");
    std::string e = errorOf([&] { TomlDocument doc(path); });
    EXPECT_NE(e.find(path + ":"), std::string::npos) << e;
    EXPECT_NE(e.find("TOML syntax error"), std::string::npos) << e;
    e = errorOf([] { TomlDocument doc("/nonexistent/scene.toml"); });
    EXPECT_NE(e.find("/nonexistent/scene.toml: file not found"), std::string::npos) << e;
}

TEST(StrictToml, MissingRequiredKey) {
    std::string path = writeTempFile("e.toml", "[[material]]\nalbedo = [0.5, 0.5, 0.5]\n");
    TomlDocument doc(path);
    StrictTable root = doc.root();
    std::vector<StrictTable> mats = root.tables("material");
    ASSERT_EQ(mats.size(), 1u);
    std::string e = errorOf([&] { mats[0].string("name"); });
    EXPECT_NE(e.find("material[0]: missing key 'name'"), std::string::npos) << e;
}
