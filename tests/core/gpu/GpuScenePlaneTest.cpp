// Issue 10, defect 5 (host part): GpuScene's per-triangle planes, used for exact bundle depths,
// never hold NaN or Inf. Slivers that mesh cleanup keeps get their exact unit-normal plane, also
// near float's range limits; triangles without a plane get kNoPlane (zero normal) on the GPU too.
#include "GpuSceneReadback.h"
#include "gpu/GpuScene.h"
#include "scene/MeshCleanup.h"
#include "support/VulkanTest.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace bl;

namespace {

bool finite(const glm::vec4& p) {
    return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z) && std::isfinite(p.w);
}

// Slivers and tiny or huge triangles, each of which cleanupMesh keeps.
Mesh sliverMesh() {
    Mesh m;
    m.name = "slivers";
    auto add = [&](glm::vec3 a, glm::vec3 b, glm::vec3 c) {
        const std::uint32_t first = std::uint32_t(m.positions.size());
        m.positions.insert(m.positions.end(), {a, b, c});
        m.triangles.emplace_back(first, first + 1, first + 2);
    };
    add({0, 0, 0}, {1, 0, 0}, {0.5f, 1e-5f, 0});                    // a needle at unit scale
    add({1e4f, 1e4f, 1e4f}, {1e4f + 1, 1e4f, 1e4f}, {1e4f, 1e4f + 1, 1e4f + 1e-3f}); // far from the origin
    add({0, 0, 0}, {1e-11f, 0, 0}, {0, 1e-11f, 0});                 // |cross|^2 is subnormal in float
    add({0, 0, 0}, {1e19f, 0, 0}, {0, 1e19f, 1});                    // |cross|^2 overflows float
    add({0, 0, 0}, {3e18f, 0, 0}, {1.5e18f, 3e12f, 0});              // a huge needle
    return m;
}

void expectExactPlane(const glm::vec4& plane, const glm::vec3 corners[3]) {
    ASSERT_TRUE(finite(plane)) << plane.x << " " << plane.y << " " << plane.z << " " << plane.w;
    EXPECT_NEAR(glm::length(glm::vec3(plane)), 1.0f, 1e-6f);
    // Every corner on the plane, to float precision of the coordinates.
    float scale = 0.0f;
    for (int k = 0; k < 3; ++k) scale = std::max({scale, std::abs(corners[k].x), std::abs(corners[k].y), std::abs(corners[k].z)});
    constexpr double kRelativeTolerance = 1e-6;
    for (int k = 0; k < 3; ++k) {
        const double distance = glm::dot(glm::dvec3(plane), glm::dvec3(corners[k])) - double(plane.w);
        EXPECT_LE(std::abs(distance), kRelativeTolerance * scale) << "corner " << k;
    }
}

} // namespace

TEST(TrianglePlane, SliversKeptByCleanupGetTheirExactPlane) {
    Mesh m = sliverMesh();
    const std::size_t triangles = m.triangles.size();
    const CleanupStats stats = cleanupMesh(m);
    ASSERT_EQ(stats.degenerateTriangles, 0u);
    ASSERT_EQ(m.triangles.size(), triangles);
    for (std::size_t i = 0; i < triangles; ++i) {
        SCOPED_TRACE("triangle " + std::to_string(i));
        const glm::vec3 corners[3] = {m.positions[m.triangles[i].x], m.positions[m.triangles[i].y],
                                      m.positions[m.triangles[i].z]};
        expectExactPlane(gpu::trianglePlane(corners[0], corners[1], corners[2]), corners);
    }
}

TEST(TrianglePlane, TrianglesWithoutAPlaneGetZeroNormal) {
    const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
    const glm::vec3 cases[][3] = {
        {{0, 0, 0}, {1, 1, 1}, {2, 2, 2}},       // collinear
        {{1, 2, 3}, {1, 2, 3}, {4, 5, 7}},       // two corners coincide
        {{5, 5, 5}, {5, 5, 5}, {5, 5, 5}},       // a point
        {{0, 0, 0}, {inf, 0, 0}, {0, 1, 0}},     // non-finite corner
        {{0, 0, 0}, {1, 0, 0}, {0, nan, 0}},
    };
    for (const auto& c : cases) {
        const glm::vec4 plane = gpu::trianglePlane(c[0], c[1], c[2]);
        EXPECT_TRUE(finite(plane));
        EXPECT_EQ(plane, gpu::kNoPlane);
    }
}

class GpuScenePlanes : public bl::test::VulkanTest {};

TEST_F(GpuScenePlanes, UploadedPlanesAreFiniteAndDegenerateOnesRecognisable) {
    Scene scene;
    scene.materials.push_back(Material{});
    Mesh slivers = sliverMesh();
    cleanupMesh(slivers);
    // A collinear triangle in a scene built in code (no cleanup): the plane buffer's worst case.
    Mesh collinear;
    collinear.positions = {{0, 0, 0}, {1, 1, 1}, {2, 2, 2}};
    collinear.normals = {{0, 1, 0}, {0, 1, 0}, {0, 1, 0}};
    collinear.triangles = {{0, 1, 2}};
    scene.meshes = {slivers, collinear};
    gpu::GpuScene gpuScene(ctx(), scene);
    ASSERT_EQ(gpuScene.triangleCount(), scene.triangleCount());
    const std::vector<glm::vec4> planes =
        bl::test::readBack<glm::vec4>(ctx(), gpuScene.planeBuffer(), scene.triangleCount());
    for (std::size_t i = 0; i < slivers.triangles.size(); ++i) {
        SCOPED_TRACE("triangle " + std::to_string(i));
        const glm::vec3 corners[3] = {slivers.positions[slivers.triangles[i].x], slivers.positions[slivers.triangles[i].y],
                                      slivers.positions[slivers.triangles[i].z]};
        expectExactPlane(planes[i], corners);
    }
    EXPECT_EQ(planes.back(), gpu::kNoPlane);
}
