// The GLSL traversal helpers (shaders/bundle/Traversal.glsl), dispatched on real bundles and
// checked against Embree's sorted hits along the same rays: depth-order walks forwards and
// backwards on unsorted lists (blBundleNext / blBundlePrevious, O(n) per step) and on lists the
// sort pass ordered (blBundleSortedNext / blBundleSortedPrevious, O(1)), and nearest-fragment
// queries in both directions (blBundleNearest, blBundleSortedNearest).
#include "bundle/BundleFrame.h"
#include "bundle/BundlePool.h"
#include "bundle/DirectionSampler.h"
#include "reference/EmbreeScene.h"
#include "scene/SceneLoader.h"
#include "support/TestFiles.h"
#include "support/VulkanTest.h"
#include "vk/Commands.h"

#include <cstdio>
#include <random>
#include <tests/bundle_traversal.comp.spv.h>

using namespace bl;

namespace {

constexpr std::uint32_t kResolution = 64;
constexpr std::uint32_t kMaxWalk = 64; // nodes per pixel and direction the walk reports
constexpr std::uint32_t kGroupSize = 64;

struct TraversalQuery {
    std::uint32_t pixel;
    float depth;
    float dir;
    float ownEpsilon;
};

struct TraversalPush {
    shader::BundlePoolView pool;
    glm::uvec2 queries;
    glm::uvec2 results;
    std::uint32_t slot;
    std::uint32_t count;
    std::uint32_t maxWalk;
    std::uint32_t walk;
};
static_assert(sizeof(TraversalPush) == 96, "push block of bundle_traversal.comp.glsl");

constexpr VkBufferUsageFlags kUsage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                                      VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT |
                                      VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;

class BundleTraversal : public bl::test::VulkanTest {
protected:
    void SetUp() override {
        VulkanTest::SetUp();
        layout = vk::makePipelineLayout(ctx().device(), {}, sizeof(TraversalPush), VK_SHADER_STAGE_COMPUTE_BIT);
        pipeline = vk::makeComputePipeline(ctx().device(), kSpv_tests_bundle_traversal_comp, layout.get());
    }

    std::vector<std::uint32_t> run(const BundlePool& pool, bool sorted, bool walk, const std::vector<TraversalQuery>& qs) {
        const std::uint32_t count = walk ? kResolution * kResolution : static_cast<std::uint32_t>(qs.size());
        const std::size_t outputs = walk ? std::size_t(count) * 2 * kMaxWalk : 2 * qs.size();
        vk::Buffer queries(ctx(), std::max<std::size_t>(qs.size(), 1) * sizeof(TraversalQuery), kUsage,
                           vk::MemoryUse::Device);
        if (!qs.empty()) queries.upload(ctx(), qs.data(), qs.size() * sizeof(TraversalQuery));
        vk::Buffer results(ctx(), outputs * sizeof(std::uint32_t), kUsage, vk::MemoryUse::Device);
        TraversalPush push{};
        push.pool = pool.view();
        push.pool.sorted = sorted ? 1u : 0u;
        push.queries = splitAddress(deviceAddress(ctx(), queries));
        push.results = splitAddress(deviceAddress(ctx(), results));
        push.count = count;
        push.maxWalk = kMaxWalk;
        push.walk = walk ? 1u : 0u;
        ctx().submitAndWait([&](VkCommandBuffer cmd) {
            vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.get());
            vkCmdPushConstants(cmd, layout.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
            vkCmdDispatch(cmd, vk::groupCount(count, kGroupSize), 1, 1);
            vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_2_TRANSFER_BIT);
        });
        std::vector<std::uint32_t> out(outputs);
        results.download(ctx(), out.data(), out.size() * sizeof(std::uint32_t));
        return out;
    }

