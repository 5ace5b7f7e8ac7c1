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
// inner point whose ray leaves the box within that distance may miss it; x's own centre line shows
// the face ahead where it crosses it ahead of x's plane beyond that tolerance; and the contact taps
// can only use what the other centres of x's 2x2 footprint show, where the face's plane meets x's
// within the taps' reach. So an inner point may miss the face that hides it where its footprint
// shows that face neither way (the face seen nearly edge-on, the corner where three outlines meet).
// Every other inner point must find it; no outer point may find anything. Points are placed on a grid over every face and
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
#include "support/BoxQueries.h"
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
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>

using namespace bl;

namespace {

constexpr std::uint32_t kResolution = 64; // coarse map pixels: wide crease strips
constexpr std::uint32_t kDirections = 48;
constexpr std::uint32_t kGroupSize = 64;
constexpr int kGrid = 24;          // grid points per face side
constexpr int kAlongEdge = 48;     // edge points per edge
constexpr int kAcrossEdge = 16;    // edge points within two map pixels of the edge
constexpr glm::vec2 kInnerBox{0.35f, 0.65f}; // the convex box inside the room: [0.35, 0.65]^3

using test::BoxPoint;
using test::BoxQueryPush;
using Query = test::BoxQuery;

struct CreasePush {
    shader::BundlePoolView pool;
    BoxQueryPush box;
};
static_assert(sizeof(CreasePush) == 88, "push block of bundle_crease.comp.glsl");

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

// The centre lines' origins of x's footprint: its own pixel's first, then the three taps of
// bundle/Traversal.glsl (blBundleContactTaps). `ambiguous`: x lies too near a pixel's edge or centre
// line for the host's choice to be sure to be the GPU's.
std::array<glm::vec3, 4> footprintCentres(const shader::BundleFrame& frame, const glm::vec3& x, bool& ambiguous) {
    const glm::vec3 rel = x - frame.origin;
    const glm::vec2 g(glm::dot(rel, frame.axisX) / frame.pixelSize, glm::dot(rel, frame.axisY) / frame.pixelSize);
    const glm::vec2 f = g - glm::floor(g);
    ambiguous = false;
    for (int a = 0; a < 2; ++a) {
        ambiguous = ambiguous || f[a] < 1e-3f || f[a] > 1.0f - 1e-3f || std::abs(f[a] - 0.5f) < 1e-3f;
    }
    const glm::ivec2 pixel(glm::floor(g));
    const glm::ivec2 step(f.x < 0.5f ? -1 : 1, f.y < 0.5f ? -1 : 1);
    const glm::ivec2 pixels[4] = {pixel, pixel + glm::ivec2(step.x, 0), pixel + glm::ivec2(0, step.y), pixel + step};
    std::array<glm::vec3, 4> out;
    for (int i = 0; i < 4; ++i) {
        out[i] = frame.origin + (float(pixels[i].x) + 0.5f) * frame.pixelSize * frame.axisX +
                 (float(pixels[i].y) + 0.5f) * frame.pixelSize * frame.axisY;
    }
    return out;
}

// Whether x's footprint shows the face x's ray leaves through (`exit`) as the map (`walk` false) or
// the walk can use it: on x's own centre line (at a point ahead of x's plane beyond the tolerance
// `epsilon`, along the normal), or on a tap's centre line with the face's plane meeting x's near
// enough (rule (c) of each). `ambiguous`: too near a pixel's edge or centre line, the footprint's limit or the
// tolerance for the host's answer to be sure to be the GPU's.
bool footprintShowsExit(const shader::BundleFrame& frame, const glm::vec3& x, const glm::vec3& outward, int exit,
                        float epsilon, float cosine, bool walk, bool& ambiguous) {
    const std::array<glm::vec3, 4> centres = footprintCentres(frame, x, ambiguous);
    const int axis = exit / 2, own = std::abs(outward[0]) > 0.5f ? 0 : std::abs(outward[1]) > 0.5f ? 1 : 2;
    if (lineCrossesFace(centres[0], frame.direction, exit)) {
        // Where the own centre line meets the face, ahead of x's plane by...
        const glm::vec3 o = centres[0];
        const float t = ((exit % 2 == 1 ? 1.0f : 0.0f) - o[axis]) / frame.direction[axis];
        const float ahead = std::abs((o + t * frame.direction)[own] - x[own]);
        ambiguous = ambiguous || std::abs(ahead - epsilon) < epsilon + 1e-5f;
        if (ahead > epsilon) return true;
    }
    // Parallel faces never meet; adjacent ones meet at their shared edge. x's distance to it runs
    // along the exit face's axis, the tap's point's along x's face's. Visibility
    // (blBundleContactNearX): within sqrt(2) px / |cos| of x, tangent capped. Walks
    // (blBundleContactNearBoth): within sqrt(2) px of both, in projection; and no face seen within
    // the tangent cap of its plane.
    if (outward[axis] != 0.0f) return false;
    if (walk && std::abs(frame.direction[axis]) * shader::kBundleMaxOwnSurfaceTangent < 1.0f) return false;
    const float limit = std::sqrt(2.0f) * frame.pixelSize;
    auto projected = [&](float distance, int along) {
        return distance * std::sqrt(std::max(0.0f, 1.0f - frame.direction[along] * frame.direction[along]));
    };
    const float contact = exit % 2 == 1 ? 1.0f - x[axis] : x[axis];
    const float toEdge = walk ? projected(contact, axis) : contact;
    const float reach = walk ? limit : limit * std::min(1.0f / std::abs(cosine), shader::kBundleMaxOwnSurfaceTangent);
    ambiguous = ambiguous || std::abs(toEdge - reach) < 0.01f * reach;
    if (toEdge > reach) return false;
    for (int i = 1; i < 4; ++i) {
        if (!lineCrossesFace(centres[i], frame.direction, exit)) continue;
        const glm::vec3 o = centres[i];
        const glm::vec3 onFace = o + ((exit % 2 == 1 ? 1.0f : 0.0f) - o[axis]) / frame.direction[axis] * frame.direction;
        // Rule (a): the tap's point must lie ahead of x's plane beyond the tolerance.
        const float tapAhead = std::abs(onFace[own] - x[own]);
        ambiguous = ambiguous || std::abs(tapAhead - epsilon) < epsilon + 1e-5f;
        if (tapAhead <= epsilon) continue;
        if (!walk) return true;
        const float pointToEdge = projected(tapAhead, own);
        ambiguous = ambiguous || std::abs(pointToEdge - limit) < 0.01f * limit;
        if (pointToEdge <= limit) return true;
    }
    return false;
}

// Whether one of the centre lines of x's footprint crosses face `face`.
bool footprintCrossesExit(const shader::BundleFrame& frame, const glm::vec3& x, int face) {
    bool unused = false;
    for (const glm::vec3& o : footprintCentres(frame, x, unused)) {
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
        const float epsilon = surfaceEpsilon(frame, cosine) * std::abs(cosine); // along the normal
        const bool shown = footprintShowsExit(frame, p.position, p.outward, exit, epsilon, cosine, !towardOmega, ambiguous);
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
    // The box (with `innerBox`: and a box of a third its size at its centre, kInnerBox), its points
    // and their queries with outward normals (`outward`), inward ones (`inward`, after them), and the
    // buffers the shaders read and write.
    void prepare(bool outward, bool inward, bool innerBox = false) {
        scene = loadScene(test::sourcePath("data/stress/scenes/dark-box.toml"));
        if (innerBox) {
            Mesh inner = scene.meshes.front();
            for (glm::vec3& p : inner.positions) p = kInnerBox.x + (kInnerBox.y - kInnerBox.x) * p;
            scene.meshes.push_back(inner);
        }
        bounds = scene.bounds();
        points = test::boxPoints(kGrid, kAlongEdge, kAcrossEdge, 2.0f * 2.0f * bounds.radius() / kResolution);
        queries.clear();
        for (int side = 0; side < 2; ++side) {
            if (side == 0 ? !outward : !inward) continue;
            const float sign = side == 0 ? 1.0f : -1.0f;
            for (const BoxPoint& p : points) queries.push_back({glm::vec4(p.position, 1.0f), glm::vec4(sign * p.outward, 0.0f)});
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
    void address(BoxQueryPush& push, std::uint32_t centreOnly) {
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

    // Builds a bundle of the scene per direction and runs the walk from every query, with the taps
    // (centreOnly 0) and x's own pixel alone (1), handing each answer set to `judge`.
    template <typename Judge>
    void walk(Judge judge) {
        gpu::GpuScene gpuScene(ctx(), scene);
        BundlePoolOptions options;
        options.slotPixels = kResolution * kResolution;
        options.payload = BundlePayload::Hit;
        BundlePool pool(ctx(), gpuScene, options);
        vk::ComputePass<CreasePush> pass(ctx().device(), kSpv_tests_bundle_crease_comp);
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
                address(push.box, centreOnly);
                judge(frame, centreOnly, answer([&](VkCommandBuffer cmd) {
                          pass.dispatch(cmd, push, vk::groupCount(push.box.count, kGroupSize));
                      }));
            }
        }
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
    prepare(true, false);
    gpu::GpuScene gpuScene(ctx(), scene);
    DepthMapPass pass(ctx(), gpuScene, kResolution);
    vk::Buffer frameBuffer(ctx(), sizeof(shader::BundleFrame), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, vk::MemoryUse::Upload);
    vk::BoundSet bound(ctx().device(), {vk::Bound::storageImage(0, pass.map().view()),
                                        vk::Bound::uniformBuffer(1, frameBuffer.get())});
    vk::ComputePass<BoxQueryPush> visibility(ctx().device(), kSpv_tests_depth_map_visibility_comp, {bound.layout()});
    Counts inner[2], outer[2]; // [0]: with the taps, [1]: the centre alone
    for (std::uint32_t k = 0; k < kDirections; ++k) {
        const shader::BundleFrame frame = frameFor(k);
        std::memcpy(frameBuffer.data(), &frame, sizeof(frame));
        for (std::uint32_t centreOnly = 0; centreOnly < 2; ++centreOnly) {
            BoxQueryPush push{};
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
    prepare(true, true);
    Counts inner[2], outer[2]; // [0]: with the taps, [1]: the own pixel alone
    walk([&](const shader::BundleFrame& frame, std::uint32_t centreOnly, const std::vector<std::uint32_t>& answers) {
        judge(frame, queries, points, answers, false, inner[centreOnly], outer[centreOnly]);
    });
    expectCreasesHold("bundle walk", inner, outer);
}

// The taps beside a convex box: a box inside the room, rays from the room's walls. Where x's ray
// lands on the inner box's face just inside a convex edge, a tap shows the box's other face, whose
// plane x's ray crosses first, in the air: the far end's rule must not take it (the tap's surface
// lies behind the found plane, not on x's side). Where x's ray passes the box, a tap can show a
// face whose plane meets the floor or the ceiling near x or near the hit: (c) must not take it
// (the face itself stays far from that line). The own pixel alone has its own such phantom hits
// (the bundle-resolution bias at outlines); the taps must add none: a walk that lands short of the
// first surface (beyond the tolerance) with the taps must do so with the own pixel alone too.
// Directions that see a face of the inner box within twice the tangent cap of its plane are left
// out of that count (reported): there the face, nearly along omega, crosses the footprint's depth
// in a fraction of a pixel, and a gap of a third of the room between it and the ceiling shrinks to
// about one pixel in projection. Mutations: the far end's side rule dropped adds 5 262 such hits
// (7 171 with the left-out directions); (c) without the point's side adds 2 (208).
TEST_F(ClosedBoxCrease, BundleWalkAddsNoHitInTheAirBesideAConvexEdge) {
    prepare(false, true, true);
    std::size_t rays = 0, short_[2] = {0, 0}, added = 0, nearGrazing = 0, onInnerBox = 0;
    std::vector<std::uint32_t> withTaps;
    walk([&](const shader::BundleFrame& frame, std::uint32_t centreOnly, const std::vector<std::uint32_t>& answers) {
        if (centreOnly == 0) {
            withTaps = answers;
            return;
        }
        // A face of the inner box seen within twice the tangent cap of its plane.
        bool grazingBox = false;
        for (int a = 0; a < 3; ++a) {
            grazingBox = grazingBox || std::abs(frame.direction[a]) * shader::kBundleMaxOwnSurfaceTangent < 2.0f;
        }
        for (std::size_t i = 0; i < queries.size(); ++i) {
            const BoxPoint& p = points[i];
            const glm::vec3 n(queries[i].normal);
            const float cosine = glm::dot(n, frame.direction);
            if (std::abs(cosine) < 1.0f / shader::kBundleMaxOwnSurfaceTangent) continue;
            const glm::vec3 d = (cosine >= 0.0f ? 1.0f : -1.0f) * frame.direction;
            float truth = 0.0f;
            exitFace(p.position, d, truth);
            // The inner box first, where x's ray enters it.
            float enter = 0.0f, leave = std::numeric_limits<float>::max();
            for (int a = 0; a < 3; ++a) {
                if (d[a] == 0.0f) continue;
                const float t0 = (kInnerBox.x - p.position[a]) / d[a], t1 = (kInnerBox.y - p.position[a]) / d[a];
                enter = std::max(enter, std::min(t0, t1));
                leave = std::min(leave, std::max(t0, t1));
            }
            if (enter < leave && enter < truth) {
                truth = enter;
                ++onInnerBox;
            }
            ++rays;
            const float slack = surfaceEpsilon(frame, cosine) + 1e-5f * truth;
            bool isShort[2];
            const std::vector<std::uint32_t>* sets[2] = {&withTaps, &answers};
            for (int c = 0; c < 2; ++c) {
                float found = 0.0f;
                std::memcpy(&found, &(*sets[c])[queries.size() + i], sizeof(found));
                isShort[c] = (*sets[c])[i] == 1u && found < truth - slack;
                short_[c] += isShort[c] ? 1 : 0;
            }
            if (isShort[0] && !isShort[1]) {
                ++added;
                nearGrazing += grazingBox ? 1 : 0;
            }
        }
    });
    std::printf("rays from the room's walls: %zu (%zu reaching the inner box); landing short of the first surface: "
                "%zu with the taps, %zu with the own pixel alone, %zu added by the taps (%zu where a face of the inner "
                "box is seen within twice the tangent cap)\n",
                rays, onInnerBox, short_[0], short_[1], added, nearGrazing);
    ASSERT_GT(onInnerBox, rays / 20) << "the rays must reach the inner box for this test to mean anything";
    EXPECT_EQ(added - nearGrazing, 0u) << "hits in the air the contact taps added";
}
