// A closed room's creases seen from a shadow cube (shaders/gpu/ShadowCubeLookup.glsl: 4x4 PCF with
// the receiver plane, and the crease rule). On a closed unit box (data/stress/scenes/meshes/
// dark-box.obj) the truth is exact for every point of its surface and a light anywhere: from a light
// outside, a point whose inner side faces the light is in shadow (the box is convex: the face between
// them hides it) and one whose outer side faces it is lit; from a light inside, every inner side is
// lit. Points: a grid over every face and dense bands within a few texels of every edge, where the
// receiver plane's extension over the filter's footprint leaves the box.
//
// Asserted:
//   - from outside, no inner point sees any light with the crease rule (4 x 4 or 2 x 2 taps) but
//     beside a crease whose other face the light sees from neither side (no tap can show it; the
//     rule's stated residual, counted and reported), and without the rule (the mutation) many do:
//     the points reach the case the rule exists for (one tap: no rule, the leak reported);
//   - the rule changes nothing where the filter's answer is right or errs toward shadow: the outer
//     sides from outside (convex edges) and the inner sides from inside (a lit room's creases),
//     and a convex box inside the lit room casting shadows on the room (penumbrae of an occluder
//     far from its shadow).
#include "gpu/ShadowCubePass.h"
#include "bundle/BundlePool.h"
#include "scene/SceneLoader.h"
#include "support/BoxQueries.h"
#include "support/TestFiles.h"
#include "support/VulkanTest.h"
#include "vk/BoundSet.h"
#include "vk/Buffer.h"
#include "vk/Commands.h"
#include "vk/ComputePass.h"

#include <tests/shadow_cube_visibility.comp.spv.h>

#include <cstdio>
#include <cstring>

using namespace bl;

namespace {

constexpr std::uint32_t kResolution = 64; // coarse texels: wide crease strips
constexpr std::uint32_t kGroupSize = 64;
constexpr int kGrid = 24, kAlongEdge = 48, kAcrossEdge = 16;
// The crease bands: four texels at the largest distance from the lights below (2.5), where a
// face texel spans at most 2 / kResolution of the distance.
constexpr float kBand = 4.0f * 2.5f * 2.0f / kResolution;
// Points that see the light within this cosine of their plane are left out: no caller shades them
// (the tangent cap of every crease test).
constexpr float kMinCosine = 1.0f / 12.0f;

constexpr std::uint32_t kNotAsked = 0xffffffffu;

// shaders/tests/shadow_cube_visibility.comp.glsl's push block.
struct ShadowQueryPush {
    test::BoxQueryPush box;
    std::uint32_t resolution;
    std::uint32_t taps;
    glm::vec3 light;
    float minCosine;
};
static_assert(sizeof(ShadowQueryPush) == 48, "push block of shadow_cube_visibility.comp.glsl");

// Lights off the texel lattice: from a light at short decimals a unit box's crease can run exactly
// through a row of texel centres (from (2.2, -1.3, 0.4) at 64 texels it does), where the two faces
// tie in depth and the one kept may be x's own (the rule's known residual, counted apart by
// hand: 56 points with 4 x 4 taps at these settings, all where a lit tap's texel centre ray meets
// the crease line).
const glm::vec3 kOutside[] = {{0.5137f, 2.0213f, 0.4871f}, {1.7093f, 1.9127f, -0.6041f}, {-0.8113f, 0.3079f, 1.6158f},
                              {2.2131f, -1.3049f, 0.4127f}};
const glm::vec3 kInside[] = {{0.5093f, 0.4917f, 0.5061f}, {0.2077f, 0.8133f, 0.3019f}};
constexpr glm::vec2 kInnerBox{0.35f, 0.65f}; // the occluder inside the lit room: [0.35, 0.65]^3

constexpr VkBufferUsageFlags kUsage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT |
                                      VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;

float visibility(std::uint32_t bits) {
    float v = 0.0f;
    std::memcpy(&v, &bits, sizeof(v));
    return v;
}

class ShadowCubeCrease : public test::VulkanTest {
protected:
    // The box's points with outward (`outward`) or inward normals; with `innerBox`, also the
    // points of the occluder's outer sides.
    void prepare(bool outward, bool innerBox) {
        scene = loadScene(test::sourcePath("data/stress/scenes/dark-box.toml"));
        const std::vector<test::BoxPoint> points = test::boxPoints(kGrid, kAlongEdge, kAcrossEdge, kBand);
        queries.clear();
        for (const test::BoxPoint& p : points) {
            queries.push_back({glm::vec4(p.position, 1.0f), glm::vec4((outward ? 1.0f : -1.0f) * p.outward, 0.0f)});
        }
        if (innerBox) {
            Mesh inner = scene.meshes.front();
            for (glm::vec3& p : inner.positions) p = kInnerBox.x + (kInnerBox.y - kInnerBox.x) * p;
            scene.meshes.push_back(inner);
            for (const test::BoxPoint& p : points) {
                queries.push_back({glm::vec4(kInnerBox.x + (kInnerBox.y - kInnerBox.x) * p.position, 1.0f),
                                   glm::vec4(p.outward, 0.0f)});
            }
        }
        queryBuffer = vk::Buffer(ctx(), queries.size() * sizeof(test::BoxQuery), kUsage, vk::MemoryUse::Device);
        queryBuffer.upload(ctx(), queries.data(), queries.size() * sizeof(test::BoxQuery));
        resultBuffer = vk::Buffer(ctx(), queries.size() * sizeof(std::uint32_t), kUsage, vk::MemoryUse::Device);
    }

