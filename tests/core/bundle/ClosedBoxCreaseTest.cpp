// A closed room's creases, for the two ways a point looks along a global direction omega: the depth
// maps' visibility (shaders/bundle/DepthMapVisibility.glsl: skylight's depth_map, the environment
// directions of raster, multibounce and atlas) and the bundle walk of the path-tracing modes
// (shaders/bundle/Traversal.glsl, blBundleSurfaceNearestAcrossCreases: multibounce, bidir). On a
// closed unit box (data/stress/scenes/meshes/dark-box.obj) the truth is exact for every point of
// its surface and every travel direction d (+omega toward a map's light; the side of +-omega on the
// point's normal for a walk): from the outer side nothing is ahead (the box is convex), from the
// inner side the face the ray leaves the box through is, however close to a crease.
//
// Tolerance, derived: both count a surface from blBundleSurfaceEpsilon past x's own plane, so an
// inner point whose ray leaves the box within that distance may miss it; and the contact taps can
// only use what the centres of x's 2x2 footprint show, so an inner point may miss the face that
// hides it where no centre line of its footprint crosses that face within the taps' reach (the
// face seen nearly edge-on, the corner where three outlines meet). Every other inner point must
// find it; no outer point may find anything. Points are placed on a grid over every face and
// densely within two pixels of every edge, where a point's own centre ray can pass outside the box.
// Directions within 1 / kBundleMaxOwnSurfaceTangent of a face's plane are left out (the tolerance's
// tangent is capped there: the convention of every bundle test).
//
// Mutation: x's own pixel alone (the rule before the contact taps) must miss the hiding face where
// the footprint shows it, at many points, so the box and its points reach the case the taps exist
// for.
//
// Reported, not asserted: walks that find a plane beyond the face ahead (the next vertex would lie
// outside the box). Measured at these settings: 12 371 of 0.98 M rays into the box with the own
// pixel alone, 1 361 with the taps at both ends of the segment; of those, 59 with the face ahead in
// the footprint and itself not grazing: near the box's corners, where three outlines meet (the far
// end's rule sees one crease at a time), or with another face seen within the tangent cap of omega
// (its plane's crossing is capped, so the hit found on it lies nowhere real).
#include "bundle/BundleFrame.h"
#include "bundle/BundlePool.h"
#include "bundle/DepthMapPass.h"
#include "bundle/DirectionSampler.h"
#include "scene/SceneLoader.h"
#include "support/TestFiles.h"
#include "support/VulkanTest.h"
#include "vk/BoundSet.h"
#include "vk/Buffer.h"
#include "vk/Commands.h"
#include "vk/ComputePass.h"

#include <shared/BundleTypes.h>
#include <tests/bundle_crease.comp.spv.h>
#include <tests/depth_map_visibility.comp.spv.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

using namespace bl;

