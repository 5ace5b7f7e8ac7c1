// The bundle pool: K >= 64 bundles resident at once, recorded into one command buffer, each exact
// against Embree's all-hits along the same parallel rays (the independent check) on a sample of
// pixels; the sort pass against Embree's sorted hits, with O(1) neighbours both ways; the hit
// payload (triangle, barycentrics, material, UV, normal) against the scene; point splats cut to
// discs; and the overflow contract (exact 64-bit request count, nothing out of range stored).
#include "base/Error.h"
#include "bundle/BundleFrame.h"
#include "bundle/BundlePool.h"
#include "bundle/DirectionSampler.h"
#include "reference/EmbreeScene.h"
#include "scene/SceneLoader.h"
#include "support/AnalyticScenes.h"
#include "support/TestFiles.h"
#include "support/VulkanTest.h"
#include "vk/Commands.h"

#include <shared/Octahedral.h>

#include <algorithm>
#include <cstdio>
#include <random>

using namespace bl;

namespace {

constexpr std::uint32_t kResolution = 96;
constexpr std::uint32_t kSlots = 64;
constexpr int kSampledPixels = 300; // per slot

struct Fragment {
    float depth;
    bool front;
    std::uint32_t node;
};

// The list of one pixel in stored order (a cycle is a bug: the walk stops and the count differs).
std::vector<Fragment> walk(const std::vector<std::uint32_t>& heads, const std::vector<shader::BundleNode>& nodes,
                           std::size_t pixel) {
    std::vector<Fragment> out;
    for (std::uint32_t i = heads[pixel] & shader::kBundleIndexMask; i != shader::kBundleNil && out.size() < 100000;
         i = nodes.at(i).next & shader::kBundleIndexMask) {
        out.push_back({nodes[i].depth, (nodes[i].next & shader::kBundleFrontFaceBit) != 0, i});
    }
    return out;
}

glm::vec3 pixelOrigin(const shader::BundleFrame& f, std::uint32_t i, std::uint32_t j) {
    return f.origin + (i + 0.5f) * f.pixelSize * f.axisX + (j + 0.5f) * f.pixelSize * f.axisY;
}

std::vector<EmbreeScene::RayHit> embreeHits(const EmbreeScene& embree, const shader::BundleFrame& f, std::uint32_t i,
                                            std::uint32_t j) {
    auto hits = embree.allHits(pixelOrigin(f, i, j) + f.depthNear * f.direction, f.direction, f.depthFar - f.depthNear);
    for (auto& h : hits) h.t += f.depthNear;
    return hits;
}

class BundlePoolTest : public bl::test::VulkanTest {
protected:
    void SetUp() override {
        VulkanTest::SetUp();
        scene = loadScene(bl::test::sourcePath("data/cornell-box/cornell.toml"));
        gpuScene = std::make_unique<gpu::GpuScene>(ctx(), scene);
        embree = std::make_unique<EmbreeScene>(scene, 0.0);
        bounds = scene.bounds();
        for (const gpu::GpuDraw& d : gpuScene->draws()) firstTriangle.push_back(d.firstIndex / 3);
    }

    std::vector<shader::BundleFrame> randomFrames(std::uint32_t count, std::uint32_t seed) const {
        DirectionSampler sampler(DirectionSequence::Random, seed);
        std::vector<shader::BundleFrame> frames;
        for (std::uint32_t k = 0; k < count; ++k) {
            BundleDirection d = sampler.sample(k);
            frames.push_back(bundleFrameForSphere(d.omega, d.rotation, bounds.center(), bounds.radius(), kResolution));
        }
        return frames;
    }

    // Builds every frame into its slot in one command buffer, as one batch (recordBuilds: the
    // modes' way), and sorts them all in one dispatch when asked.
    BundlePoolStatus buildAll(BundlePool& pool, const std::vector<shader::BundleFrame>& frames, bool sort) {
        std::vector<BundlePool::SlotBuild> builds;
        for (std::uint32_t s = 0; s < frames.size(); ++s) builds.push_back({s, frames[s], BundleGeometry::triangles(0.0)});
        ctx().submitAndWait([&](VkCommandBuffer cmd) {
            pool.recordReset(cmd);
            pool.recordBuilds(cmd, builds);
            if (sort) pool.recordSorts(cmd, 0, static_cast<std::uint32_t>(frames.size()));
        });
        return pool.status();
    }

