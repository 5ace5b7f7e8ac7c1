// Perfect bundles are exact: for random directions every pixel's list holds exactly the surface
// crossings Embree finds along the same parallel ray through the pixel centre (the independent
// check), with the same depths and faces; and no fragment is ever lost, whatever the depth
// complexity or memory cap.
#include "bundle/BundleBuilder.h"
#include "bundle/BundleFrame.h"
#include "bundle/DirectionSampler.h"
#include "reference/EmbreeScene.h"
#include "scene/SceneLoader.h"
#include "support/AnalyticScenes.h"
#include "support/TestFiles.h"
#include "support/VulkanTest.h"

#include <algorithm>
#include <glm/gtc/packing.hpp>
#include <shared/Octahedral.h>
#include <cstdio>

using namespace bl;

namespace {

struct PixelList {
    std::vector<float> depths; // sorted
    std::vector<bool> frontFaces;
};

// The list of every pixel, sorted by depth.
std::vector<PixelList> sortedLists(const std::vector<std::uint32_t>& heads, const std::vector<shader::BundleNode>& nodes) {
    std::vector<PixelList> out(heads.size());
    for (std::size_t p = 0; p < heads.size(); ++p) {
        std::vector<std::pair<float, bool>> items;
        for (std::uint32_t i = heads[p] & shader::kBundleIndexMask; i != shader::kBundleNil;
             i = nodes.at(i).next & shader::kBundleIndexMask) {
            items.emplace_back(nodes[i].depth, (nodes[i].next & shader::kBundleFrontFaceBit) != 0);
            if (items.size() > 100000) break; // a cycle would be a bug: stop, the counts will differ
        }
        std::sort(items.begin(), items.end());
        for (auto& [d, f] : items) {
            out[p].depths.push_back(d);
            out[p].frontFaces.push_back(f);
        }
    }
    return out;
}

struct Agreement {
    std::size_t pixels = 0, sameCount = 0;
    std::size_t pixelsWithDepthMismatch = 0, pixelsWithFaceMismatch = 0;
    double worstDepthError = 0.0;
};

Agreement compareWithEmbree(const shader::BundleFrame& f, const std::vector<PixelList>& lists, const EmbreeScene& embree,
                            float depthTolerance) {
    Agreement a;
    for (std::uint32_t j = 0; j < f.height; ++j) {
        for (std::uint32_t i = 0; i < f.width; ++i) {
            glm::vec3 o = f.origin + (i + 0.5f) * f.pixelSize * f.axisX + (j + 0.5f) * f.pixelSize * f.axisY +
                          f.depthNear * f.direction;
            std::vector<EmbreeScene::RayHit> hits = embree.allHits(o, f.direction, f.depthFar - f.depthNear);
            const PixelList& l = lists[j * f.width + i];
            ++a.pixels;
            if (hits.size() != l.depths.size()) continue;
            ++a.sameCount;
            bool depthMismatch = false, faceMismatch = false;
            for (std::size_t k = 0; k < hits.size(); ++k) {
                double err = std::abs(double(f.depthNear) + hits[k].t - l.depths[k]);
                a.worstDepthError = std::max(a.worstDepthError, err);
                depthMismatch |= err > depthTolerance;
                bool front = glm::dot(hits[k].geometricNormal, f.direction) < 0.0f;
                faceMismatch |= front != l.frontFaces[k];
            }
            a.pixelsWithDepthMismatch += depthMismatch;
            a.pixelsWithFaceMismatch += faceMismatch;
        }
    }
    return a;
}

class BundleExactness : public bl::test::VulkanTest {
protected:
    void checkScene(const std::string& path, std::uint32_t resolution, int directions,
                    BundleBackend backend = BundleBackend::Raster) {
        SCOPED_TRACE(path);
        Scene scene = loadScene(path);
        gpu::GpuScene gpuScene(ctx(), scene);
        EmbreeScene embree(scene, 0.0);
        BundleBuilderOptions options;
        options.backend = backend;
        BundleBuilder builder(ctx(), gpuScene, options);
        DirectionSampler sampler(DirectionSequence::Random, 12345);
        const Bounds b = scene.bounds();
        for (int k = 0; k < directions; ++k) {
            BundleDirection d = sampler.sample(k);
            shader::BundleFrame frame = bundleFrameForSphere(d.omega, d.rotation, b.center(), b.radius(), resolution);
            std::size_t fragments = 0;
            builder.build(frame, 0.0, [&](const BuiltBundle& built) {
                std::vector<std::uint32_t> heads;
                std::vector<shader::BundleNode> nodes;
                builder.readLists(built, heads, nodes);
                fragments += built.fragments;
                // 1e-5 of the scene's extent, as the issue asks.
                Agreement a = compareWithEmbree(built.frame, sortedLists(heads, nodes), embree, 1e-5f * 2.0f * b.radius());
                // A pixel centre on a shared edge may be given to either triangle by the
                // rasterizer's tie rule and by Embree's watertight test: such pixels are the
                // allowed 0.1%.
                const double allowed = 0.001 * double(a.pixels);
                EXPECT_GE(double(a.sameCount), double(a.pixels) - allowed) << "direction " << k;
                EXPECT_LE(double(a.pixelsWithDepthMismatch), allowed) << "worst depth error " << a.worstDepthError;
                EXPECT_LE(double(a.pixelsWithFaceMismatch), allowed);
                std::printf("direction %d: %zu of %zu pixels agree in count, %zu differ in depth (worst %.3g of extent "
                            "%.3g), %zu in face\n",
                            k, a.sameCount, a.pixels, a.pixelsWithDepthMismatch, a.worstDepthError, 2.0 * b.radius(),
                            a.pixelsWithFaceMismatch);
            });
            EXPECT_GT(fragments, 0u);
        }
    }
};

} // namespace

