// glTF files written by real exporters, from Debian's assimp-testmodels (the Khronos sample models
// BoxTextured, 2CylinderEngine and Cameras, written by COLLADA2GLTF and others, and the assimp test
// suite's broken files), and a file written by assimp's own glTF 2.0 exporter (assimp-utils): each
// loads as the scene its JSON describes, or is refused with an error naming what is wrong.
// Skipped, naming the package, where those are not installed.
#include "scene/SceneLoader.h"
#include "support/TestFiles.h"

#include <gtest/gtest.h>

#include <cmath>
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>

using namespace bl;
using bl::test::errorOf;

namespace {

const std::string kModels = "/usr/share/assimp/models/glTF2/";

#define BL_SKIP_WITHOUT_MODELS()                                                                               \
    if (!std::filesystem::is_directory(kModels)) GTEST_SKIP() << kModels << " missing (Debian: assimp-testmodels)"

std::size_t triangles(const Scene& s) {
    std::size_t n = 0;
    for (const Mesh& m : s.meshes) n += m.triangles.size();
    return n;
}

} // namespace

// The same box as .gltf with a .bin, as .glb, and with its buffers embedded as data URIs: one scene.
TEST(GltfSampleModels, BoxTexturedReadsTheSameInEveryContainer) {
    BL_SKIP_WITHOUT_MODELS();
    const Scene gltf = loadScene(kModels + "BoxTextured-glTF/BoxTextured.gltf");
    for (const char* other : {"BoxTextured-glTF-Binary/BoxTextured.glb", "BoxTextured-glTF-Embedded/BoxTextured.gltf"}) {
        const Scene s = loadScene(kModels + other);
        ASSERT_EQ(s.meshes.size(), gltf.meshes.size()) << other;
        EXPECT_EQ(s.meshes[0].positions, gltf.meshes[0].positions) << other;
        EXPECT_EQ(s.meshes[0].triangles, gltf.meshes[0].triangles) << other;
        EXPECT_EQ(s.meshes[0].uvs, gltf.meshes[0].uvs) << other;
        ASSERT_EQ(s.textures.size(), 1u) << other;
        EXPECT_EQ(s.textures[0].image.texels, gltf.textures[0].image.texels) << other;
    }
    EXPECT_EQ(triangles(gltf), 12u);
    EXPECT_GE(gltf.materials[gltf.meshes[0].material].albedoTexture, 0) << "base colour texture as albedo";
    // The file brings no light: like a bare mesh, a headlight and a white sky are added.
    EXPECT_EQ(gltf.lights.size(), 1u);
    EXPECT_TRUE(gltf.environment.present);
}

// Scene::inputFiles: a .gltf with its .bin and image lists all three (percent-encoded uris
// decoded, as tinygltf reads them); the embedded and binary containers are one file each. The
// texture's path is its file beside the glTF, never a name relative to the working directory.
TEST(GltfSampleModels, InputFilesNameTheBuffersAndImages) {
    BL_SKIP_WITHOUT_MODELS();
    const Scene gltf = loadScene(kModels + "BoxTextured-glTF/BoxTextured.gltf");
    ASSERT_EQ(gltf.textures.size(), 1u);
    EXPECT_EQ(gltf.textures[0].path, kModels + "BoxTextured-glTF/CesiumLogoFlat.png");
    std::vector<std::string> names;
    for (const std::string& f : gltf.inputFiles) names.push_back(std::filesystem::path(f).filename().string());
    std::sort(names.begin(), names.end());
    EXPECT_EQ(names, (std::vector<std::string>{"BoxTextured.gltf", "BoxTextured0.bin", "CesiumLogoFlat.png"}));
    for (const char* one : {"BoxTextured-glTF-Binary/BoxTextured.glb", "BoxTextured-glTF-Embedded/BoxTextured.gltf"}) {
        EXPECT_EQ(loadScene(kModels + one).inputFiles, std::vector<std::string>{kModels + one}) << one;
    }
    // The same box with spaces in its file names, written %20 in the uris.
    const std::string dir = bl::test::tempDir();
    std::filesystem::copy_file(kModels + "BoxTextured-glTF/BoxTextured0.bin", dir + "/Box Textured0.bin",
                               std::filesystem::copy_options::overwrite_existing);
    std::filesystem::copy_file(kModels + "BoxTextured-glTF/CesiumLogoFlat.png", dir + "/Cesium Logo.png",
                               std::filesystem::copy_options::overwrite_existing);
    std::ifstream in(kModels + "BoxTextured-glTF/BoxTextured.gltf");
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    for (const auto& [from, to] : {std::pair<std::string, std::string>{"BoxTextured0.bin", "Box%20Textured0.bin"},
                                   {"CesiumLogoFlat.png", "Cesium%20Logo.png"}}) {
        const std::size_t at = text.find(from);
        ASSERT_NE(at, std::string::npos) << from;
        text.replace(at, from.size(), to);
    }
    const Scene spaced = loadScene(bl::test::writeTempFile("spaced.gltf", text));
    EXPECT_EQ(spaced.inputFiles, (std::vector<std::string>{dir + "/Box Textured0.bin", dir + "/Cesium Logo.png",
                                                          dir + "/spaced.gltf"}));
}