    // Walks every pixel forwards and backwards and queries between consecutive hits; every
    // answer is compared with Embree's sorted hits by depth.
    void check(const std::string& path, bool sorted) {
        SCOPED_TRACE(path + (sorted ? " (sorted)" : " (unsorted)"));
        Scene scene = loadScene(path);
        gpu::GpuScene gpuScene(ctx(), scene);
        EmbreeScene embree(scene, 0.0);
        const Bounds b = scene.bounds();
        BundlePoolOptions options;
        options.slotPixels = kResolution * kResolution;
        options.sortable = true;
        BundlePool pool(ctx(), gpuScene, options);
        DirectionSampler sampler(DirectionSequence::Random, 2024);
        const BundleDirection d = sampler.sample(3);
        const shader::BundleFrame frame = bundleFrameForSphere(d.omega, d.rotation, b.center(), b.radius(), kResolution);
        ctx().submitAndWait([&](VkCommandBuffer cmd) {
            pool.recordReset(cmd);
            pool.recordBuild(cmd, 0, frame, BundleGeometry::triangles(0.0));
            if (sorted) pool.recordSort(cmd, 0);
        });
        const BundlePoolStatus status = pool.status();
        ASSERT_FALSE(status.overflowed());
        const auto nodes = pool.readNodes(status.requested);
        const float tolerance = 1e-5f * 2.0f * b.radius();

        // Embree's hits per pixel, and queries halfway between consecutive ones (and beyond the
        // ends), each expecting the hit on its side.
        std::vector<std::vector<float>> hits(kResolution * kResolution);
        std::vector<TraversalQuery> queries;
        std::vector<float> expected;
        for (std::uint32_t j = 0; j < kResolution; ++j) {
            for (std::uint32_t i = 0; i < kResolution; ++i) {
                const std::uint32_t p = j * kResolution + i;
                const glm::vec3 o = frame.origin + (i + 0.5f) * frame.pixelSize * frame.axisX +
                                    (j + 0.5f) * frame.pixelSize * frame.axisY;
                for (const auto& h : embree.allHits(o + frame.depthNear * frame.direction, frame.direction,
                                                    frame.depthFar - frame.depthNear)) {
                    hits[p].push_back(frame.depthNear + h.t);
                }
                const auto& t = hits[p];
                if (t.empty()) continue;
                queries.push_back({p, t.front() - 4.0f * tolerance, 1.0f, frame.depthEpsilon});
                expected.push_back(t.front());
                queries.push_back({p, t.back() + 4.0f * tolerance, -1.0f, frame.depthEpsilon});
                expected.push_back(t.back());
                for (std::size_t k = 0; k + 1 < t.size(); ++k) {
                    if (t[k + 1] - t[k] < 8.0f * tolerance) continue; // coincident surfaces: either is right
                    const float mid = 0.5f * (t[k] + t[k + 1]);
                    queries.push_back({p, mid, 1.0f, frame.depthEpsilon});
                    expected.push_back(t[k + 1]);
                    queries.push_back({p, mid, -1.0f, frame.depthEpsilon});
                    expected.push_back(t[k]);
                }
            }
        }

        const auto walks = run(pool, sorted, true, {});
        std::size_t pixels = 0, agree = 0;
        for (std::uint32_t p = 0; p < kResolution * kResolution; ++p) {
            if (hits[p].empty() || hits[p].size() > kMaxWalk) continue;
            ++pixels;
            const std::uint32_t* forward = &walks[std::size_t(p) * 2 * kMaxWalk];
            const std::uint32_t* backward = forward + kMaxWalk;
            bool same = true;
            const std::size_t n = hits[p].size();
            for (std::size_t k = 0; k < kMaxWalk && same; ++k) {
                if (k >= n) {
                    same = forward[k] == shader::kBundleNil && backward[k] == shader::kBundleNil;
                    break;
                }
                same = forward[k] != shader::kBundleNil && backward[n - 1 - k] == forward[k] &&
                       std::abs(nodes.at(forward[k]).depth - hits[p][k]) <= tolerance;
            }
            agree += same;
        }
        const auto answers = run(pool, sorted, false, queries);
        std::size_t wrong = 0, wrongSorted = 0;
        for (std::size_t q = 0; q < queries.size(); ++q) {
            auto off = [&](std::uint32_t node) {
                return node == shader::kBundleNil || std::abs(nodes.at(node).depth - expected[q]) > tolerance;
            };
            wrong += off(answers[2 * q]);
            if (sorted) wrongSorted += off(answers[2 * q + 1]);
        }
        std::printf("%s: walks agree with Embree in %zu of %zu pixels; %zu of %zu nearest queries off (sorted: %zu)\n",
                    sorted ? "sorted" : "unsorted", agree, pixels, wrong, queries.size(), wrongSorted);
        EXPECT_GT(pixels, kResolution * kResolution / 4);
        EXPECT_GT(queries.size(), pixels * 2);
        // Pixel centres on a shared edge may go to either triangle (rasterizer tie rule against
        // Embree's watertight test): those are the allowed 0.5%.
        EXPECT_GE(double(agree), 0.995 * double(pixels));
        EXPECT_LE(double(wrong), 0.005 * double(queries.size()));
        EXPECT_LE(double(wrongSorted), 0.005 * double(queries.size()));
    }

    vk::PipelineLayout layout;
    vk::Pipeline pipeline;
};

} // namespace

TEST_F(BundleTraversal, UnsortedCornellBox) { check(bl::test::sourcePath("data/cornell-box/cornell.toml"), false); }
TEST_F(BundleTraversal, SortedCornellBox) { check(bl::test::sourcePath("data/cornell-box/cornell.toml"), true); }
TEST_F(BundleTraversal, SortedSponza) {
    BL_SKIP_WITHOUT_SCENE_FILES("data/external/sponza-point.toml");
    check(bl::test::sourcePath("data/external/sponza-point.toml"), true);
}