TEST_F(BundleExactness, CornellBox) { checkScene(bl::test::sourcePath("data/cornell-box/cornell.toml"), 256, 6); }

TEST_F(BundleExactness, McGuireCornellWithCoplanarDuplicates) {
    BL_SKIP_WITHOUT_SHARED("data/cornell-box/mcguire/CornellBox-Original.obj");
    checkScene(bl::test::sharedPath("data/cornell-box/mcguire/CornellBox-Original.obj"), 256, 4);
}

TEST_F(BundleExactness, StanfordBunny) {
    BL_SKIP_WITHOUT_SHARED("data/bunny/mcguire/bunny.obj");
    checkScene(bl::test::sharedPath("data/bunny/mcguire/bunny.obj"), 256, 2);
}

TEST_F(BundleExactness, Sponza) {
    BL_SKIP_WITHOUT_SCENE_FILES("data/external/sponza-point.toml");
    checkScene(bl::test::sourcePath("data/external/sponza-point.toml"), 256, 2);
}

// The compute backend (software rasterization in compute shaders) against the same Embree hits.
TEST_F(BundleExactness, ComputeBackendCornellBox) {
    checkScene(bl::test::sourcePath("data/cornell-box/cornell.toml"), 256, 6, BundleBackend::Compute);
}

TEST_F(BundleExactness, ComputeBackendMcGuireCornellWithCoplanarDuplicates) {
    BL_SKIP_WITHOUT_SHARED("data/cornell-box/mcguire/CornellBox-Original.obj");
    checkScene(bl::test::sharedPath("data/cornell-box/mcguire/CornellBox-Original.obj"), 256, 4, BundleBackend::Compute);
}

TEST_F(BundleExactness, ComputeBackendStanfordBunny) {
    BL_SKIP_WITHOUT_SHARED("data/bunny/mcguire/bunny.obj");
    checkScene(bl::test::sharedPath("data/bunny/mcguire/bunny.obj"), 256, 2, BundleBackend::Compute);
}