    // Per query the visibility of `light` (kNotAsked where the query's side does not face it), with
    // the crease rule ([0]) and without ([1]), from a cube of kResolution filtered by taps x taps.
    std::array<std::vector<std::uint32_t>, 2> lookup(const glm::vec3& light, std::uint32_t taps) {
        gpu::GpuScene gpuScene(ctx(), scene);
        gpu::ShadowCubePass cubes = gpu::ShadowCubePass::forPositions(ctx(), gpuScene, kResolution, 1);
        vk::BoundSet bound(ctx().device(), {vk::Bound::storageImage(0, cubes.maps().view())});
        vk::ComputePass<ShadowQueryPush> pass(ctx().device(), kSpv_tests_shadow_cube_visibility_comp, {bound.layout()});
        std::array<std::vector<std::uint32_t>, 2> out;
        for (std::uint32_t withoutRule = 0; withoutRule < 2; ++withoutRule) {
            ShadowQueryPush push{};
            push.box.queries = splitAddress(deviceAddress(ctx(), queryBuffer));
            push.box.results = splitAddress(deviceAddress(ctx(), resultBuffer));
            push.box.count = static_cast<std::uint32_t>(queries.size());
            push.box.centreOnly = withoutRule;
            push.resolution = kResolution;
            push.taps = taps;
            push.light = light;
            push.minCosine = kMinCosine;
            const VkDescriptorSet sets[] = {bound.set()};
            ctx().submitAndWait([&](VkCommandBuffer cmd) {
                if (withoutRule == 0) {
                    cubes.record(cmd, light, 0, 0.0, nullptr);
                    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                                      VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
                }
                pass.dispatch(cmd, push, vk::groupCount(push.box.count, kGroupSize), sets);
                vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_2_TRANSFER_BIT);
            });
            out[withoutRule].resize(queries.size());
            resultBuffer.download(ctx(), out[withoutRule].data(), out[withoutRule].size() * sizeof(std::uint32_t));
        }
        return out;
    }

    Scene scene;
    std::vector<test::BoxQuery> queries;
    vk::Buffer queryBuffer, resultBuffer;
};

} // namespace

// Whether inner point `x` (on the face whose outward normal is `outward`) lies within the band of an
// edge whose other face has `light` on its inner side: the light sees that face from neither side (a
// third face hides it), so no tap can show the crease, and the rule's planes are those of faces
// whose creases with x's face lie elsewhere.
bool nearAnUnseenCrease(const glm::vec3& x, const glm::vec3& outward, const glm::vec3& light) {
    for (int b = 0; b < 3; ++b) {
        if (outward[b] != 0.0f) continue;
        for (int t = 0; t < 2; ++t) {
            const bool inBand = std::abs(x[b] - float(t)) <= kBand;
            const bool lightInside = t == 0 ? light[b] > 0.0f : light[b] < 1.0f;
            if (inBand && lightInside) return true;
        }
    }
    return false;
}

