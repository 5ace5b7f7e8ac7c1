#include "scene/SceneLoader.h"
#include "support/TestFiles.h"

#include <algorithm>
#include <filesystem>
#include <gtest/gtest.h>
#include <map>
#include <set>
#include <string>
#include <vector>

using namespace bl;
using bl::test::errorOf;
using bl::test::missingSharedFileOf;
using bl::test::sharedPath;
using bl::test::sourcePath;
using bl::test::writeTempFile;

namespace {

const char* kQuadObj = "v 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\nf 1 4 3 2\n";
// Two quads with MTL materials 'red' and 'blue', for material remapping.
const char* kTwoObj = "mtllib two.mtl\nv 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\nv 0 1 0\nv 1 1 0\nv 1 1 1\n"
                      "v 0 1 1\nusemtl red\nf 1 4 3 2\nusemtl blue\nf 5 8 7 6\n";
const char* kTwoMtl = "newmtl red\nKd 0.8 0.1 0.1\nnewmtl blue\nKd 0.1 0.1 0.8\n";

// A minimal valid scene whose mesh file sits beside it; `extra` is appended verbatim.
std::string sceneWith(const std::string& extra, const std::string& name = "scene.toml") {
    writeTempFile("quad.obj", kQuadObj);
    writeTempFile("two.obj", kTwoObj);
    writeTempFile("two.mtl", kTwoMtl);
    return writeTempFile(name, "[[material]]\nname = \"white\"\nalbedo = [0.5, 0.5, 0.5]\n\n"
                               "[[mesh]]\nfile = \"quad.obj\"\nmaterial = \"white\"\n" +
                                   extra);
}

std::string loadError(const std::string& path) {
    return errorOf([&] { loadScene(path); });
}

} // namespace

TEST(SceneLoader, LoadsTheTypedCornellBox) {
    Scene s = loadScene(sourcePath("data/cornell-box/cornell.toml"));
    SceneFeatures f = s.features();
    EXPECT_EQ(f.triangles, 32u);
    EXPECT_EQ(f.materials, 4u);
    EXPECT_EQ(f.emissiveMeshes, 1u);
    EXPECT_EQ(f.emissiveTriangles, 2u);
    EXPECT_FALSE(f.glossy);
    EXPECT_FALSE(f.animated);
    EXPECT_NEAR(f.bounds.hi.x, 556.0f, 1e-3f);
    EXPECT_NEAR(f.bounds.hi.z, 559.2f, 1e-3f);
    EXPECT_EQ(s.camera.resolution, glm::ivec2(512, 512));
    EXPECT_EQ(s.camera.fovAxis, FovAxis::X);
    const Mesh* light = nullptr;
    for (const Mesh& m : s.meshes) {
        if (m.emissive()) light = &m;
    }
    ASSERT_TRUE(light);
    EXPECT_EQ(light->emission, glm::vec3(17.0f, 12.0f, 4.0f));
}

// Scene::inputFiles (what the runner hashes to tell a changed scene): the scene file, every mesh
// file and the MTL an OBJ names, and an MTL named but missing (adding it changes the scene).
TEST(SceneLoader, InputFilesAreEveryFileRead) {
    const std::string path = sceneWith("[[mesh]]\nfile = \"two.obj\"\n");
    const Scene s = loadScene(path);
    const std::string dir = std::filesystem::path(path).parent_path().string();
    const auto in = [&](const std::string& name) {
        return std::count(s.inputFiles.begin(), s.inputFiles.end(), (std::filesystem::path(dir) / name).string());
    };
    EXPECT_EQ(s.inputFiles.size(), 4u);
    EXPECT_EQ(in("scene.toml"), 1);
    EXPECT_EQ(in("quad.obj"), 1);
    EXPECT_EQ(in("two.obj"), 1);
    EXPECT_EQ(in("two.mtl"), 1);

    writeTempFile("lost.obj", std::string("mtllib lost.mtl\n") + kQuadObj);
    const Scene lost = loadScene(writeTempFile("lost.toml", "[[mesh]]\nfile = \"lost.obj\"\n"));
    EXPECT_EQ(std::count(lost.inputFiles.begin(), lost.inputFiles.end(), (std::filesystem::path(dir) / "lost.mtl").string()), 1)
        << "a missing MTL is listed";
}