TEST_F(BundleExactness, ComputeBackendSponza) {
    BL_SKIP_WITHOUT_SCENE_FILES("data/external/sponza-point.toml");
    checkScene(bl::test::sourcePath("data/external/sponza-point.toml"), 256, 2, BundleBackend::Compute);
}

// The hit payload from both backends (shaders/bundle/PoolHit.glsl, one function): Sponza (textured,
// many materials) at 256^2 from two directions, and the animated Cornell box at a time when its
// short block is turned and moved (the compute build's model matrix, packed as three rows). lavapipe
// breaks ties as the compute build does, so each pixel holds the same fragments: per fragment (by
// depth) the same triangle and material, and the same facet plane, shading normal and
// barycentrics to two steps of their 16-bit packing, uv to float rounding (measured: identical,
// 332k fragments of Sponza and 70k of the box).
TEST_F(BundleExactness, ComputeBuildWritesTheRasterHits) {
    BL_SKIP_WITHOUT_SCENE_FILES("data/external/sponza-point.toml");
    if (ctx().info().type != "CPU") GTEST_SKIP() << "tie rules may differ from the compute build's on a GPU";
    struct Fragment {
        float depth;
        shader::BundleHit hit;
    };
    // Per pixel its fragments by depth (ties by triangle).
    auto fragments = [&](BundleBuilder& builder, const shader::BundleFrame& frame, double time) {
        std::vector<std::vector<Fragment>> out(std::size_t(frame.width) * frame.height);
        builder.build(frame, time, [&](const BuiltBundle& built) {
            std::vector<std::uint32_t> heads;
            std::vector<shader::BundleNode> nodes;
            std::vector<shader::BundleHit> hits;
            builder.readLists(built, heads, nodes, &hits);
            ASSERT_EQ(hits.size(), nodes.size());
            for (std::size_t p = 0; p < heads.size(); ++p) {
                for (std::uint32_t i = heads[p] & shader::kBundleIndexMask; i != shader::kBundleNil;
                     i = nodes[i].next & shader::kBundleIndexMask) {
                    out[p].push_back({nodes[i].depth, hits[i]});
                }
                std::sort(out[p].begin(), out[p].end(), [](const Fragment& a, const Fragment& c) {
                    return a.depth != c.depth ? a.depth < c.depth : a.hit.id < c.hit.id;
                });
            }
        });
        return out;
    };
    // The larger difference of two words' 16-bit halves, signed (octahedral) or not (barycentrics).
    auto steps = [](std::uint32_t a, std::uint32_t b, bool sign) {
        auto half = [sign](std::uint32_t w, int k) {
            const std::uint32_t h = (w >> (16 * k)) & 0xffffu;
            return sign ? int(std::int16_t(h)) : int(h);
        };
        return std::max(std::abs(half(a, 0) - half(b, 0)), std::abs(half(a, 1) - half(b, 1)));
    };
    struct Case {
        const char* file;
        double time;
        int directions;
    };
    for (const Case& c : {Case{"data/external/sponza-point.toml", 0.0, 2}, Case{"data/cornell-box/cornell-animated.toml", 0.7, 1}}) {
        SCOPED_TRACE(c.file);
        Scene scene = loadScene(bl::test::sourcePath(c.file));
        gpu::GpuScene gpuScene(ctx(), scene);
        const Bounds b = scene.bounds();
        DirectionSampler sampler(DirectionSequence::Random, 99);
        BundleBuilderOptions options;
        options.payload = BundlePayload::Hit;
        BundleBuilder raster(ctx(), gpuScene, options);
        options.backend = BundleBackend::Compute;
        BundleBuilder compute(ctx(), gpuScene, options);
        std::size_t compared = 0;
        int worstPlane = 0, worstNormal = 0, worstBarycentric = 0;
        for (int direction = 0; direction < c.directions; ++direction) {
            const BundleDirection d = sampler.sample(direction);
            const shader::BundleFrame frame = bundleFrameForSphere(d.omega, d.rotation, b.center(), b.radius(), 256);
            const auto r = fragments(raster, frame, c.time), g = fragments(compute, frame, c.time);
            for (std::size_t p = 0; p < r.size(); ++p) {
                ASSERT_EQ(r[p].size(), g[p].size()) << "pixel " << p;
                for (std::size_t k = 0; k < r[p].size(); ++k) {
                    const shader::BundleHit &h = r[p][k].hit, &q = g[p][k].hit;
                    ASSERT_EQ(h.id, q.id) << "pixel " << p;
                    EXPECT_EQ(h.material, q.material);
                    worstPlane = std::max(worstPlane, steps(h.plane, q.plane, true));
                    worstNormal = std::max(worstNormal, steps(h.normal, q.normal, true));
                    worstBarycentric = std::max(worstBarycentric, steps(h.barycentric, q.barycentric, false));
                    EXPECT_LE(glm::length(h.uv - q.uv), 1e-5f * (1.0f + glm::length(h.uv)));
                    ++compared;
                }
            }
        }
        std::printf("%s: %zu fragments, worst steps: plane %d, normal %d, barycentrics %d\n", c.file, compared,
                    worstPlane, worstNormal, worstBarycentric);
        EXPECT_GT(compared, 10000u);
        EXPECT_LE(worstPlane, 2);
        EXPECT_LE(worstNormal, 2);
        EXPECT_LE(worstBarycentric, 2);
    }
}