namespace {

constexpr std::uint32_t kResolution = 64; // coarse map pixels: wide crease strips
constexpr std::uint32_t kDirections = 48;
constexpr std::uint32_t kGroupSize = 64;
constexpr int kGrid = 24;          // grid points per face side
constexpr int kAlongEdge = 48;     // edge points per edge
constexpr int kAcrossEdge = 16;    // edge points within two map pixels of the edge

struct Query {
    glm::vec4 position;
    glm::vec4 normal;
};

struct VisibilityPush {
    glm::uvec2 queries;
    glm::uvec2 results;
    std::uint32_t count;
    std::uint32_t centreOnly;
};

struct CreasePush {
    shader::BundlePoolView pool;
    glm::uvec2 queries;
    glm::uvec2 results;
    std::uint32_t count;
    std::uint32_t centreOnly;
};
static_assert(sizeof(CreasePush) == 88, "push block of bundle_crease.comp.glsl");

struct BoxPoint {
    glm::vec3 position;
    glm::vec3 outward;
};

// Points on the unit box's faces: a grid, and points within `band` of every edge.
std::vector<BoxPoint> boxPoints(float band) {
    std::vector<BoxPoint> points;
    for (int axis = 0; axis < 3; ++axis) {
        for (int side = 0; side < 2; ++side) {
            const int u = (axis + 1) % 3, v = (axis + 2) % 3;
            auto add = [&](float a, float b) {
                glm::vec3 p(0.0f), n(0.0f);
                p[axis] = float(side);
                p[u] = a;
                p[v] = b;
                n[axis] = side == 0 ? -1.0f : 1.0f;
                points.push_back({p, n});
            };
            for (int i = 0; i < kGrid; ++i) {
                for (int j = 0; j < kGrid; ++j) add((i + 0.5f) / kGrid, (j + 0.5f) / kGrid);
            }
            for (int i = 0; i < kAlongEdge; ++i) {
                const float along = (i + 0.37f) / kAlongEdge;
                for (int j = 0; j < kAcrossEdge; ++j) {
                    const float across = band * (j + 0.5f) / kAcrossEdge;
                    add(across, along);
                    add(1.0f - across, along);
                    add(along, across);
                    add(along, 1.0f - across);
                }
            }
        }
    }
    return points;
}

// blBundleSurfaceEpsilon (shaders/bundle/Traversal.glsl) on the host.
float surfaceEpsilon(const shader::BundleFrame& frame, float cosine) {
    const float c = std::max(std::abs(cosine), 1.0f / shader::kBundleMaxOwnSurfaceTangent);
    const float tangent = std::min(std::sqrt(std::max(0.0f, 1.0f - c * c)) / c, shader::kBundleMaxOwnSurfaceTangent);
    return frame.depthEpsilon / c + frame.pixelSize * tangent / shader::kBundleSubpixelGrid;
}

// The face of the unit box (axis * 2 + side) that x's ray along omega leaves it through, and the
// distance along omega.
int exitFace(const glm::vec3& x, const glm::vec3& omega, float& distance) {
    distance = std::numeric_limits<float>::max();
    int face = -1;
    for (int a = 0; a < 3; ++a) {
        const float t = omega[a] > 0.0f ? (1.0f - x[a]) / omega[a] : omega[a] < 0.0f ? -x[a] / omega[a] : distance;
        if (t < distance) {
            distance = t;
            face = 2 * a + (omega[a] > 0.0f ? 1 : 0);
        }
    }
    return face;
}

// Whether the line o + t omega crosses face `face` (axis * 2 + side) of the unit box.
bool lineCrossesFace(const glm::vec3& o, const glm::vec3& omega, int face) {
    const int axis = face / 2;
    if (omega[axis] == 0.0f) return false;
    const glm::vec3 p = o + ((face % 2 == 1 ? 1.0f : 0.0f) - o[axis]) / omega[axis] * omega;
    for (int a = 0; a < 3; ++a) {
        if (a != axis && (p[a] < 0.0f || p[a] > 1.0f)) return false;
    }
    return true;
}

// Whether x's footprint (its pixel and the three taps of bundle/Traversal.glsl) shows the face
// x's ray leaves through as the contact taps can use it: on one of the four centre lines, its plane
// meeting x's within the taps' reach. `ambiguous`: x lies too near a pixel's edge or centre line,
// or the contact too near the reach, for the host's answer to be sure to be the GPU's.
bool footprintShowsExit(const shader::BundleFrame& frame, const glm::vec3& x, const glm::vec3& outward, int exit,
                        float cosine, bool& ambiguous) {
    const glm::vec3 rel = x - frame.origin;
    const glm::vec2 g(glm::dot(rel, frame.axisX) / frame.pixelSize, glm::dot(rel, frame.axisY) / frame.pixelSize);
    const glm::vec2 f = g - glm::floor(g);
    ambiguous = false;
    for (int a = 0; a < 2; ++a) {
        ambiguous = ambiguous || f[a] < 1e-3f || f[a] > 1.0f - 1e-3f || std::abs(f[a] - 0.5f) < 1e-3f;
    }
    // Parallel faces never meet; adjacent ones meet at their shared edge, whose distance from x is
    // x's distance from the exit face's plane.
    const int axis = exit / 2;
    if (outward[axis] != 0.0f) return false;
    const float contact = exit % 2 == 1 ? 1.0f - x[axis] : x[axis];
    const float reach = std::sqrt(2.0f) * frame.pixelSize *
                        std::min(1.0f / std::abs(cosine), shader::kBundleMaxOwnSurfaceTangent);
    ambiguous = ambiguous || std::abs(contact - reach) < 0.01f * reach;
    if (contact > reach) return false;
    const glm::ivec2 pixel(glm::floor(g));
    const glm::ivec2 step(f.x < 0.5f ? -1 : 1, f.y < 0.5f ? -1 : 1);
    for (const glm::ivec2& c : {pixel, pixel + glm::ivec2(step.x, 0), pixel + glm::ivec2(0, step.y), pixel + step}) {
        const glm::vec3 o = frame.origin + (float(c.x) + 0.5f) * frame.pixelSize * frame.axisX +
                            (float(c.y) + 0.5f) * frame.pixelSize * frame.axisY;
        if (lineCrossesFace(o, frame.direction, exit)) return true;
    }
    return false;
}

// Whether one of the centre lines of x's footprint crosses face `face`.
bool footprintCrossesExit(const shader::BundleFrame& frame, const glm::vec3& x, int face) {
    const glm::vec3 rel = x - frame.origin;
    const glm::vec2 g(glm::dot(rel, frame.axisX) / frame.pixelSize, glm::dot(rel, frame.axisY) / frame.pixelSize);
    const glm::vec2 f = g - glm::floor(g);
    const glm::ivec2 pixel(glm::floor(g));
    const glm::ivec2 step(f.x < 0.5f ? -1 : 1, f.y < 0.5f ? -1 : 1);
    for (const glm::ivec2& c : {pixel, pixel + glm::ivec2(step.x, 0), pixel + glm::ivec2(0, step.y), pixel + step}) {
        const glm::vec3 o = frame.origin + (float(c.x) + 0.5f) * frame.pixelSize * frame.axisX +
                            (float(c.y) + 0.5f) * frame.pixelSize * frame.axisY;
        if (lineCrossesFace(o, frame.direction, face)) return true;
    }
    return false;
}

// Counts over every (point, direction) of one side.
struct Counts {
    std::size_t queries = 0, missed = 0, unexplained = 0, overshoot = 0, overshootShown = 0;
};

// Judges one direction's answers (1: something ahead, 0: nothing) to queries along travel
// directions d = sign(normal . omega) omega (a map's light: the normals all outward, d = +omega
// for every one by `towardOmega`): `inner` counts the rays into the box (missed: nothing found
// beyond the tolerance; unexplained: missed although the footprint shows the face), `outer` the
// rays away from it (unexplained: something found).
void judge(const shader::BundleFrame& frame, const std::vector<Query>& queries, const std::vector<BoxPoint>& points,
           const std::vector<std::uint32_t>& results, bool towardOmega, Counts& inner, Counts& outer) {
    for (std::size_t i = 0; i < queries.size(); ++i) {
        const BoxPoint& p = points[i % points.size()];
        const float cosine = glm::dot(p.outward, frame.direction);
        if (std::abs(cosine) < 1.0f / shader::kBundleMaxOwnSurfaceTangent) continue;
        ASSERT_NE(results[i], 2u) << "the frame covers the scene's bounding sphere";
        const float side = towardOmega ? 1.0f : (glm::dot(glm::vec3(queries[i].normal), frame.direction) >= 0.0f ? 1.0f : -1.0f);
        const glm::vec3 d = side * frame.direction;
        if (glm::dot(d, p.outward) > 0.0f) {
            ++outer.queries;
            outer.unexplained += results[i] == 1u ? 1 : 0;
            continue;
        }
        ++inner.queries;
        float distance = 0.0f;
        const int exit = exitFace(p.position, d, distance);
        if (!towardOmega && results[i] == 1u) {
            float found = 0.0f;
            std::memcpy(&found, &results[queries.size() + i], sizeof(found));
            // Beyond the face ahead: the next vertex would lie outside the box (reported). Where
            // that face is seen within the tolerance's cap of its plane, the taps' reach is capped.
            if (found > distance + surfaceEpsilon(frame, cosine) + 1e-5f * distance) {
                ++inner.overshoot;
                const bool grazing = std::abs(frame.direction[exit / 2]) < 1.0f / shader::kBundleMaxOwnSurfaceTangent;
                inner.overshootShown += !grazing && footprintCrossesExit(frame, p.position, exit) ? 1 : 0;
            }
        }
        if (results[i] != 0u || distance <= surfaceEpsilon(frame, cosine)) continue;
        ++inner.missed;
        bool ambiguous = false;
        const bool shown = footprintShowsExit(frame, p.position, p.outward, exit, cosine, ambiguous);
        inner.unexplained += shown && !ambiguous ? 1 : 0;
    }
}

void report(const char* what, const Counts inner[2], const Counts outer[2]) {
    for (int c = 0; c < 2; ++c) {
        std::printf("%s, %s: into the box %zu rays, %zu find nothing beyond the tolerance, %zu of them where the "
                    "footprint shows the face ahead; %zu found something beyond it (%zu with the face in the footprint, not grazing); out of it "
                    "%zu rays, %zu find something\n",
                    what, c == 0 ? "with the contact taps" : "own pixel alone", inner[c].queries, inner[c].missed,
                    inner[c].unexplained, inner[c].overshoot, inner[c].overshootShown, outer[c].queries, outer[c].unexplained);
    }
}

constexpr VkBufferUsageFlags kUsage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT |
                                      VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;

class ClosedBoxCrease : public test::VulkanTest {
protected:
    // The box, its points and their queries with `normals` (outward; with `bothSides` also inward,
    // after them), and the buffers the shaders read and write.
    void prepare(bool bothSides) {
        scene = loadScene(test::sourcePath("data/stress/scenes/dark-box.toml"));
        bounds = scene.bounds();
        points = boxPoints(2.0f * 2.0f * bounds.radius() / kResolution);
        queries.clear();
        for (const BoxPoint& p : points) queries.push_back({glm::vec4(p.position, 1.0f), glm::vec4(p.outward, 0.0f)});
        if (bothSides) {
            for (const BoxPoint& p : points) queries.push_back({glm::vec4(p.position, 1.0f), glm::vec4(-p.outward, 0.0f)});
        }
        queryBuffer = vk::Buffer(ctx(), queries.size() * sizeof(Query), kUsage, vk::MemoryUse::Device);
        queryBuffer.upload(ctx(), queries.data(), queries.size() * sizeof(Query));
        resultBuffer = vk::Buffer(ctx(), 2 * queries.size() * sizeof(std::uint32_t), kUsage, vk::MemoryUse::Device);
    }

