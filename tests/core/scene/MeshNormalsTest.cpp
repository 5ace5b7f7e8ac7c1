// Which normals a mesh is shaded with: a file without normals is shaded flat unless its [[mesh]]
// asks for generated ones (`normals = "smooth"`, `crease_angle`), as other renderers shade such
// files; `normals = "flat"` overrides the file's; bad values are errors naming file, line, value.
#include "scene/SceneLoader.h"
#include "support/SphereObj.h"
#include "support/TestFiles.h"

#include <gtest/gtest.h>

using namespace bl;
using bl::test::errorOf;
using bl::test::writeTempFile;

namespace {

// A scene of one mesh file `obj`; `keys` go into its [[mesh]] table, which starts on line 5.
std::string sceneOf(const std::string& name, const std::string& obj, const std::string& keys) {
    writeTempFile(name + ".obj", obj);
    return writeTempFile(name + ".toml", "[[material]]\nname = \"white\"\nalbedo = [0.5, 0.5, 0.5]\n\n"
                                         "[[mesh]]\nfile = \"" + name + ".obj\"\nmaterial = \"white\"\n" + keys);
}

glm::vec3 faceNormal(const Mesh& m, const glm::uvec3& t) {
    return glm::normalize(glm::cross(m.positions[t.y] - m.positions[t.x], m.positions[t.z] - m.positions[t.x]));
}

// Largest distance between a corner's normal and its face's normal over the mesh.
float largestDeviationFromFaces(const Mesh& m) {
    float worst = 0.0f;
    for (const glm::uvec3& t : m.triangles) {
        for (int k = 0; k < 3; ++k) worst = std::max(worst, glm::distance(m.normals[t[k]], faceNormal(m, t)));
    }
    return worst;
}

// 12 x 24 sphere: neighbouring faces meet at 15 degrees.
const std::string& sphere() {
    static const std::string obj = bl::test::sphereObj(12, 24, 1.0f, false);
    return obj;
}

} // namespace

TEST(MeshNormals, AFileWithoutNormalsIsShadedFlatByDefault) {
    Scene s = loadScene(sceneOf("default", sphere(), ""));
    ASSERT_EQ(s.meshes.size(), 1u);
    EXPECT_LT(largestDeviationFromFaces(s.meshes[0]), 1e-5f);
    for (const glm::uvec3& t : s.meshes[0].triangles) { // outward, as wound
        EXPECT_GT(glm::dot(faceNormal(s.meshes[0], t), s.meshes[0].positions[t.x]), 0.0f);
    }
}

TEST(MeshNormals, SmoothAsksForGeneratedNormalsWithACrease) {
    // Smooth across the 15-degree edges: the corner normals are the sphere's normals.
    Scene smooth = loadScene(sceneOf("smooth", sphere(), "normals = \"smooth\"\n"));
    const Mesh& m = smooth.meshes[0];
    EXPECT_GT(largestDeviationFromFaces(m), 0.1f);
    for (std::size_t v = 0; v < m.positions.size(); ++v) {
        EXPECT_GT(glm::dot(m.normals[v], glm::normalize(m.positions[v])), 0.995f);
    }
    // A crease below every angle between neighbours (2 degrees at the poles) keeps every edge: flat
    // again. Above the largest (15 degrees), smooth.
    Scene sharp = loadScene(sceneOf("sharp", sphere(), "normals = \"smooth\"\ncrease_angle = 0.5\n"));
    EXPECT_LT(largestDeviationFromFaces(sharp.meshes[0]), 1e-5f);
    Scene wide = loadScene(sceneOf("wide", sphere(), "normals = \"smooth\"\ncrease_angle = 20.0\n"));
    EXPECT_GT(largestDeviationFromFaces(wide.meshes[0]), 0.1f);
}

TEST(MeshNormals, FlatOverridesTheFilesNormalsAndFileKeepsThem) {
    // A triangle facing +y whose file normals lean 45 degrees toward +x.
    const std::string obj = "v 0 0 0\nv 0 0 1\nv 1 0 0\nvn 1 1 0\nvn 1 1 0\nvn 1 1 0\nf 1//1 2//2 3//3\n";
    const glm::vec3 leaning = glm::normalize(glm::vec3(1, 1, 0));
    for (const char* keys : {"", "normals = \"file\"\n"}) {
        Scene s = loadScene(sceneOf("file", obj, keys));
        for (const glm::vec3& n : s.meshes[0].normals) EXPECT_LT(glm::distance(n, leaning), 1e-6f) << keys;
    }
    Scene flat = loadScene(sceneOf("flat", obj, "normals = \"flat\"\n"));
    for (const glm::vec3& n : flat.meshes[0].normals) EXPECT_LT(glm::distance(n, glm::vec3(0, 1, 0)), 1e-6f);
}

TEST(MeshNormals, BadValuesAreErrorsNamingFileLineAndValue) {
    struct Bad {
        const char* name;
        const char* keys;
        int line;
        const char* expected;
    };
    for (const Bad& bad : {Bad{"typo", "normals = \"smoth\"\n", 8, "got \"smoth\""},
                           Bad{"type", "normals = 1\n", 8, "normals"},
                           Bad{"zero_crease", "normals = \"smooth\"\ncrease_angle = 0\n", 9, "value 0 outside (0, 180]"},
                           Bad{"wide_crease", "normals = \"smooth\"\ncrease_angle = 200\n", 9, "value 200 outside"},
                           Bad{"crease_flat", "normals = \"flat\"\ncrease_angle = 30\n", 9, "only with normals = \"smooth\""},
                           Bad{"crease_alone", "crease_angle = 30\n", 8, "only with normals = \"smooth\""}}) {
        const std::string path = sceneOf(bad.name, sphere(), bad.keys);
        const std::string e = errorOf([&] { loadScene(path); });
        EXPECT_NE(e.find(path + ":" + std::to_string(bad.line) + ":"), std::string::npos) << bad.name << ": " << e;
        EXPECT_NE(e.find(bad.expected), std::string::npos) << bad.name << ": " << e;
    }
}