// 250 parallel squares: every pixel that sees them holds 250 fragments, with a pool far too small
// at first (grow and rebuild) and then under a memory cap that forces tiles; with either backend.
class BundleDepthComplexity : public BundleExactness, public ::testing::WithParamInterface<BundleBackend> {};

TEST_P(BundleDepthComplexity, NeverLosesAFragment) {
    Scene s;
    s.materials.push_back(Material{});
    const int layers = 250;
    for (int i = 0; i < layers; ++i) {
        s.meshes.push_back(bl::test::makeSquare(2.0f, 0, glm::vec3(0.0f, 0.004f * i, 0.0f)));
    }
    gpu::GpuScene gpuScene(ctx(), s);
    const std::uint32_t resolution = 64;
    // Looking straight down: squares of side 2 inside a sphere of radius ~1.5.
    const Bounds b = s.bounds();
    shader::BundleFrame frame = bundleFrameForSphere(glm::vec3(0, -1, 0), 0.3f, b.center(), b.radius(), resolution);
    auto check = [&](BundleBuilder& builder, BundleStats& stats) {
        std::size_t covered = 0;
        stats = builder.build(frame, 0.0, [&](const BuiltBundle& built) {
            std::vector<std::uint32_t> heads;
            std::vector<shader::BundleNode> nodes;
            builder.readLists(built, heads, nodes);
            for (const PixelList& l : sortedLists(heads, nodes)) {
                if (l.depths.empty()) continue;
                ASSERT_EQ(l.depths.size(), std::size_t(layers));
                ++covered;
                for (int k = 1; k < layers; ++k) ASSERT_GT(l.depths[k], l.depths[k - 1]);
            }
        });
        EXPECT_GT(covered, resolution * resolution / 4);
    };
    BundleBuilderOptions small;
    small.backend = GetParam();
    small.initialNodes = 1000;
    small.listStatistics = true;
    BundleBuilder growing(ctx(), gpuScene, small);
    BundleStats stats;
    check(growing, stats);
    EXPECT_GE(stats.rebuilds, 1u);
    EXPECT_EQ(stats.tiles, 1u);
    EXPECT_EQ(stats.longestList, std::uint32_t(layers));
    EXPECT_NEAR(stats.meanListLength(), double(layers), 1e-9);
    const std::uint64_t untiledFragments = stats.fragments;

    BundleBuilderOptions capped;
    capped.backend = GetParam();
    capped.initialNodes = 1000;
    capped.memoryCapBytes = resolution * resolution * layers * sizeof(shader::BundleNode) / 5; // a fifth of the need
    BundleBuilder tiled(ctx(), gpuScene, capped);
    check(tiled, stats);
    EXPECT_GE(stats.tiles, 4u);
    // Counted per tile: every fragment of the untiled bundle in exactly one tile.
    EXPECT_EQ(stats.fragments, untiledFragments);
    EXPECT_LE(tiled.capacity() * sizeof(shader::BundleNode), capped.memoryCapBytes);

    // One pixel alone needs 250 nodes: a cap below that is a clear error, not a crash.
    BundleBuilderOptions impossible;
    impossible.backend = GetParam();
    impossible.memoryCapBytes = 100 * sizeof(shader::BundleNode);
    BundleBuilder refusing(ctx(), gpuScene, impossible);
    EXPECT_NE(bl::test::errorOf([&] { refusing.build(frame, 0.0, [](const BuiltBundle&) {}); })
                  .find("more than the memory cap allows"),
              std::string::npos);
}