// Mitsuba: the main file, its includes and the mesh files their shapes name (the cbox: three
// fragments, eight OBJs); shapes the importer tessellates (veach_mis's five spheres) add none.
TEST(SceneLoader, MitsubaInputFilesIncludeTheIncludes) {
    BL_SKIP_WITHOUT_SHARED("data/cornell-box/mitsuba-cbox/cbox-rgb.xml");
    BL_SKIP_WITHOUT_SHARED("data/glossy/veach-mis/veach_mis.xml");
    const auto namesOf = [](const Scene& s) {
        std::vector<std::string> names;
        for (const std::string& f : s.inputFiles) {
            EXPECT_TRUE(std::filesystem::is_regular_file(f)) << f;
            names.push_back(std::filesystem::path(f).filename().string());
        }
        return names;
    };
    const auto count = [](const std::vector<std::string>& names, const std::string& ext) {
        return std::count_if(names.begin(), names.end(),
                             [&](const std::string& n) { return std::filesystem::path(n).extension() == ext; });
    };
    const std::vector<std::string> cbox = namesOf(loadScene(bl::test::sharedPath("data/cornell-box/mitsuba-cbox/cbox-rgb.xml")));
    for (const char* name : {"cbox-rgb.xml", "base.xml", "bsdfs-rgb.xml", "shapes.xml"}) {
        EXPECT_EQ(std::count(cbox.begin(), cbox.end(), name), 1) << name;
    }
    EXPECT_EQ(count(cbox, ".obj"), 8);
    EXPECT_EQ(cbox.size(), 12u);
    const std::vector<std::string> veach = namesOf(loadScene(bl::test::sharedPath("data/glossy/veach-mis/veach_mis.xml")));
    EXPECT_EQ(count(veach, ".xml"), 1);
    EXPECT_EQ(count(veach, ".obj"), 5); // the plates and the floor
    EXPECT_EQ(veach.size(), 6u);
}

// Every scene of data/ loads; those that read ../shared only where it is there (the others are
// listed, and the test is marked skipped when any was left out).

TEST(SceneLoader, EverySceneInDataLoads) {
    std::vector<std::string> leftOut;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(sourcePath("data"))) {
        if (entry.path().extension() == ".toml") {
            SCOPED_TRACE(entry.path().string());
            const std::string relative = std::filesystem::relative(entry.path(), sourcePath("")).string();
            if (const std::string missing = missingSharedFileOf(relative); !missing.empty()) {
                leftOut.push_back(relative + " (needs " + missing + ")");
                continue;
            }
            EXPECT_NO_THROW(loadScene(entry.path().string()));
        }
    }
    if (!leftOut.empty()) {
        std::string list;
        for (const std::string& s : leftOut) list += "\n  " + s;
        GTEST_SKIP() << "the other scenes load; left out, ../shared not here:" << list;
    }
}

TEST(SceneLoader, McGuireCornellDropsDuplicatesAndKeepsItsLight) {
    BL_SKIP_WITHOUT_SHARED("data/cornell-box/mcguire/CornellBox-Original.obj");
    Scene s = loadScene(sharedPath("data/cornell-box/mcguire/CornellBox-Original.obj"));
    SceneFeatures f = s.features();
    EXPECT_GT(s.loadStats.duplicateTriangles + s.loadStats.degenerateTriangles, 0u);
    EXPECT_EQ(f.emissiveMeshes, 1u);
    EXPECT_TRUE(s.lights.empty()); // the MTL emitter lights it: no headlight added
    for (const Mesh& m : s.meshes) {
        for (const glm::vec3& n : m.normals) {
            EXPECT_NEAR(glm::length(n), 1.0f, 1e-4f);
        }
    }
}

TEST(SceneLoader, BareMeshGetsCameraAndLight) {
    BL_SKIP_WITHOUT_SHARED("data/bunny/stanford/bun_zipper_res4.ply");
    Scene s = loadScene(sharedPath("data/bunny/stanford/bun_zipper_res4.ply"));
    EXPECT_EQ(s.lights.size(), 1u);
    EXPECT_TRUE(s.environment.present);
    EXPECT_GT(s.triangleCount(), 900u);
    Bounds b = s.bounds();
    // The fitted camera sees the bounding sphere: its distance exceeds the radius.
    EXPECT_GT(glm::length(s.camera.pose.position - b.center()), b.radius());
}