    Scene scene;
    std::unique_ptr<gpu::GpuScene> gpuScene;
    std::unique_ptr<EmbreeScene> embree;
    Bounds bounds;
    std::vector<std::uint32_t> firstTriangle; // per mesh: its first triangle in GpuScene order
};

} // namespace

// 64 bundles stay resident together: after all were built in one submission, every slot still
// holds its own lists, and they match Embree along the same rays.
TEST_F(BundlePoolTest, SixtyFourResidentBundlesMatchEmbreeAllHits) {
    BundlePoolOptions options;
    options.slots = kSlots;
    options.slotPixels = kResolution * kResolution;
    options.sortable = true;
    BundlePool pool(ctx(), *gpuScene, options);
    const auto frames = randomFrames(kSlots, 777);
    BundlePoolStatus status = buildAll(pool, frames, true);
    if (status.overflowed()) {
        ASSERT_TRUE(pool.grow(status));
        status = buildAll(pool, frames, true);
    }
    ASSERT_FALSE(status.overflowed()) << status.requested << " of " << status.capacity;
    const auto nodes = pool.readNodes(status.requested);
    const auto previous = pool.readPrevious(status.requested);
    const float tolerance = 1e-5f * 2.0f * bounds.radius();
    std::mt19937 rng(99);
    std::size_t checked = 0, agree = 0, nonEmpty = 0, unsorted = 0, badLinks = 0;
    std::uint64_t reachable = 0;
    for (std::uint32_t s = 0; s < kSlots; ++s) {
        const shader::BundleFrame frame = pool.readFrame(s);
        ASSERT_EQ(frame.direction.x, frames[s].direction.x) << "slot " << s << " lost its frame";
        const auto heads = pool.readHeads(s);
        for (std::size_t p = 0; p < std::size_t(kResolution) * kResolution; ++p) reachable += walk(heads, nodes, p).size();
        for (int k = 0; k < kSampledPixels; ++k) {
            const std::uint32_t i = rng() % kResolution, j = rng() % kResolution;
            const auto list = walk(heads, nodes, std::size_t(j) * kResolution + i);
            const auto hits = embreeHits(*embree, frame, i, j);
            ++checked;
            nonEmpty += !list.empty();
            if (list.size() != hits.size()) continue;
            bool same = true;
            for (std::size_t n = 0; n < hits.size(); ++n) {
                // Sorted lists: the n-th stored fragment is Embree's n-th hit.
                same &= std::abs(hits[n].t - list[n].depth) <= tolerance;
                same &= (glm::dot(hits[n].geometricNormal, frame.direction) < 0.0f) == list[n].front;
                unsorted += n > 0 && list[n].depth < list[n - 1].depth;
                badLinks += previous.at(list[n].node) != (n ? list[n - 1].node : shader::kBundleNil);
            }
            agree += same;
        }
    }
    std::printf("%zu of %zu sampled pixels agree with Embree (%zu non-empty), %llu fragments in %u slots\n", agree,
                checked, nonEmpty, static_cast<unsigned long long>(status.requested), kSlots);
    EXPECT_EQ(reachable, status.requested) << "every stored node is in exactly one list";
    EXPECT_GT(nonEmpty, checked / 3); // the box fills about half of its bounding sphere's frame
    // A pixel centre on a shared edge may go to either triangle (rasterizer tie rule vs Embree's
    // watertight test): those are the allowed 0.5%.
    EXPECT_GE(double(agree), 0.995 * double(checked));
    EXPECT_EQ(unsorted, 0u);
    EXPECT_EQ(badLinks, 0u);
}

// A batch names each slot once (a second build of a slot would clear its heads after the batch's
// barrier), and a sort stays within the pool's slots.
TEST_F(BundlePoolTest, BatchesRefuseARepeatedSlotAndSortsStayInThePool) {
    BundlePoolOptions options;
    options.slots = 4;
    options.slotPixels = kResolution * kResolution;
    options.sortable = true;
    BundlePool pool(ctx(), *gpuScene, options);
    const auto frames = randomFrames(2, 5);
    const std::vector<BundlePool::SlotBuild> twice{{1, frames[0], BundleGeometry::triangles(0.0)},
                                                   {1, frames[1], BundleGeometry::triangles(0.0)}};
    ctx().submitAndWait([&](VkCommandBuffer cmd) {
        EXPECT_THROW(pool.recordBuilds(cmd, twice), Error);
        EXPECT_THROW(pool.recordSorts(cmd, 3, 2), Error);
        EXPECT_THROW(pool.recordSorts(cmd, 0, 0), Error);
        pool.recordReset(cmd); // the command buffer stays valid
    });
}