// A node hierarchy of 115 meshes with instancing (COLLADA2GLTF): every instance placed, the file's
// own zero-area triangles dropped (10419 in its meshes, counted independently in their index
// data; 11160 once instanced), nothing else.
TEST(GltfSampleModels, TwoCylinderEngineHierarchyLoads) {
    BL_SKIP_WITHOUT_MODELS();
    const Scene s = loadScene(kModels + "2CylinderEngine-glTF-Binary/2CylinderEngine.glb");
    EXPECT_EQ(triangles(s), 121496u - 11160u);
    const Bounds b = s.bounds();
    for (int a = 0; a < 3; ++a) {
        EXPECT_TRUE(std::isfinite(b.lo[a]) && std::isfinite(b.hi[a]));
        EXPECT_GT(b.hi[a] - b.lo[a], 0.0f);
    }
}

// The first camera (perspective, yfov 0.7 rad at (0.5, 0.5, 3)) is the scene's camera.
TEST(GltfSampleModels, CamerasFileSetsThePerspectiveCamera) {
    BL_SKIP_WITHOUT_MODELS();
    const Scene s = loadScene(kModels + "cameras/Cameras.gltf");
    EXPECT_NEAR(s.camera.fovDegrees, 0.7 * 180.0 / M_PI, 1e-3);
    EXPECT_NEAR(s.camera.pose.position.x, 0.5f, 1e-6f);
    EXPECT_NEAR(s.camera.pose.position.z, 3.0f, 1e-6f);
}

// The assimp suite's broken files: refused, each with the reason.
TEST(GltfSampleModels, BrokenFilesAreRefusedWithTheReason) {
    BL_SKIP_WITHOUT_MODELS();
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb", "POSITION: element 0 is -inf (not finite)"},
        {"IndexOutOfRange/IndexOutOfRange.gltf", "index 255 beyond its 24 vertices"},
        {"MissingBin/BoxTextured.gltf", "BoxTextured0.bin"},
        {"draco/2CylinderEngine.gltf", "requires extension KHR_draco_mesh_compression, which is not supported"},
        {"RecursiveNodes/RecursiveNodes.gltf", "the node hierarchy has a cycle"},
        {"glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_00.gltf", "mode 0 is not supported"},
    };
    for (const auto& [file, reason] : cases) {
        const std::string error = errorOf([&] { loadScene(kModels + file); });
        EXPECT_NE(error.find(kModels + file), std::string::npos) << file << ": " << error;
        EXPECT_NE(error.find(reason), std::string::npos) << file << ": " << error;
    }
}

// assimp's glTF 2.0 exporter (a real exporter, not ours) writes the Cornell box's tall block; the
// import holds the OBJ's triangles (same corners, same count) and its MTL albedo (Kd 0.25 0.5 0.75).
TEST(GltfSampleModels, AssimpExportOfAnObjReadsAsTheObj) {
    if (std::system("command -v assimp >/dev/null 2>&1") != 0) GTEST_SKIP() << "assimp missing (Debian: assimp-utils)";
    // The tall block with an MTL material (assimp's exporter writes Kd as the base colour factor).
    std::ifstream in(bl::test::sourcePath("data/cornell-box/meshes/tallblock.obj"));
    const std::string block((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    ASSERT_FALSE(block.empty());
    bl::test::writeTempFile("block.mtl", "newmtl paint\nKd 0.25 0.5 0.75\n");
    const std::string obj = bl::test::writeTempFile("block.obj", "mtllib block.mtl\nusemtl paint\n" + block);
    for (const char* format : {"gltf2", "glb2"}) {
        const std::string out = bl::test::tempDir() + "/tallblock." + (std::string(format) == "gltf2" ? "gltf" : "glb");
        const std::string command = "assimp export '" + obj + "' '" + out + "' -f" + format + " >/dev/null 2>&1";
        ASSERT_EQ(std::system(command.c_str()), 0) << command;
        const Scene fromObj = loadScene(obj), fromGltf = loadScene(out);
        ASSERT_EQ(triangles(fromGltf), triangles(fromObj)) << format;
        const Bounds a = fromObj.bounds(), b = fromGltf.bounds();
        for (int k = 0; k < 3; ++k) {
            EXPECT_NEAR(a.lo[k], b.lo[k], 1e-3f) << format;
            EXPECT_NEAR(a.hi[k], b.hi[k], 1e-3f) << format;
        }
        std::vector<glm::vec3> cornersObj, cornersGltf;
        const auto corners = [](const Scene& s, std::vector<glm::vec3>& into) {
            for (const Mesh& m : s.meshes) {
                for (const glm::uvec3& t : m.triangles) {
                    for (int c = 0; c < 3; ++c) into.push_back(m.positions[t[c]]);
                }
            }
        };
        corners(fromObj, cornersObj);
        corners(fromGltf, cornersGltf);
        auto less = [](const glm::vec3& p, const glm::vec3& q) {
            return p.x != q.x ? p.x < q.x : p.y != q.y ? p.y < q.y : p.z < q.z;
        };
        std::sort(cornersObj.begin(), cornersObj.end(), less);
        std::sort(cornersGltf.begin(), cornersGltf.end(), less);
        EXPECT_EQ(cornersObj, cornersGltf) << format;
        EXPECT_EQ(fromGltf.materials[fromGltf.meshes[0].material].albedo, fromObj.materials[fromObj.meshes[0].material].albedo)
            << format;
        EXPECT_EQ(fromObj.materials[fromObj.meshes[0].material].albedo, glm::vec3(0.25f, 0.5f, 0.75f));
    }
}