INSTANTIATE_TEST_SUITE_P(Backends, BundleDepthComplexity, ::testing::Values(BundleBackend::Raster, BundleBackend::Compute),
                         [](const ::testing::TestParamInfo<BundleBackend>& p) {
                             return p.param == BundleBackend::Raster ? std::string("Raster") : std::string("Compute");
                         });

namespace {
// Every pixel's sorted list of the whole frame, assembled from the parts a build hands over (one
// part, or tiles placed at their offsets in the frame's pixel grid).
struct AssembledBundle {
    std::vector<PixelList> lists;
    BundleStats stats;
};

AssembledBundle assemble(BundleBuilder& builder, const shader::BundleFrame& frame) {
    AssembledBundle out;
    out.lists.resize(std::size_t(frame.width) * frame.height);
    out.stats = builder.build(frame, 0.0, [&](const BuiltBundle& built) {
        const shader::BundleFrame& tile = built.frame;
        std::vector<std::uint32_t> heads;
        std::vector<shader::BundleNode> nodes;
        builder.readLists(built, heads, nodes);
        const std::vector<PixelList> lists = sortedLists(heads, nodes);
        const std::uint32_t x0 = tile.tileX, y0 = tile.tileY;
        for (std::uint32_t j = 0; j < tile.height; ++j) {
            for (std::uint32_t i = 0; i < tile.width; ++i) {
                PixelList& target = out.lists.at(std::size_t(y0 + j) * frame.width + (x0 + i));
                EXPECT_TRUE(target.depths.empty()) << "pixel " << x0 + i << "," << y0 + j << " built twice";
                target = lists[std::size_t(j) * tile.width + i];
            }
        }
    });
    return out;
}
// Pixels whose lists differ in length, in faces (same length), and the largest depth difference.
struct BundleDifference {
    std::size_t countDiffers = 0, faceDiffers = 0;
    double worstDepth = 0.0;
};

BundleDifference difference(const AssembledBundle& reference, const AssembledBundle& parts) {
    BundleDifference d;
    for (std::size_t p = 0; p < reference.lists.size(); ++p) {
        const PixelList &r = reference.lists[p], &t = parts.lists[p];
        if (r.depths.size() != t.depths.size()) {
            ++d.countDiffers;
            continue;
        }
        d.faceDiffers += r.frontFaces != t.frontFaces;
        for (std::size_t i = 0; i < r.depths.size(); ++i) {
            d.worstDepth = std::max(d.worstDepth, double(std::abs(r.depths[i] - t.depths[i])));
        }
    }
    return d;
}
} // namespace

