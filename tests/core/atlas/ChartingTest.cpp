// Charting: region growing partitions every mesh's faces into charts within the normal cone, and
// the seam-length cost gives charts with shorter seams than the normal cone alone.
#include "atlas/Charting.h"
#include "scene/SceneLoader.h"
#include "support/TestFiles.h"

#include <gtest/gtest.h>

#include <map>

using namespace bl;
using namespace bl::atlas;

namespace {

const Mesh& scannedBunny() {
    static const Scene scene = loadScene(bl::test::sharedPath("data/bunny/stanford/bun_zipper_res2.ply"));
    return scene.meshes.at(0);
}

struct Seams {
    double length = 0.0;      // edges whose two faces lie in different charts
    double compactness = 0.0; // area-weighted isoperimetric quotient 4 pi A / P^2 of the charts (1: a disc)
};

Seams measureSeams(const Mesh& mesh, const std::vector<ChartFaces>& charts) {
    std::uint32_t distinct = 0;
    const std::vector<std::uint32_t> welded = weldVertices(mesh, distinct);
    std::vector<int> chartOf(mesh.triangles.size(), -1);
    std::vector<double> area(charts.size(), 0.0), perimeter(charts.size(), 0.0);
    for (std::size_t c = 0; c < charts.size(); ++c) {
        for (std::uint32_t f : charts[c].faces) {
            chartOf[f] = int(c);
            const glm::uvec3& t = mesh.triangles[f];
            area[c] += 0.5 * glm::length(glm::cross(mesh.positions[t.y] - mesh.positions[t.x], mesh.positions[t.z] - mesh.positions[t.x]));
        }
    }
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<int>> edgeCharts;
    std::map<std::pair<std::uint32_t, std::uint32_t>, float> edgeLength;
    for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
        const glm::uvec3& t = mesh.triangles[f];
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t a = welded[t[k]], b = welded[t[(k + 1) % 3]];
            const auto key = std::make_pair(std::min(a, b), std::max(a, b));
            edgeCharts[key].push_back(chartOf[f]);
            edgeLength[key] = glm::distance(mesh.positions[t[k]], mesh.positions[t[(k + 1) % 3]]);
        }
    }
    Seams s;
    for (const auto& [edge, owners] : edgeCharts) {
        if (owners.size() == 2 && owners[0] == owners[1]) continue;
        if (owners.size() == 2) s.length += edgeLength[edge];
        for (int c : owners) perimeter[std::size_t(c)] += edgeLength[edge];
    }
    double total = 0.0;
    for (std::size_t c = 0; c < charts.size(); ++c) {
        total += area[c];
        if (perimeter[c] > 0.0) s.compactness += area[c] * 4.0 * M_PI * area[c] / (perimeter[c] * perimeter[c]);
    }
    s.compactness /= total;
    return s;
}

} // namespace

TEST(Charting, EveryFaceInExactlyOneChartWithinTheCone) {
    BL_SKIP_WITHOUT_SHARED("data/bunny/stanford/bun_zipper_res2.ply");
    const Mesh& mesh = scannedBunny();
    for (float seamWeight : {0.0f, 1.0f, 2.0f, 5.0f}) {
        ChartingStats stats;
        const ChartingOptions options{30.0f, seamWeight};
        const std::vector<ChartFaces> charts = growCharts(mesh, 0, options, stats);
        std::vector<int> seen(mesh.triangles.size(), 0);
        for (const ChartFaces& c : charts) {
            ASSERT_FALSE(c.faces.empty()) << "seam weight " << seamWeight;
            glm::vec3 axis(0.0f);
            for (std::uint32_t f : c.faces) {
                ++seen[f];
                const glm::uvec3& t = mesh.triangles[f];
                axis += glm::cross(mesh.positions[t.y] - mesh.positions[t.x], mesh.positions[t.z] - mesh.positions[t.x]);
            }
            // The cone holds against the chart's final normal up to the drift of its growth.
            axis = glm::normalize(axis);
            for (std::uint32_t f : c.faces) {
                const glm::uvec3& t = mesh.triangles[f];
                const glm::vec3 n = glm::normalize(
                    glm::cross(mesh.positions[t.y] - mesh.positions[t.x], mesh.positions[t.z] - mesh.positions[t.x]));
                if (c.faces.size() > 1) {
                    EXPECT_GT(glm::dot(n, axis), std::cos(glm::radians(2.0f * options.coneDegrees)));
                }
            }
        }
        for (std::size_t f = 0; f < seen.size(); ++f) ASSERT_EQ(seen[f], 1) << "face " << f << ", seam weight " << seamWeight;
    }
}

TEST(Charting, SeamCostGivesRounderChartsWithShorterSeams) {
    // Measured on this scan (cone 45): seams 7.56 -> 6.99, compactness 0.166 -> 0.307.
    BL_SKIP_WITHOUT_SHARED("data/bunny/stanford/bun_zipper_res2.ply");
    const Mesh& mesh = scannedBunny();
    ChartingStats stats;
    const Seams coneOnly = measureSeams(mesh, growCharts(mesh, 0, ChartingOptions{45.0f, 0.0f}, stats));
    const Seams withSeams = measureSeams(mesh, growCharts(mesh, 0, ChartingOptions{45.0f, 1.0f}, stats));
    EXPECT_LT(withSeams.length, 0.97 * coneOnly.length);
    EXPECT_GT(withSeams.compactness, 1.5 * coneOnly.compactness);
}