    // Per query its answer, then (walks) the distance to what it found, as float bits.
    std::vector<std::uint32_t> results() {
        std::vector<std::uint32_t> out(2 * queries.size());
        resultBuffer.download(ctx(), out.data(), out.size() * sizeof(std::uint32_t));
        return out;
    }

    // The query pass's push addresses, count and variant.
    template <typename Push>
    void address(Push& push, std::uint32_t centreOnly) {
        push.queries = splitAddress(deviceAddress(ctx(), queryBuffer));
        push.results = splitAddress(deviceAddress(ctx(), resultBuffer));
        push.count = static_cast<std::uint32_t>(queries.size());
        push.centreOnly = centreOnly;
    }

    // Records `record` (the query pass) in one submission and returns the answers.
    template <typename Record>
    std::vector<std::uint32_t> answer(Record record) {
        ctx().submitAndWait([&](VkCommandBuffer cmd) {
            record(cmd);
            vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_2_TRANSFER_BIT);
        });
        return results();
    }

    // Both tests' checks ([0]: with the taps, [1]: x's own pixel alone), after printing the counts.
    static void expectCreasesHold(const char* what, const Counts inner[2], const Counts outer[2]) {
        report(what, inner, outer);
        EXPECT_EQ(inner[0].unexplained, 0u) << what << ": rays into the closed box that miss the face ahead where "
                                                       "the footprint shows it";
        EXPECT_EQ(outer[0].unexplained, 0u) << what << ": rays out of the convex box that find it ahead";
        EXPECT_GT(inner[1].unexplained, inner[1].queries / 100)
            << what << ": x's own pixel alone must miss where the taps close the box, or the points miss the creases";
    }