// Defect 3: tiles are integer rectangles of the frame's pixel grid, rasterized exactly as the
// untiled frame: every pixel holds the same fragments with the same faces and depths, on a scene
// full of triangle edges, from directions where tile borders cut thousands of triangles. (With
// shifted tile origins: 1-11 pixels per direction differed, tiles held up to 7 fragments more or
// less; with per-tile viewports, triangles clipped at tile borders still moved 1-4 pixels.)
// The statistics pass walks every list once and is the traversal benchmark (`bench bundles`): its
// GPU time must be the walk's. On lavapipe a compute pass timed without a flush after the start
// timestamp read ~0 (0.02 ms for a 1024^2 walk that takes 80 ms; vk/GpuTimer.cpp).
TEST_F(BundleExactness, ListWalkIsTimed) {
    Scene scene = loadScene(bl::test::sourcePath("data/cornell-box/cornell.toml"));
    gpu::GpuScene gpuScene(ctx(), scene);
    BundleBuilderOptions options;
    options.listStatistics = true;
    BundleBuilder builder(ctx(), gpuScene, options);
    const Bounds b = scene.bounds();
    shader::BundleFrame frame = bundleFrameForSphere(glm::normalize(glm::vec3(0.3f, -0.8f, 0.5f)), 0.7f, b.center(), b.radius(), 1024);
    BundleStats stats;
    for (int k = 0; k < 2; ++k) { // the first builds compile the shaders
        stats = builder.build(frame, 0.0, [](const BuiltBundle&) {});
    }
    std::printf("walk %.3f ms over %llu nodes, build %.3f ms\n", stats.traverseMs,
                static_cast<unsigned long long>(stats.fragments), stats.buildMs);
    // A million heads and some millions of nodes: far more than the build's 1/50 on any device
    // measured (lavapipe: about a quarter of it).
    EXPECT_GT(stats.traverseMs, 0.02 * stats.buildMs);
}

TEST_F(BundleExactness, TiledBuildIsTheUntiledBuildFragmentForFragment) {
    BL_SKIP_WITHOUT_SCENE_FILES("data/external/sponza-point.toml");
    Scene scene = loadScene(bl::test::sourcePath("data/external/sponza-point.toml"));
    gpu::GpuScene gpuScene(ctx(), scene);
    const Bounds b = scene.bounds();
    DirectionSampler sampler(DirectionSequence::Random, 777);
    const std::uint32_t resolution = 320;
    BundleBuilder whole(ctx(), gpuScene);
    BundleBuilderOptions capped;
    capped.memoryCapBytes = 1u << 18; // 32k nodes: a sixteenth of a 320^2 Sponza bundle
    BundleBuilder tiled(ctx(), gpuScene, capped);
    for (int k = 0; k < 2; ++k) {
        const BundleDirection d = sampler.sample(k);
        // A frame whose origin is not a round number in world units, as any random direction gives.
        const shader::BundleFrame frame =
            bundleFrameForSphere(d.omega, d.rotation, b.center(), b.radius(), resolution);
        const AssembledBundle reference = assemble(whole, frame);
        const AssembledBundle parts = assemble(tiled, frame);
        ASSERT_EQ(reference.stats.tiles, 1u);
        ASSERT_GE(parts.stats.tiles, 9u);
        const BundleDifference diff = difference(reference, parts);
        const std::size_t countDiffers = diff.countDiffers, faceDiffers = diff.faceDiffers;
        const double worstDepth = diff.worstDepth;
        std::printf("direction %d: %u tiles, %llu vs %llu fragments, %zu pixels differ in count, %zu in faces, worst "
                    "depth difference %.3g (extent %.3g)\n",
                    k, parts.stats.tiles, (unsigned long long)parts.stats.fragments,
                    (unsigned long long)reference.stats.fragments, countDiffers, faceDiffers, worstDepth,
                    2.0 * b.radius());
        EXPECT_EQ(parts.stats.fragments, reference.stats.fragments) << "direction " << k;
        EXPECT_EQ(countDiffers, 0u) << "direction " << k;
        EXPECT_EQ(faceDiffers, 0u) << "direction " << k;
        EXPECT_EQ(worstDepth, 0.0) << "direction " << k; // the same pixel rays: the same depths
    }
}

