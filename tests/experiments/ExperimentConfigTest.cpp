#include "runner/ExperimentConfig.h"
#include "support/TestFiles.h"

#include <gtest/gtest.h>

#include <filesystem>

using namespace bl;
using bl::test::errorOf;
using bl::test::sourcePath;
using bl::test::tempDir;
using bl::test::writeTempFile;

TEST(ExperimentConfig, ExpandsTheGrid) {
    ExperimentConfig c = loadExperimentConfig(sourcePath("tests/experiments/tiny.toml"));
    // reference: 1 scene x 2 seeds; raster: 1 scene x 2 grid points x 2 seeds; skylight: 1 x 2.
    ASSERT_EQ(c.tasks.size(), 2u + 4u + 2u);
    EXPECT_EQ(c.tasks[0].id, "0000-cornell-pt-s0");
    EXPECT_EQ(c.tasks[2].id, "0002-cornell-raster-shadow_resolution_64-s0");
    EXPECT_EQ(c.tasks[2].checkpoints, (std::vector<std::uint32_t>{1, 2, 4}));
    EXPECT_EQ(c.tasks[6].budget.iterations, 8u);
    EXPECT_TRUE(c.tasks[6].needsGpu);
    EXPECT_FALSE(c.tasks[0].needsGpu);
    ASSERT_EQ(c.tasks[6].referenceSettings.size(), 1u);
    EXPECT_EQ(c.tasks[6].referenceSettings[0].first, "max_segments");
    // Every task is identified by what determines its result.
    EXPECT_NE(c.tasks[0].hash, c.tasks[1].hash);
    EXPECT_EQ(c.tasks[0].hash, loadExperimentConfig(sourcePath("tests/experiments/tiny.toml")).tasks[0].hash);
    EXPECT_EQ(logCheckpoints(10), (std::vector<std::uint32_t>{1, 2, 4, 8, 10}));
}

namespace {
std::string configWith(const std::string& name, const std::string& modes, const std::string& extra = "") {
    const std::string scene = sourcePath("data/cornell-box/cornell.toml");
    return writeTempFile(name, "[experiment]\nname = \"x\"\n" + extra + "\n[[scene]]\nfile = \"" + scene + "\"\n\n" + modes);
}
std::string errorFor(const std::string& path) {
    return errorOf([&] { loadExperimentConfig(path); });
}
} // namespace

TEST(ExperimentConfig, ErrorsBeforeAnyTaskRuns) {
    // Lines: 1 [experiment], 2 name, 3 extra, 4 [[scene]], 5 file, 6 blank, 7 [[mode]], 8 mode, ...
    std::string p = configWith("a.toml", "[[mode]]\nmode = \"rasterr\"\n");
    EXPECT_NE(errorFor(p).find(p + ":8: mode[0].mode: unknown mode 'rasterr'"), std::string::npos) << errorFor(p);
    p = configWith("b.toml", "[[mode]]\nmode = \"raster\"\ngrid = { shadow_res = [1, 2] }\n");
    EXPECT_NE(errorFor(p).find("unknown parameter 'shadow_res'"), std::string::npos) << errorFor(p);
    p = configWith("c.toml", "[[mode]]\nmode = \"raster\"\ngrid = { shadow_resolution = [512, 3] }\n");
    EXPECT_NE(errorFor(p).find("shadow_resolution' = 3 outside [16, 8192]"), std::string::npos) << errorFor(p);
    p = configWith("d.toml", "[[mode]]\nmode = \"raster\"\ncolour = 1\n");
    EXPECT_NE(errorFor(p).find(p + ":9: mode[0]: unknown key 'colour'"), std::string::npos) << errorFor(p);
    p = configWith("e.toml", "[[mode]]\nmode = \"raster\"\nscenes = [\"kitchen\"]\n");
    EXPECT_NE(errorFor(p).find("no [[scene]] named 'kitchen'"), std::string::npos) << errorFor(p);
    p = configWith("f.toml", "[[mode]]\nmode = \"raster\"\n[[mode]]\nmode = \"raster\"\n");
    EXPECT_NE(errorFor(p).find("duplicate label 'raster'"), std::string::npos) << errorFor(p);
    p = configWith("g.toml", "[[mode]]\nmode = \"raster\"\n", "iterations = 0");
    EXPECT_NE(errorFor(p).find(p + ":3: experiment.iterations: value 0 outside"), std::string::npos) << errorFor(p);
    p = configWith("h.toml", "[[mode]]\nmode = \"raster\"\nreference = { max_segmets = 2 }\n");
    EXPECT_NE(errorFor(p).find("unknown parameter 'max_segmets'"), std::string::npos) << errorFor(p);
    p = writeTempFile("i.toml", "[experiment]\nname = \"x\"\n[[scene]]\nfile = \"missing.toml\"\n[[mode]]\nmode = \"raster\"\n");
    EXPECT_NE(errorFor(p).find("missing.toml: file not found"), std::string::npos) << errorFor(p);
    p = configWith("j.toml", "");
    EXPECT_NE(errorFor(p).find("no [[mode]]"), std::string::npos) << errorFor(p);
}