// The hit payload describes the surface each fragment lies on: its triangle's plane contains the
// fragment, the barycentrics rebuild the fragment's position, the material is the mesh's.
TEST_F(BundlePoolTest, HitPayloadRebuildsTheFragment) {
    if (!ctx().geometryShader()) GTEST_SKIP() << "hit payload needs gl_PrimitiveID";
    BundlePoolOptions options;
    options.slots = 2;
    options.slotPixels = kResolution * kResolution;
    options.payload = BundlePayload::Hit;
    options.initialNodes = 1 << 18;
    BundlePool pool(ctx(), *gpuScene, options);
    const auto frames = randomFrames(2, 4242);
    const BundlePoolStatus status = buildAll(pool, frames, false);
    ASSERT_FALSE(status.overflowed());
    const auto nodes = pool.readNodes(status.requested);
    const auto hits = pool.readHits(status.requested);
    // Host copies of the triangles in GpuScene order.
    std::vector<glm::vec3> corners;
    std::vector<std::uint32_t> materials;
    for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
        const Mesh& mesh = scene.meshes[m];
        for (const glm::uvec3& t : mesh.triangles) {
            for (int c = 0; c < 3; ++c) corners.push_back(mesh.positions[t[c]]);
            materials.push_back(mesh.material);
        }
    }
    const float tolerance = 1e-4f * 2.0f * bounds.radius();
    std::size_t checked = 0, wrong = 0;
    double worst = 0.0;
    for (std::uint32_t s = 0; s < 2; ++s) {
        const auto heads = pool.readHeads(s);
        for (std::uint32_t j = 0; j < kResolution; ++j) {
            for (std::uint32_t i = 0; i < kResolution; ++i) {
                for (const Fragment& f : walk(heads, nodes, std::size_t(j) * kResolution + i)) {
                    const shader::BundleHit& h = hits.at(f.node);
                    ASSERT_LT(h.id, materials.size());
                    const glm::vec2 b = glm::unpackUnorm2x16(h.barycentric);
                    const glm::vec3* p = &corners[3 * h.id];
                    const glm::vec3 rebuilt = (1.0f - b.x - b.y) * p[0] + b.x * p[1] + b.y * p[2];
                    const glm::vec3 actual = pixelOrigin(frames[s], i, j) + f.depth * frames[s].direction;
                    const double error = glm::length(rebuilt - actual);
                    worst = std::max(worst, error);
                    const glm::vec3 n = shader::blUnpackOctahedral(h.normal);
                    wrong += error > tolerance || (h.material & shader::kBundleHitMaterialMask) != materials[h.id] ||
                             (h.material & shader::kBundleHitSplat) != 0 || std::abs(glm::length(n) - 1.0f) > 1e-3f;
                    ++checked;
                }
            }
        }
    }
    std::printf("%zu fragments, worst rebuilt-position error %.3g (scene extent %.3g)\n", checked, worst,
                2.0 * bounds.radius());
    EXPECT_GT(checked, 1000u);
    EXPECT_EQ(wrong, 0u) << "worst position error " << worst;
}

// Overflow: a pool far too small stores nothing out of range, counts exactly what was asked for,
// and after grow() the same builds fit and give the same count.
TEST_F(BundlePoolTest, OverflowIsCountedExactlyAndGrowFits) {
    BundlePoolOptions options;
    options.slots = 8;
    options.slotPixels = kResolution * kResolution;
    options.initialNodes = 100;
    BundlePool pool(ctx(), *gpuScene, options);
    const auto frames = randomFrames(8, 31);
    const BundlePoolStatus small = buildAll(pool, frames, false);
    EXPECT_TRUE(small.overflowed());
    EXPECT_EQ(small.capacity, 100u);
    // The lists that were built point only at stored nodes.
    const auto nodes = pool.readNodes(small.capacity);
    for (std::uint32_t s = 0; s < 8; ++s) {
        const auto heads = pool.readHeads(s);
        for (std::size_t p = 0; p < heads.size(); ++p) {
            for (std::uint32_t i = heads[p] & shader::kBundleIndexMask; i != shader::kBundleNil;
                 i = nodes[i].next & shader::kBundleIndexMask) {
                ASSERT_LT(i, small.capacity);
            }
        }
    }
    ASSERT_TRUE(pool.grow(small));
    const BundlePoolStatus grown = buildAll(pool, frames, false);
    EXPECT_FALSE(grown.overflowed());
    EXPECT_EQ(grown.requested, small.requested);
}