TEST(SceneLoader, TransformsAndKeyframes) {
    Scene s = loadScene(sceneWith("translate = [0, 2, 0]\nscale = 2.0\n"
                                  "[[mesh.keyframe]]\ntime = 0.0\n"
                                  "[[mesh.keyframe]]\ntime = 1.0\ntranslate = [4, 0, 0]\n"));
    ASSERT_EQ(s.meshes.size(), 1u);
    Bounds local;
    for (const glm::vec3& p : s.meshes[0].positions) local.extend(p);
    EXPECT_EQ(local.lo, glm::vec3(0, 2, 0)); // the unit quad, scaled by 2, raised by 2
    EXPECT_EQ(local.hi, glm::vec3(2, 2, 2));
    EXPECT_TRUE(s.features().animated);
    glm::vec4 mid = s.meshes[0].animation.at(0.5) * glm::vec4(0, 0, 0, 1);
    EXPECT_NEAR(mid.x, 2.0f, 1e-5f);
    EXPECT_NEAR(s.bounds().hi.x, 6.0f, 1e-5f); // bounds cover every keyframe
}

TEST(SceneLoader, LightsAndEnvironment) {
    Scene s = loadScene(sceneWith("[[light]]\ntype = \"spot\"\nposition = [0, 1, 0]\nintensity = [1, 2, 3]\n"
                                  "direction = [0, -2, 0]\ncone_angle = 30\nfalloff = 5\n"
                                  "[environment]\nradiance = [0.5, 0.5, 0.5]\nrotation = 90\n"));
    ASSERT_EQ(s.lights.size(), 1u);
    EXPECT_EQ(s.lights[0].type, Light::Type::Spot);
    EXPECT_EQ(s.lights[0].direction, glm::vec3(0, -1, 0));
    EXPECT_TRUE(s.environment.present);
    EXPECT_FALSE(s.environment.hasMap());
    EXPECT_EQ(s.features().spotLights, 1u);
}

TEST(SceneLoader, LightKeyframes) {
    Scene s = loadScene(sceneWith("[[light]]\ntype = \"spot\"\nposition = [0, 1, 0]\nintensity = [1, 1, 1]\n"
                                  "direction = [0, -1, 0]\ncone_angle = 30\n"
                                  "[[light.keyframe]]\ntime = 0.0\n"
                                  "[[light.keyframe]]\ntime = 1.0\nposition = [2, 1, 0]\ndirection = [0, 0, -3]\n"));
    ASSERT_EQ(s.lights.size(), 1u);
    ASSERT_EQ(s.lights[0].keys.size(), 2u);
    EXPECT_EQ(s.lights[0].keys[0].position, glm::vec3(0, 1, 0)); // a key without position keeps the light's
    EXPECT_EQ(s.lights[0].keys[1].direction, glm::vec3(0, 0, -1)); // unit
    EXPECT_EQ(s.lightsAt(0.5)[0].position, glm::vec3(1, 1, 0));
    EXPECT_TRUE(s.features().animated);
}

TEST(SceneLoader, EnvironmentMapFromSharedData) {
    BL_SKIP_WITHOUT_SHARED("data/envmap/classroom-sky.hdr");
    std::string hdr = std::filesystem::absolute(sharedPath("data/envmap/classroom-sky.hdr")).string();
    Scene s = loadScene(sceneWith("[environment]\nfile = \"" + hdr + "\"\nscale = 2.0\n"));
    EXPECT_TRUE(s.environment.hasMap());
    EXPECT_EQ(s.environment.map.width(), 512);
}