TEST(ExperimentConfig, EditingAMeshInvalidatesFinishedTasks) {
    writeTempFile("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    writeTempFile("scene.toml", "[[mesh]]\nfile = \"tri.obj\"\n");
    std::string config = writeTempFile("e.toml", "[experiment]\nname = \"x\"\n[[scene]]\nfile = \"scene.toml\"\n"
                                                 "[[mode]]\nmode = \"raster\"\n");
    const std::string before = loadExperimentConfig(config).tasks.at(0).hash;
    EXPECT_EQ(loadExperimentConfig(config).tasks.at(0).hash, before);
    writeTempFile("tri.obj", "v 0 0 0\nv 2 0 0\nv 0 1 0\nf 1 2 3\n"); // the scene file is unchanged
    EXPECT_NE(loadExperimentConfig(config).tasks.at(0).hash, before);
}

// Editing an MTL, or adding one the OBJ names but that was missing, is a different scene too
// (Scene::inputFiles lists files looked for and not found; the runner hashes them as absent).
TEST(ExperimentConfig, EditingOrAddingAMaterialFileInvalidatesFinishedTasks) {
    writeTempFile("tri.obj", "mtllib tri.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl m\nf 1 2 3\n");
    std::filesystem::remove(std::filesystem::path(tempDir()) / "tri.mtl");
    writeTempFile("scene.toml", "[[mesh]]\nfile = \"tri.obj\"\n");
    std::string config = writeTempFile("e.toml", "[experiment]\nname = \"x\"\n[[scene]]\nfile = \"scene.toml\"\n"
                                                 "[[mode]]\nmode = \"raster\"\n");
    const std::string missing = loadExperimentConfig(config).tasks.at(0).hash;
    writeTempFile("tri.mtl", "newmtl m\nKd 0.5 0.5 0.5\n");
    const std::string added = loadExperimentConfig(config).tasks.at(0).hash;
    EXPECT_NE(added, missing);
    writeTempFile("tri.mtl", "newmtl m\nKd 0.25 0.5 0.5\n");
    EXPECT_NE(loadExperimentConfig(config).tasks.at(0).hash, added);
}

// Names become paths under the output directory (results/<experiment>, references/<scene>-…):
// none may leave it.
TEST(ExperimentConfig, NamesCannotLeaveTheOutputDirectory) {
    const std::string scene = sourcePath("data/cornell-box/cornell.toml");
    auto config = [&](const std::string& experiment, const std::string& sceneName) {
        return writeTempFile("names.toml", "[experiment]\nname = \"" + experiment + "\"\n[[scene]]\nfile = \"" + scene +
                                               "\"\nname = \"" + sceneName + "\"\n[[mode]]\nmode = \"raster\"\n");
    };
    for (const std::string bad : {"../x", "/tmp/x", "a/b", "..", ".", "", "a\\\\b"}) {
        const std::string p = config(bad, "ok");
        const std::string shown = bad == "a\\\\b" ? "a\\b" : bad;
        EXPECT_NE(errorFor(p).find(p + ":2: experiment.name: '" + shown + "' is not a plain name"), std::string::npos)
            << errorFor(p);
    }
    for (const std::string bad : {"x/../../../../y", "..", "/etc/passwd", "a/b"}) {
        const std::string p = config("ok", bad);
        EXPECT_NE(errorFor(p).find(p + ":5: scene[0].name: '" + bad + "' is not a plain name"), std::string::npos)
            << errorFor(p);
    }
    EXPECT_EQ(errorFor(config("bidir-equal-time.v2", "cornell_box")), "");
}