// A memory cap is honoured and refused clearly when it cannot hold a node.
TEST_F(BundlePoolTest, LimitsComeFromTheCapOrTheDevice) {
    BundlePoolOptions options;
    options.slotPixels = 64 * 64;
    options.memoryCapBytes = 1000 * sizeof(shader::BundleNode);
    BundlePool capped(ctx(), *gpuScene, options);
    EXPECT_EQ(capped.maxNodes(), 1000u);
    options.memoryCapBytes = 0;
    BundlePool device(ctx(), *gpuScene, options);
    EXPECT_GT(device.maxNodes(), 1000000u);
    EXPECT_LE(device.maxNodes() * sizeof(shader::BundleNode), ctx().maxAllocationBytes());
    options.memoryCapBytes = 3;
    EXPECT_NE(bl::test::errorOf([&] { BundlePool none(ctx(), *gpuScene, options); }).find("holds no node"),
              std::string::npos);
    options.memoryCapBytes = 0;
    options.slots = 0;
    EXPECT_NE(bl::test::errorOf([&] { BundlePool none(ctx(), *gpuScene, options); }).find("hold nothing"),
              std::string::npos);
}

// Point splats (imperfect bundles): each splat covers its disc, projected, and nothing else; its
// fragments lie exactly on its plane and carry its id; splats with no usable disc draw nothing.
TEST_F(BundlePoolTest, PointSplatsCoverTheirDiscsExactly) {
    if (!ctx().geometryShader()) GTEST_SKIP() << "hit payload needs gl_PrimitiveID";
    constexpr std::uint32_t kSide = 256;
    constexpr int kGrid = 8;            // kGrid x kGrid splats in the plane z = 0
    constexpr float kPitch = 1.0f;      // world units between splat centres
    constexpr float kRadius = 0.3f;     // world units
    const glm::vec3 direction = glm::normalize(glm::vec3(0.0f, 0.0f, -1.0f));
    const float tilt = 60.0f;           // degrees between the splats' normal and the direction
    const glm::vec3 normal(0.0f, std::sin(glm::radians(tilt)), std::cos(glm::radians(tilt)));
    std::vector<shader::BundleSplat> splats;
    for (int y = 0; y < kGrid; ++y) {
        for (int x = 0; x < kGrid; ++x) {
            splats.push_back({glm::vec3((x - kGrid / 2 + 0.5f) * kPitch, (y - kGrid / 2 + 0.5f) * kPitch, 0.0f),
                              kRadius, normal, 3u});
        }
    }
    // Refused discs: NaN radius, zero radius, an unnormalized normal.
    splats.push_back({glm::vec3(0.0f), std::nanf(""), normal, 0u});
    splats.push_back({glm::vec3(0.0f), 0.0f, normal, 0u});
    splats.push_back({glm::vec3(0.0f), kRadius, glm::vec3(0.0f), 0u});
    vk::Buffer buffer(ctx(), splats.size() * sizeof(shader::BundleSplat),
                      VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT |
                          VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                      vk::MemoryUse::Device);
    buffer.upload(ctx(), splats.data(), splats.size() * sizeof(shader::BundleSplat));

    BundlePoolOptions options;
    options.slotPixels = kSide * kSide;
    options.payload = BundlePayload::Hit;
    BundlePool pool(ctx(), *gpuScene, options);
    const float extent = kGrid * kPitch * 0.5f * std::sqrt(2.0f) + kRadius;
    const shader::BundleFrame frame = bundleFrameForSphere(direction, 0.0f, glm::vec3(0.0f), extent, kSide);
    ctx().submitAndWait([&](VkCommandBuffer cmd) {
        pool.recordReset(cmd);
        pool.recordBuild(cmd, 0, frame,
                         BundleGeometry::pointSplats(deviceAddress(ctx(), buffer), std::uint32_t(splats.size())));
    });
    const BundlePoolStatus status = pool.status();
    ASSERT_FALSE(status.overflowed());
    const auto nodes = pool.readNodes(status.requested);
    const auto hits = pool.readHits(status.requested);
    const auto heads = pool.readHeads(0);
    std::vector<std::size_t> perSplat(splats.size(), 0);
    double worstDepth = 0.0;
    std::size_t outside = 0;
    for (std::uint32_t j = 0; j < kSide; ++j) {
        for (std::uint32_t i = 0; i < kSide; ++i) {
            for (const Fragment& f : walk(heads, nodes, std::size_t(j) * kSide + i)) {
                const shader::BundleHit& h = hits.at(f.node);
                ASSERT_LT(h.id, splats.size());
                ASSERT_NE(h.material & shader::kBundleHitSplat, 0u);
                ++perSplat[h.id];
                const shader::BundleSplat& s = splats[h.id];
                const glm::vec3 p = pixelOrigin(frame, i, j) + f.depth * frame.direction;
                worstDepth = std::max(worstDepth, double(std::abs(glm::dot(p - s.position, s.normal))));
                outside += glm::length(p - s.position) > kRadius * (1.0f + 1e-4f);
            }
        }
    }
    // Projected disc: an ellipse of area pi r^2 |cos(tilt)|, in pixels.
    const double expected = glm::pi<double>() * kRadius * kRadius * std::cos(glm::radians(double(tilt))) /
                            (double(frame.pixelSize) * frame.pixelSize);
    double total = 0.0;
    for (int k = 0; k < kGrid * kGrid; ++k) total += double(perSplat[k]);
    std::printf("splats: %.1f fragments per disc, %.1f expected; worst distance from the plane %.3g\n",
                total / (kGrid * kGrid), expected, worstDepth);
    EXPECT_NEAR(total / (kGrid * kGrid), expected, 0.02 * expected);
    EXPECT_EQ(outside, 0u);
    EXPECT_LT(worstDepth, 1e-5);
    for (std::size_t k = kGrid * kGrid; k < splats.size(); ++k) EXPECT_EQ(perSplat[k], 0u) << "refused splat " << k;
}