TEST(SceneLoader, MeshMaterialsMapToSceneMaterialsByName) {
    Scene s = loadScene(sceneWith("[[material]]\nname = \"glossy\"\nalbedo = [0.2, 0.2, 0.2]\n"
                                  "specular = [0.5, 0.5, 0.5]\nexponent = 40\n"
                                  "[[mesh]]\nfile = \"two.obj\"\nmaterials = { red = \"glossy\" }\n"));
    std::map<std::string, std::string> materialOfMesh; // MTL group -> the scene material it got
    for (const Mesh& m : s.meshes) {
        materialOfMesh[m.name.substr(m.name.rfind(':') + 1)] = s.materials.at(m.material).name;
    }
    EXPECT_EQ(materialOfMesh["red"], "glossy");
    EXPECT_EQ(materialOfMesh["blue"], "blue"); // unmapped: the MTL's own material
    // The replaced MTL material is not added: it would count as a material nothing uses.
    std::set<std::string> names;
    for (const Material& m : s.materials) names.insert(m.name);
    EXPECT_EQ(names, (std::set<std::string>{"white", "glossy", "blue"}));
    EXPECT_TRUE(s.features().glossy);
}

TEST(SceneLoader, McGuireGlossyGetsTheExactMaterialsOfItsSceneFile) {
    BL_SKIP_WITHOUT_SCENE_FILES("data/external/cornell-glossy-point.toml");
    Scene s = loadScene(sourcePath("data/external/cornell-glossy-point.toml"));
    std::map<std::string, std::string> materialOfMesh;
    for (const Mesh& m : s.meshes) {
        materialOfMesh[m.name.substr(m.name.rfind(':') + 1)] = s.materials.at(m.material).name;
    }
    EXPECT_EQ(materialOfMesh["sphere"], "glossy-sphere");
    EXPECT_EQ(materialOfMesh["shortBox"], "glossy-box");
    EXPECT_EQ(materialOfMesh["light"], "light-panel");
    EXPECT_EQ(materialOfMesh["floor"], "floor");
    EXPECT_EQ(s.features().pointLights, 1u);
    EXPECT_EQ(s.features().emissiveMeshes, 0u);
}

TEST(SceneLoader, AnEmptySceneIsAnErrorNamingTheFile) {
    std::string path = writeTempFile("empty.toml", "[[light]]\nposition = [0, 1, 0]\nintensity = [1, 1, 1]\n");
    std::string e = loadError(path);
    EXPECT_NE(e.find(path + ": the scene has no triangles"), std::string::npos) << e;
    // Triangles that cleanup drops (all degenerate) leave nothing either.
    std::string obj = writeTempFile("flat.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n");
    e = loadError(obj);
    EXPECT_NE(e.find(obj + ": the scene has no triangles"), std::string::npos) << e;
}

struct BadScene {
    const char* name;
    std::string extra;
    int line;             // expected line in the message (0: not checked)
    const char* expected; // substring of the message
};

class SceneLoaderErrors : public ::testing::TestWithParam<BadScene> {};

TEST_P(SceneLoaderErrors, NamesFileLineAndValue) {
    const BadScene& bad = GetParam();
    std::string path = sceneWith(bad.extra, std::string(bad.name) + ".toml");
    std::string e = loadError(path);
    EXPECT_NE(e.find(bad.expected), std::string::npos) << "message: " << e;
    EXPECT_NE(e.find(path), std::string::npos) << "message: " << e;
    if (bad.line > 0) {
        EXPECT_NE(e.find(path + ":" + std::to_string(bad.line) + ":"), std::string::npos) << "message: " << e;
    }
}

