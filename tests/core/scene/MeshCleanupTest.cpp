#include "scene/MeshCleanup.h"

#include <gtest/gtest.h>

using namespace bl;

TEST(MeshCleanup, DropsDegenerateAndDuplicateTriangles) {
    Mesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 0, 0}, {0, 0, 0}};
    m.triangles = {{0, 1, 2},  // kept
                   {1, 2, 0},  // duplicate (same positions, rotated)
                   {2, 1, 4},  // duplicate via a coincident vertex (4 == 0 in position)
                   {0, 1, 3},  // collinear: zero area
                   {0, 0, 2}}; // repeated index
    CleanupStats s = cleanupMesh(m);
    EXPECT_EQ(m.triangles.size(), 1u);
    EXPECT_EQ(s.duplicateTriangles, 2u);
    EXPECT_EQ(s.degenerateTriangles, 2u);
    EXPECT_TRUE(s.generatedNormals);
}

TEST(MeshCleanup, GeneratedNormalsKeepCreasesAndSmoothCurves) {
    const NormalOptions smooth{NormalSource::Smooth, 45.0f};
    // Two faces of a box meeting at 90 degrees: flat normals on each side of the crease.
    Mesh box;
    box.positions = {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}, {0, 1, 0}, {0, 1, 1}};
    box.triangles = {{0, 3, 2}, {0, 2, 1}, {0, 4, 5}, {0, 5, 3}};
    cleanupMesh(box, smooth);
    for (std::size_t t = 0; t < box.triangles.size(); ++t) {
        glm::vec3 n = box.normals[box.triangles[t].x];
        for (int k = 1; k < 3; ++k) {
            EXPECT_LT(glm::distance(box.normals[box.triangles[t][k]], n), 1e-6f);
        }
    }
    // A shallow fold (10 degrees) is smoothed: the shared edge's normal is the average.
    Mesh fold;
    float s = std::sin(glm::radians(10.0f)), c = std::cos(glm::radians(10.0f));
    fold.positions = {{0, 0, 0}, {0, 0, 1}, {-1, 0, 0}, {c, s, 0}};
    fold.triangles = {{0, 1, 2}, {0, 3, 1}};
    Mesh flatFold = fold;
    cleanupMesh(fold, smooth);
    // The faces' normals are 10 degrees apart and the faces equal in area: 5 degrees from each.
    std::size_t shared = fold.triangles[0].x;
    EXPECT_NEAR(glm::dot(fold.normals[shared], glm::vec3(0, -1, 0)), std::cos(glm::radians(5.0f)), 1e-4f);
    EXPECT_EQ(fold.normals[fold.triangles[0].x], fold.normals[fold.triangles[1].x]); // one vertex, shared
    // By default (no normals in the file) each face keeps its own normal at the shared edge.
    CleanupStats stats = cleanupMesh(flatFold);
    EXPECT_TRUE(stats.generatedNormals);
    for (const glm::uvec3& t : flatFold.triangles) {
        const glm::vec3 face = glm::normalize(glm::cross(flatFold.positions[t.y] - flatFold.positions[t.x],
                                                         flatFold.positions[t.z] - flatFold.positions[t.x]));
        for (int k = 0; k < 3; ++k) EXPECT_LT(glm::distance(flatFold.normals[t[k]], face), 1e-6f);
    }
}

TEST(MeshCleanup, RepairsBrokenNormals) {
    Mesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 0, 1}};
    m.normals = {{0, 0, 0}, {0, 2, 0}, {0, 1, 0}};
    m.triangles = {{0, 2, 1}};
    CleanupStats s = cleanupMesh(m);
    EXPECT_EQ(s.repairedNormals, 1u);
    for (const glm::vec3& n : m.normals) {
        EXPECT_NEAR(glm::length(n), 1.0f, 1e-6f);
    }
}