// Defect 5: vertex normals that cancel (zero, or opposite at the corners: a folded or badly
// exported mesh) must not put NaN into the payload; the fragment falls back to its plane's normal.
TEST_F(BundlePoolTest, CancellingVertexNormalsGiveAFiniteNormal) {
    if (!ctx().geometryShader()) GTEST_SKIP() << "hit payload needs gl_PrimitiveID";
    Scene s;
    s.materials.push_back(Material{});
    Mesh square = bl::test::makeSquare(2.0f, 0);
    ASSERT_EQ(square.normals.size(), square.positions.size());
    for (std::size_t v = 0; v < square.normals.size(); ++v) {
        square.normals[v] = glm::vec3(0.0f); // what a file with zero normals gives, uncleaned
    }
    s.meshes.push_back(square);
    gpu::GpuScene folded(ctx(), s);
    BundlePoolOptions options;
    options.slotPixels = 64 * 64;
    options.payload = BundlePayload::Hit;
    BundlePool pool(ctx(), folded, options);
    const Bounds b = s.bounds();
    const shader::BundleFrame frame = bundleFrameForSphere(glm::vec3(0, -1, 0), 0.2f, b.center(), b.radius(), 64);
    ctx().submitAndWait([&](VkCommandBuffer cmd) {
        pool.recordReset(cmd);
        pool.recordBuild(cmd, 0, frame, BundleGeometry::triangles(0.0));
    });
    const BundlePoolStatus status = pool.status();
    ASSERT_FALSE(status.overflowed());
    ASSERT_GT(status.requested, 100u);
    std::size_t bad = 0;
    for (const shader::BundleHit& h : pool.readHits(status.requested)) {
        const glm::vec3 n = shader::blUnpackOctahedral(h.normal);
        // The plane's normal is +-y; a NaN would unpack to some other (finite) direction.
        bad += !std::isfinite(n.x) || std::abs(std::abs(n.y) - 1.0f) > 1e-3f;
    }
    EXPECT_EQ(bad, 0u) << "of " << status.requested;
}