// The base scene has 7 lines; `extra` starts on line 8.
INSTANTIATE_TEST_SUITE_P(
    Invalid, SceneLoaderErrors,
    ::testing::Values(
        BadScene{"unknown_key", "colour = [1, 0, 0]\n", 8, "unknown key 'colour'"},
        BadScene{"unknown_top", "[lights]\nx = 1\n", 8, "unknown key 'lights'"},
        BadScene{"wrong_type", "[camera]\nfov = \"wide\"\n", 9, "camera.fov: expected a number"},
        BadScene{"nan", "[camera]\nfov = nan\n", 9, "not finite"},
        BadScene{"inf_position", "[[light]]\nposition = [0, inf, 0]\nintensity = [1, 1, 1]\n", 9, "not finite"},
        BadScene{"zero_resolution", "[camera]\nresolution = [0, 512]\n", 9, "resolution: value 0 outside [1, 16384]"},
        BadScene{"absurd_resolution", "[camera]\nresolution = [1000000, 512]\n", 9, "value 1000000 outside"},
        BadScene{"fov_axis", "[camera]\nfov_axis = \"z\"\n", 9, "expected \"x\" or \"y\""},
        BadScene{"camera_degenerate", "[camera]\nposition = [0, 0, 0]\ntarget = [0, 0, 0]\n", 0,
                 "camera target equals its position"},
        BadScene{"up_parallel", "[camera]\nposition = [0, 0, 0]\ntarget = [0, 1, 0]\nup = [0, 2, 0]\n", 0,
                 "parallel"},
        BadScene{"albedo_range", "[[material]]\nname = \"hot\"\nalbedo = [1.2, 0.5, 0.5]\n", 10,
                 "albedo: value 1.2 outside [0, 1]"},
        BadScene{"negative_specular", "[[material]]\nname = \"s\"\nspecular = [-0.1, 0, 0]\n", 10, "outside [0, 1]"},
        BadScene{"exponent", "[[material]]\nname = \"e\"\nexponent = 0\n", 10, "exponent: value 0 outside"},
        BadScene{"duplicate_material", "[[material]]\nname = \"white\"\n", 9, "duplicate material name 'white'"},
        BadScene{"unknown_material", "[[mesh]]\nfile = \"quad.obj\"\nmaterial = \"gold\"\n", 10,
                 "no [[material]] named 'gold'"},
        BadScene{"unknown_mtl_material", "[[mesh]]\nfile = \"two.obj\"\nmaterials = { green = \"white\" }\n", 10,
                 "two.obj has no MTL material 'green' (it has: blue, red)"},
        BadScene{"unknown_mapped_material", "[[mesh]]\nfile = \"two.obj\"\nmaterials = { red = \"gold\" }\n", 10,
                 "materials.red: no [[material]] named 'gold'"},
        BadScene{"material_and_materials",
                 "[[mesh]]\nfile = \"two.obj\"\nmaterial = \"white\"\nmaterials = { red = \"white\" }\n", 11,
                 "give either material or materials, not both"},
        BadScene{"missing_mesh", "[[mesh]]\nfile = \"nothere.obj\"\n", 9, "file 'nothere.obj' not found"},
        BadScene{"negative_scale", "[[mesh]]\nfile = \"quad.obj\"\nscale = -1.0\n", 10, "scale: value -1 must be positive"},
        BadScene{"negative_emission", "[[mesh]]\nfile = \"quad.obj\"\nemission = [1, -1, 1]\n", 10,
                 "emission: value -1 is negative"},
        BadScene{"light_type", "[[light]]\ntype = \"area\"\nposition = [0, 1, 0]\nintensity = [1, 1, 1]\n", 9,
                 "expected \"point\" or \"spot\""},
        BadScene{"spot_cone", "[[light]]\ntype = \"spot\"\nposition = [0, 1, 0]\nintensity = [1, 1, 1]\n"
                              "direction = [0, -1, 0]\ncone_angle = 0\n",
                 13, "cone_angle: value 0 outside"},
        BadScene{"spot_direction", "[[light]]\ntype = \"spot\"\nposition = [0, 1, 0]\nintensity = [1, 1, 1]\n"
                                   "direction = [0, 0, 0]\ncone_angle = 10\n",
                 12, "direction must not be zero"},
        BadScene{"env_both", "[environment]\nradiance = [1, 1, 1]\nfile = \"x.hdr\"\n", 0, "exactly one of"},
        BadScene{"keyframe_order", "[[mesh.keyframe]]\ntime = 1.0\n[[mesh.keyframe]]\ntime = 0.5\n", 11,
                 "keyframe times must increase"},
        BadScene{"light_keyframe_order",
                 "[[light]]\nposition = [0, 1, 0]\nintensity = [1, 1, 1]\n[[light.keyframe]]\ntime = 1.0\n"
                 "[[light.keyframe]]\ntime = 1.0\n",
                 14, "keyframe times must increase"},
        BadScene{"point_light_keyframe_direction",
                 "[[light]]\nposition = [0, 1, 0]\nintensity = [1, 1, 1]\n[[light.keyframe]]\ntime = 0.0\n"
                 "direction = [0, 0, 1]\n",
                 13, "unknown key 'direction'"},
        BadScene{"syntax", "x = [1, 2\n", 0, "TOML syntax error"}),
    [](const ::testing::TestParamInfo<BadScene>& param) { return std::string(param.param.name); });