// The compute backend builds the raster backend's nodes: Sponza (66k triangles, every size and
// slant) from two random directions at 320^2, the raster build whole against the compute build in
// tiles (a 1/16 memory cap), and one direction at 1024^2 untiled (its floor triangles cover >65k
// pixels each: walked by one invocation, lavapipe's loop limit cut 20% of the fragments): per
// pixel the same fragments with the same faces and depths, except pixel centres exactly on a
// shared edge, which the two tie rules may give to different triangles.
TEST_F(BundleExactness, ComputeBuildMatchesTheRasterBuild) {
    BL_SKIP_WITHOUT_SCENE_FILES("data/external/sponza-point.toml");
    Scene scene = loadScene(bl::test::sourcePath("data/external/sponza-point.toml"));
    gpu::GpuScene gpuScene(ctx(), scene);
    const Bounds b = scene.bounds();
    DirectionSampler sampler(DirectionSequence::Random, 4242);
    BundleBuilder raster(ctx(), gpuScene);
    BundleBuilderOptions tiles;
    tiles.backend = BundleBackend::Compute;
    tiles.memoryCapBytes = 1u << 18;
    BundleBuilder computeTiled(ctx(), gpuScene, tiles);
    BundleBuilderOptions whole;
    whole.backend = BundleBackend::Compute;
    BundleBuilder computeWhole(ctx(), gpuScene, whole);
    struct Case {
        int direction;
        std::uint32_t resolution;
        BundleBuilder* compute;
    };
    for (const Case& c : {Case{0, 320, &computeTiled}, Case{1, 320, &computeTiled}, Case{0, 1024, &computeWhole}}) {
        const BundleDirection d = sampler.sample(c.direction);
        const shader::BundleFrame frame = bundleFrameForSphere(d.omega, d.rotation, b.center(), b.radius(), c.resolution);
        const AssembledBundle reference = assemble(raster, frame);
        const AssembledBundle parts = assemble(*c.compute, frame);
        if (c.compute == &computeTiled) {
            EXPECT_GE(parts.stats.tiles, 9u);
        }
        const BundleDifference diff = difference(reference, parts);
        const std::size_t countDiffers = diff.countDiffers, faceDiffers = diff.faceDiffers;
        const double worstDepth = diff.worstDepth;
        std::printf("direction %d at %u^2: compute %llu fragments in %u tiles, raster %llu; %zu of %zu pixels differ "
                    "in count, %zu in faces, worst depth difference %.3g (extent %.3g)\n",
                    c.direction, c.resolution, (unsigned long long)parts.stats.fragments, parts.stats.tiles,
                    (unsigned long long)reference.stats.fragments, countDiffers, reference.lists.size(), faceDiffers,
                    worstDepth, 2.0 * b.radius());
        // lavapipe's rasterizer breaks ties as the compute backend does (top-left, the same snapped
        // vertices): identical there, fragment for fragment (a compute build that gives centres on
        // shared edges to both triangles fails it: 5-6 pixels at 320^2); a GPU's tie rule may
        // differ at a few pixels: 0.1% there.
        const bool sameTieRule = ctx().info().type == "CPU";
        const double allowed = sameTieRule ? 0.0 : 0.001 * double(reference.lists.size());
        EXPECT_LE(double(countDiffers), allowed) << "direction " << c.direction << " at " << c.resolution;
        EXPECT_LE(double(faceDiffers), allowed) << "direction " << c.direction << " at " << c.resolution;
        EXPECT_LE(worstDepth, 1e-5 * 2.0 * b.radius()) << "direction " << c.direction << " at " << c.resolution;
        if (sameTieRule) {
            EXPECT_EQ(parts.stats.fragments, reference.stats.fragments) << "direction " << c.direction;
        }
    }
}