TEST_F(ShadowCubeCrease, ClosedBoxStaysDarkFromALightOutside) {
    prepare(false, false);
    for (std::uint32_t taps : {4u, 2u, 1u}) {
        std::size_t asked = 0, leaked[2] = {0, 0}, unseen = 0;
        float worst = 0.0f;
        for (const glm::vec3& light : kOutside) {
            const auto answers = lookup(light, taps);
            for (std::size_t i = 0; i < queries.size(); ++i) {
                if (answers[0][i] == kNotAsked) continue;
                ++asked;
                for (int c = 0; c < 2; ++c) leaked[c] += visibility(answers[c][i]) > 0.0f ? 1 : 0;
                if (visibility(answers[0][i]) > 0.0f &&
                    nearAnUnseenCrease(queries[i].position, -glm::vec3(queries[i].normal), light)) {
                    ++unseen;
                    worst = std::max(worst, visibility(answers[0][i]));
                }
            }
        }
        std::printf("%u tap(s) a side: %zu inner points facing a light outside; %zu see light with the crease rule "
                    "(%zu beside a crease no tap can show, at most %.4f), %zu without it\n",
                    taps, asked, leaked[0], unseen, worst, leaked[1]);
        if (taps == 1) {
            // A one-tap filter has no footprint and keeps its leak (ShadowCubeLookup.glsl, "The
            // crease rule": the cost of judging it on a SIMD CPU driver): reported, and the rule
            // must leave it as it is.
            EXPECT_EQ(leaked[0], leaked[1]) << "one tap: the rule runs on multi-tap filters only";
            continue;
        }
        EXPECT_EQ(leaked[0] - unseen, 0u) << taps << " tap(s): inner points that see a light outside the closed box";
        // The exemption covers the rule's stated residual only: a classifier that excused every
        // leak would pass the line above (56 of 13,912 with 4 x 4 taps at these settings, 0 of 4,961
        // with 2 x 2).
        EXPECT_LE(unseen, leaked[1] / 100) << taps << " tap(s): the unseen-crease exemption covers too much";
        EXPECT_GT(leaked[1], asked / 100) << taps << " tap(s): without the rule the points must reach the leak";
    }
}

TEST_F(ShadowCubeCrease, RuleLeavesLitSidesAndPenumbraeAsTheFilterHasThem) {
    struct Case {
        const char* what;
        bool outward, innerBox;
        std::vector<glm::vec3> lights;
    };
    const Case cases[] = {
        {"outer sides, light outside", true, false, {std::begin(kOutside), std::end(kOutside)}},
        {"inner sides, light inside", false, false, {std::begin(kInside), std::end(kInside)}},
        {"room and occluder, light inside", false, true, {std::begin(kInside), std::end(kInside)}},
    };
    for (const Case& c : cases) {
        prepare(c.outward, c.innerBox);
        for (std::uint32_t taps : {4u, 2u}) { // the filters the rule runs on
            std::size_t asked = 0, changed = 0, partial = 0;
            for (const glm::vec3& light : c.lights) {
                const auto answers = lookup(light, taps);
                for (std::size_t i = 0; i < queries.size(); ++i) {
                    if (answers[0][i] == kNotAsked) continue;
                    ++asked;
                    changed += answers[0][i] != answers[1][i] ? 1 : 0;
                    if (answers[0][i] != answers[1][i] && changed < 12) {
                        std::printf("changed %.4f -> %.4f at (%.4f %.4f %.4f) n (%.0f %.0f %.0f), light (%.1f %.1f %.1f)\n",
                                    visibility(answers[1][i]), visibility(answers[0][i]), queries[i].position.x,
                                    queries[i].position.y, queries[i].position.z, queries[i].normal.x,
                                    queries[i].normal.y, queries[i].normal.z, light.x, light.y, light.z);
                    }
                    const float v = visibility(answers[1][i]);
                    partial += v > 0.0f && v < 1.0f ? 1 : 0;
                }
            }
            std::printf("%s, %u tap(s) a side: %zu points, %zu in penumbra, %zu changed by the crease rule\n", c.what,
                        taps, asked, partial, changed);
            EXPECT_EQ(changed, 0u) << c.what << ", " << taps << " tap(s)";
            if (c.innerBox && taps > 1) {
                EXPECT_GT(partial, asked / 100) << c.what << ": the occluder must cast penumbrae the rule could touch";
            }
        }
    }
}