// Radiometric values a 32-bit float cannot hold: every mode rendered them black without a word.
INSTANTIATE_TEST_SUITE_P(
    Unrepresentable, SceneLoaderErrors,
    ::testing::Values(
        BadScene{"huge_intensity", "[[light]]\nposition = [0, 1, 0]\nintensity = [1e39, 1, 1]\n", 10,
                 "intensity: value 1e+39 is beyond the largest 32-bit float"},
        BadScene{"tiny_intensity", "[[light]]\nposition = [0, 1, 0]\nintensity = [1, 1e-39, 1]\n", 10,
                 "intensity: value 1e-39 is below the smallest normal 32-bit float"},
        BadScene{"huge_emission", "[[mesh]]\nfile = \"quad.obj\"\nemission = [1, 1, 5e38]\n", 10,
                 "emission: value 5e+38 is beyond the largest 32-bit float"},
        BadScene{"huge_albedo", "[[material]]\nname = \"hot\"\nalbedo = [1e39, 0.5, 0.5]\n", 10,
                 "albedo: value 1e+39 is beyond the largest 32-bit float"},
        BadScene{"huge_env_radiance", "[environment]\nradiance = [1e40, 1, 1]\n", 9,
                 "radiance: value 1e+40 is beyond the largest 32-bit float"},
        BadScene{"huge_env_scale", "[environment]\nradiance = [1, 1, 1]\nscale = 1e39\n", 10,
                 "scale: value 1e+39 is beyond the largest 32-bit float"},
        BadScene{"env_radiance_times_scale", "[environment]\nradiance = [1e20, 1, 1]\nscale = 1e20\n", 10,
                 "the brightest environment radiance times scale: 1e+20 x 1e+20 = 1e+40 is beyond"},
        // cos(0.03 deg) is 2 float steps below 1: every mode rendered its lit area 32 % short.
        BadScene{"spot_too_narrow", "[[light]]\ntype = \"spot\"\nposition = [0, 1, 0]\nintensity = [1, 1, 1]\n"
                                    "direction = [0, -1, 0]\ncone_angle = 0.03\n",
                 13, "cone_angle 0.03 degrees: its cosine is 2 float steps (2^-24) below 1, so 32-bit floats render "
                     "its lit area up to 50 % off"},
        BadScene{"spot_black", "[[light]]\ntype = \"spot\"\nposition = [0, 1, 0]\nintensity = [1, 1, 1]\n"
                               "direction = [0, -1, 0]\ncone_angle = 0.01\n",
                 13, "up to 100 % off (black)"}),
    [](const ::testing::TestParamInfo<BadScene>& param) { return std::string(param.param.name); });

TEST(SceneLoader, EnvironmentMapTimesScaleMustBeAFloat) {
    BL_SKIP_WITHOUT_SHARED("data/envmap/classroom-sky.hdr");
    const std::string hdr = std::filesystem::absolute(sharedPath("data/envmap/classroom-sky.hdr")).string();
    const std::string ok = sceneWith("[environment]\nfile = \"" + hdr + "\"\nscale = 1e30\n", "env_ok.toml");
    EXPECT_EQ(loadError(ok), "");
    const std::string bad = sceneWith("[environment]\nfile = \"" + hdr + "\"\nscale = 3e38\n", "env_bad.toml");
    EXPECT_NE(loadError(bad).find(bad + ":10: environment.scale: the brightest environment radiance times scale"),
              std::string::npos)
        << loadError(bad);
}

TEST(SceneLoader, NarrowButResolvableSpotConesLoad) {
    for (const char* cone : {"0.07", "0.2", "1"}) { // 0.07: 12.5 steps, a warning only
        const std::string p = sceneWith(std::string("[[light]]\ntype = \"spot\"\nposition = [0, 1, 0]\n"
                                                    "intensity = [1, 1, 1]\ndirection = [0, -1, 0]\ncone_angle = ") +
                                            cone + "\n",
                                        "cone.toml");
        EXPECT_EQ(loadError(p), "") << cone;
    }
}

TEST(SceneLoader, MissingSceneFile) {
    EXPECT_NE(loadError("/no/such/scene.toml").find("/no/such/scene.toml: file not found"), std::string::npos);
}