    shader::BundleFrame frameFor(std::uint32_t k) {
        const BundleDirection d = sampler.sample(k);
        return bundleFrameForSphere(d.omega, d.rotation, bounds.center(), bounds.radius(), kResolution);
    }

    Scene scene;
    Bounds bounds;
    std::vector<BoxPoint> points;
    std::vector<Query> queries;
    vk::Buffer queryBuffer, resultBuffer;
    DirectionSampler sampler{DirectionSequence::Random, 7};
};

} // namespace

TEST_F(ClosedBoxCrease, DepthMapHidesTheInsideAndShowsTheOutside) {
    prepare(false);
    gpu::GpuScene gpuScene(ctx(), scene);
    DepthMapPass pass(ctx(), gpuScene, kResolution);
    vk::Buffer frameBuffer(ctx(), sizeof(shader::BundleFrame), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, vk::MemoryUse::Upload);
    vk::BoundSet bound(ctx().device(), {vk::Bound::storageImage(0, pass.map().view()),
                                        vk::Bound::uniformBuffer(1, frameBuffer.get())});
    vk::ComputePass<VisibilityPush> visibility(ctx().device(), kSpv_tests_depth_map_visibility_comp, {bound.layout()});
    Counts inner[2], outer[2]; // [0]: with the taps, [1]: the centre alone
    for (std::uint32_t k = 0; k < kDirections; ++k) {
        const shader::BundleFrame frame = frameFor(k);
        std::memcpy(frameBuffer.data(), &frame, sizeof(frame));
        for (std::uint32_t centreOnly = 0; centreOnly < 2; ++centreOnly) {
            VisibilityPush push{};
            address(push, centreOnly);
            const VkDescriptorSet sets[] = {bound.set()};
            const std::vector<std::uint32_t> answers = answer([&](VkCommandBuffer cmd) {
                if (centreOnly == 0) {
                    pass.record(cmd, frame, 0.0, nullptr);
                    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                                      VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
                }
                visibility.dispatch(cmd, push, vk::groupCount(push.count, kGroupSize), sets);
            });
            judge(frame, queries, points, answers, true, inner[centreOnly], outer[centreOnly]);
        }
    }
    expectCreasesHold("depth map", inner, outer);
}

TEST_F(ClosedBoxCrease, BundleWalkFindsTheWallAheadInsideAndNothingOutside) {
    prepare(true);
    gpu::GpuScene gpuScene(ctx(), scene);
    BundlePoolOptions options;
    options.slotPixels = kResolution * kResolution;
    options.payload = BundlePayload::Hit;
    BundlePool pool(ctx(), gpuScene, options);
    vk::ComputePass<CreasePush> walk(ctx().device(), kSpv_tests_bundle_crease_comp);
    Counts inner[2], outer[2]; // [0]: with the taps, [1]: the own pixel alone
    for (std::uint32_t k = 0; k < kDirections; ++k) {
        const shader::BundleFrame frame = frameFor(k);
        ctx().submitAndWait([&](VkCommandBuffer cmd) {
            pool.recordReset(cmd);
            pool.recordBuild(cmd, 0, frame, BundleGeometry::triangles(0.0));
        });
        ASSERT_FALSE(pool.status().overflowed());
        for (std::uint32_t centreOnly = 0; centreOnly < 2; ++centreOnly) {
            CreasePush push{};
            push.pool = pool.view();
            address(push, centreOnly);
            const std::vector<std::uint32_t> answers = answer(
                [&](VkCommandBuffer cmd) { walk.dispatch(cmd, push, vk::groupCount(push.count, kGroupSize)); });
            judge(frame, queries, points, answers, false, inner[centreOnly], outer[centreOnly]);
        }
    }
    expectCreasesHold("bundle walk", inner, outer);
}
