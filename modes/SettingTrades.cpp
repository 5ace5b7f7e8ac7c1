#include "modes/SettingTrades.h"

#include "modes/Mode.h"
#include "reference/EmbreeScene.h"
#include "reference/ReferenceRenderer.h"
#include "scene/Scene.h"
#include "scene/ScenePrecision.h"
#include "scene/ShaderConversions.h"

#include <shared/BundleContacts.h>
#include <shared/Camera.h>
#include <shared/CubeFaces.h>
#include <shared/Lights.h>
#include <shared/Random.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace bl {

namespace {

// Primary rays per side of the grid the checks sample the camera's view with: 48^2 = 2304
// points, so a check's standard error is a few tenths of a percent where a tenth of the points
// disagree, well under kTradeTolerance / kTradeSigmas.
constexpr std::uint32_t kViewGrid = 48;
// Uniform directions per view point in the bundle check (9,216 queries at kViewGrid).
constexpr std::uint32_t kBundleDirectionsPerPoint = 4;
// The largest settings a fix may suggest. A shadow cube of 4096^2 texels holds 6 x 128 MiB of
// distances and normals (plus 64 MiB of depth while rendering): beyond it the cube costs more than
// the scene.
// A bundle of 2048^2 pixels needs 16 MiB of list heads alone per bundle and K times that in
// multibounce: the pool caps of the modes refuse more long before.
constexpr std::uint32_t kMaxShadowResolution = 4096;
constexpr std::uint32_t kMaxBundleResolution = 2048;

// The constants of the GPU code each replay mirrors (ShadowCubeLookup.glsl, Traversal.glsl).
constexpr float kShadowRelativeBias = 1e-3f;
constexpr float kShadowParallelCosine = 1e-6f;
constexpr int kShadowPcfTaps = 4;

float uniform01(std::uint32_t a, std::uint32_t b, std::uint32_t dimension) {
    const std::uint32_t h =
        shader::blHash(a ^ shader::blHash(b ^ shader::blHash(dimension + 0x9e3779b9u)));
    return float(h >> 8) * (1.0f / 16777216.0f);
}

// Mean of differences d_i relative to the sum of exact values: error and standard error.
struct RatioAccumulator {
    double sumExact = 0.0, sumDiff = 0.0, sumDiff2 = 0.0;
    std::uint64_t n = 0;
    void add(double exact, double approx) {
        const double d = approx - exact;
        sumExact += exact;
        sumDiff += d;
        sumDiff2 += d * d;
        ++n;
    }
    TradeError result() const {
        TradeError e;
        if (n < 2 || !(sumExact > 0.0))
            return e;
        const double mean = sumDiff / double(n);
        const double var =
            std::max(0.0, (sumDiff2 / double(n) - mean * mean)) * double(n) / double(n - 1);
        e.error = sumDiff / sumExact;
        e.stderr_ = std::sqrt(var / double(n)) * double(n) / sumExact;
        return e;
    }
};

// ShadowCubeLookup.glsl's blShadowFaceTexel.
glm::vec2 faceTexel(const glm::vec3& d, std::uint32_t face, float res) {
    glm::vec3 r, u, f;
    shader::blCubeFaceBasis(face, r, u, f);
    const float z = glm::dot(d, f);
    const glm::vec2 xy = glm::vec2(glm::dot(d, r), glm::dot(d, u)) / z;
    return glm::vec2(xy.x + 1.0f, 1.0f - xy.y) * (0.5f * res);
}

// The distance a shadow cube stores along a texel's centre ray: the nearest surface beyond the
// light's clearance (ShadowCubePass renders no closer), +inf where nothing.
float storedDistance(const EmbreeScene& rt, const glm::vec3& light, const glm::vec3& ray) {
    const float clearance = rt.lightClearance();
    SurfaceHit hit;
    if (rt.intersect(light + clearance * ray, ray, std::numeric_limits<float>::infinity(), hit)) {
        return hit.t + clearance;
    }
    return std::numeric_limits<float>::infinity();
}

// blShadowTap: texel `texel` of face (r, u, f) against the receiver plane through p (relative to
// the light) with normal n (toward the light).
float shadowTap(const EmbreeScene& rt, const glm::vec3& light, glm::ivec2 texel, const glm::vec3& r,
                const glm::vec3& u, const glm::vec3& f, float res, const glm::vec3& p,
                const glm::vec3& n) {
    const glm::vec2 c = (glm::vec2(texel) + 0.5f) / res * 2.0f - 1.0f;
    const glm::vec3 ray = glm::normalize(f + c.x * r - c.y * u);
    const float denom = glm::dot(ray, n);
    if (denom >= -kShadowParallelCosine)
        return 1.0f;
    const float receiver = glm::dot(p, n) / denom;
    return storedDistance(rt, light, ray) >= receiver * (1.0f - kShadowRelativeBias) ? 1.0f : 0.0f;
}

// blShadowVisibilityTaps with 4 x 4 taps, each tap's stored distance traced along its centre ray.
float pcfVisibility(const EmbreeScene& rt, const glm::vec3& light, std::uint32_t resolution,
                    const glm::vec3& p, const glm::vec3& n) {
    const float res = float(resolution);
    const std::uint32_t face = shader::blCubeFaceOf(p);
    glm::vec3 r, u, f;
    shader::blCubeFaceBasis(face, r, u, f);
    const glm::vec2 st = faceTexel(p, face, res);
    const float centre = 0.5f * float(kShadowPcfTaps - 1);
    float lit = 0.0f;
    for (int j = 0; j < kShadowPcfTaps; ++j) {
        for (int i = 0; i < kShadowPcfTaps; ++i) {
            const glm::vec2 tap = st + glm::vec2(float(i) - centre, float(j) - centre);
            if (tap.x >= 1.0f && tap.y >= 1.0f && tap.x < res - 1.0f && tap.y < res - 1.0f) {
                lit += shadowTap(rt, light, glm::ivec2(glm::floor(tap)), r, u, f, res, p, n);
                continue;
            }
            const glm::vec2 xy(tap.x / res * 2.0f - 1.0f, 1.0f - tap.y / res * 2.0f);
            const glm::vec3 dir = f + xy.x * r + xy.y * u;
            const std::uint32_t tapFace = shader::blCubeFaceOf(dir);
            const glm::vec2 tapSt = tapFace == face ? tap : faceTexel(dir, tapFace, res);
            const glm::ivec2 texel = glm::clamp(glm::ivec2(glm::floor(tapSt)), glm::ivec2(0),
                                                glm::ivec2(int(resolution) - 1));
            glm::vec3 tr, tu, tf;
            shader::blCubeFaceBasis(tapFace, tr, tu, tf);
            lit += shadowTap(rt, light, texel, tr, tu, tf, res, p, n);
        }
    }
    return lit / float(kShadowPcfTaps * kShadowPcfTaps);
}

// The largest extent of the points' projections on (ax, ay): the fitted frame's pixel is that
// over resolution - 1 (core/bundle bundleFrameForPoints).
float projectedExtent(const std::vector<ViewPoint>& points, const glm::vec3& ax,
                      const glm::vec3& ay) {
    glm::vec2 lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
    for (const ViewPoint& v : points) {
        const glm::vec2 q(glm::dot(v.position, ax), glm::dot(v.position, ay));
        lo = glm::min(lo, q);
        hi = glm::max(hi, q);
    }
    return std::max(hi.x - lo.x, hi.y - lo.y);
}

std::string percent(double x) {
    char b[32];
    std::snprintf(b, sizeof b, "%+.1f %%", 100.0 * x);
    return b;
}

std::string describe(const TradeError& e) {
    char b[32];
    std::snprintf(b, sizeof b, " (+- %.1f %%)", 100.0 * e.stderr_);
    return percent(e.error) + b;
}

} // namespace

bool TradeError::exceeds() const {
    return std::abs(error) > kTradeTolerance + kTradeSigmas * stderr_;
}
bool TradeError::within() const {
    return std::abs(error) <= kTradeTolerance;
}

std::vector<ViewPoint> viewPoints(const EmbreeScene& rt, const Scene& scene, std::uint32_t grid) {
    const shader::GpuCamera cam = makeGpuCamera(scene.camera, 0.0, 1.0f);
    const std::uint32_t gx = grid;
    const std::uint32_t gy =
        std::max(1u, std::uint32_t(std::lround(double(grid) * cam.height / cam.width)));
    std::vector<ViewPoint> out;
    out.reserve(std::size_t(gx) * gy);
    for (std::uint32_t j = 0; j < gy; ++j) {
        for (std::uint32_t i = 0; i < gx; ++i) {
            const glm::vec2 pixel((float(i) + 0.5f) / float(gx) * cam.width,
                                  (float(j) + 0.5f) / float(gy) * cam.height);
            const glm::vec3 dir = shader::blCameraRayDirection(cam, pixel);
            SurfaceHit hit;
            if (!rt.intersect(cam.position, dir, std::numeric_limits<float>::infinity(), hit))
                continue;
            const glm::vec3 n = glm::dot(hit.geometricNormal, dir) > 0.0f ? -hit.geometricNormal
                                                                          : hit.geometricNormal;
            out.push_back({hit.position, n, hit.offsetScale, hit.mesh, hit.triangle});
        }
    }
    return out;
}

TradeError shadowCubeError(const EmbreeScene& rt, const std::vector<ViewPoint>& points,
                           std::uint32_t light, std::uint32_t resolution) {
    const Light l = rt.scene().lightsAt(rt.time()).at(light);
    const shader::GpuLight gpuLight = toGpuLight(l);
    RatioAccumulator acc;
    for (const ViewPoint& v : points) {
        const glm::vec3 p = v.position - l.position;
        const float r2 = glm::dot(p, p);
        if (!(r2 > 0.0f))
            continue;
        const glm::vec3 fromLight = p / std::sqrt(r2);
        // Two-sided: the side of the surface the light is on (the GPU lights only the viewer's
        // side, which the exact and the cube answer alike).
        const glm::vec3 n = glm::dot(v.normal, fromLight) < 0.0f ? v.normal : -v.normal;
        if (glm::dot(v.normal, fromLight) >= 0.0f) {
            acc.add(0.0, 0.0);
            continue;
        }
        const double w =
            double(shader::blLightProfile(gpuLight, fromLight)) * -glm::dot(n, fromLight) / r2;
        if (!(w > 0.0)) {
            acc.add(0.0, 0.0);
            continue;
        }
        const bool exact = !rt.occludedFromLight(
            EmbreeScene::offsetOrigin(v.position, n, v.offsetScale), l.position);
        acc.add(exact ? w : 0.0, w * pcfVisibility(rt, l.position, resolution, p, n));
    }
    return acc.result();
}

// Whether a hit is x's own triangle, which the walks skip by identity.
bool ownTriangle(const EmbreeScene::RayHit& h, const ViewPoint& v) { return h.mesh == v.mesh && h.triangle == v.triangle; }

// Where x's own list found nothing: whether the contact taps at x's end of the walk hide it
// (bundle/Traversal.glsl, blBundleSurfaceNearestAcrossCreases, with the rules of
// shared/BundleContacts.h): the three other pixels of x's footprint toward the quarter of its pixel
// x lies in (stepX, stepY), each fragment of theirs ahead of x by rules (a) to (c), where x's own
// centre ray (`hits`, depths `back` before its point at x's depth) leaves the neighbourhood open to
// it (blBundleNearEndOpen).
bool contactTapsHide(const EmbreeScene& rt, const ViewPoint& v, const std::vector<EmbreeScene::RayHit>& hits,
                     const glm::vec3& centrePoint, float back, const glm::vec3& omega, const glm::vec3& e,
                     const glm::vec3& d, const glm::vec3& lit, float litCosine, float epsilon, float pixel,
                     const glm::vec3& ax, const glm::vec3& ay, float stepX, float stepY) {
    const float dir = glm::dot(d, omega) >= 0.0f ? 1.0f : -1.0f;
    const float reach = shader::blBundleReach(pixel, glm::dot(v.normal, omega));
    const float lateralSquared = glm::dot(e, e);
    const auto nearEndOpen = [&](const glm::vec3& point, const glm::vec3& m) {
        const float tolerance = epsilon * std::abs(glm::dot(m, d));
        bool neighbourOnXsSide = false;
        for (const EmbreeScene::RayHit& h : hits) {
            const glm::vec3 fragment = centrePoint + (h.t - back) * omega;
            // x's own list found nothing: the walk's distance is unbounded.
            const std::uint32_t kind = shader::blBundleNearFragment(
                fragment, h.geometricNormal, h.t - back, lateralSquared, v.position, d, dir, lit, litCosine, epsilon,
                reach, std::numeric_limits<float>::infinity());
            if (kind == shader::kBundleFragmentRoom) return true;
            neighbourOnXsSide = neighbourOnXsSide || (kind == shader::kBundleFragmentNeighbour &&
                                                      shader::blBundleOnXsSide(fragment, point, m, v.position, tolerance));
        }
        return !neighbourOnXsSide;
    };
    const glm::vec3 offsets[3] = {stepX * ax, stepY * ay, stepX * ax + stepY * ay};
    for (const glm::vec3& offset : offsets) {
        const glm::vec3 tapCentre = centrePoint + pixel * offset;
        for (const EmbreeScene::RayHit& h : rt.allHits(tapCentre - back * omega, omega, 2.0f * back)) {
            const glm::vec3 m = h.geometricNormal;
            if (ownTriangle(h, v) || std::abs(glm::dot(m, omega)) * shader::kBundleMaxOwnSurfaceTangent < 1.0f)
                continue;
            const glm::vec3 point = tapCentre + (h.t - back) * omega;
            if (shader::blBundleContactAhead(point, m, v.position, lit, litCosine, d, epsilon) >= 0.0f &&
                shader::blBundleContactNearBoth(omega, pixel, point, m, v.position, lit) && nearEndOpen(point, m))
                return true;
        }
    }
    return false;
}

TradeError bundleVisibilityError(const EmbreeScene& rt, const std::vector<ViewPoint>& points,
                                 std::uint32_t resolution, bool fitVisible,
                                 std::uint32_t directionsPerPoint, BundleRule rule) {
    const Bounds bounds = rt.scene().bounds();
    const glm::vec3 centre = bounds.center();
    const float radius = bounds.radius();
    const float depthEpsilon = kRelativeClearance * radius;
    RatioAccumulator acc;
    for (std::uint32_t i = 0; i < points.size(); ++i) {
        const ViewPoint& v = points[i];
        for (std::uint32_t k = 0; k < directionsPerPoint; ++k) {
            // omega uniform on the sphere, the frame's rotation about it uniform, and x's place in
            // its pixel uniform (the grid's phase moves with every frame's rotation and fit).
            const float z = 1.0f - 2.0f * uniform01(i, k, 0);
            const float phi = 2.0f * shader::kPi * uniform01(i, k, 1);
            const float s = std::sqrt(std::max(0.0f, 1.0f - z * z));
            const glm::vec3 omega(s * std::cos(phi), s * std::sin(phi), z);
            glm::vec3 ax = glm::normalize(glm::cross(
                std::abs(omega.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0), omega));
            glm::vec3 ay = glm::cross(omega, ax);
            const float rot = 2.0f * shader::kPi * uniform01(i, k, 2);
            const glm::vec3 rx = std::cos(rot) * ax + std::sin(rot) * ay;
            ay = glm::cross(omega, rx);
            ax = rx;
            const float pixel = fitVisible
                                    ? std::max(projectedExtent(points, ax, ay), 1e-6f * radius) /
                                          float(resolution - 1)
                                    : 2.0f * radius / float(resolution);
            const glm::vec3 e =
                (uniform01(i, k, 3) - 0.5f) * pixel * ax + (uniform01(i, k, 4) - 0.5f) * pixel * ay;

            const float cosine = glm::dot(v.normal, omega);
            const float dir = cosine >= 0.0f ? 1.0f : -1.0f;
            const glm::vec3 d = dir * omega;
            const double weight = std::abs(cosine);
            const bool exact =
                !rt.occluded(EmbreeScene::offsetOrigin(v.position, v.normal, v.offsetScale), d,
                             std::numeric_limits<float>::infinity());

            // The pixel's centre ray through the whole sphere; depths measured from x's depth.
            // Lists (the walks with payloads: multibounce, bidir, skylight): each fragment but x's
            // own triangle on its own facet's plane where its centre-ray point lies ahead of x's
            // plane; where that finds nothing, the near end's contact taps behind their gate
            // (shared/BundleContacts.h). Depth maps (and atlas,
            // whose sorted lists exchange along exact centre rays: an approximation): only the
            // surface nearest the light along d, which hides x where it lies beyond both x's plane
            // and its own facet's plane (the map's normal) as x's ray crosses them
            // (blDepthMapTexelHides; the contact taps, which answer only where the centre shows
            // nothing near x, are not replayed).
            const glm::vec3 centrePoint = v.position - e;
            const float back = glm::length(centrePoint - centre) + radius * 1.01f;
            const std::vector<EmbreeScene::RayHit> hits =
                rt.allHits(centrePoint - back * omega, omega, 2.0f * back);
            const float epsilon = shader::blBundleOwnSurfaceTolerance(depthEpsilon, pixel, cosine);
            const auto distanceTo = [&](const EmbreeScene::RayHit& h, const glm::vec3& plane) {
                return dir * shader::blBundlePlaneCrossing(omega, h.t - back, e, plane);
            };
            const auto beyond = [&](const EmbreeScene::RayHit& h, const glm::vec3& plane) {
                return distanceTo(h, plane) > epsilon;
            };
            bool blocked = false;
            if (rule == BundleRule::DepthMapNearestLight) {
                if (!hits.empty()) {
                    const EmbreeScene::RayHit& nearest = dir > 0.0f ? hits.back() : hits.front();
                    blocked = beyond(nearest, v.normal) && beyond(nearest, nearest.geometricNormal);
                }
            } else {
                const glm::vec3 lit = glm::dot(v.normal, d) >= 0.0f ? v.normal : -v.normal;
                float walkFound = std::numeric_limits<float>::infinity();
                for (const EmbreeScene::RayHit& h : hits) {
                    const glm::vec3 point = centrePoint + (h.t - back) * omega;
                    if (!ownTriangle(h, v) && glm::dot(point - v.position, lit) > epsilon * std::abs(cosine) &&
                        beyond(h, h.geometricNormal))
                        walkFound = std::min(walkFound, distanceTo(h, h.geometricNormal));
                }
                blocked = walkFound < std::numeric_limits<float>::infinity() ||
                          contactTapsHide(rt, v, hits, centrePoint, back, omega, e, d, lit, std::abs(cosine), epsilon,
                                          pixel, ax, ay, uniform01(i, k, 3) < 0.5f ? -1.0f : 1.0f,
                                          uniform01(i, k, 4) < 0.5f ? -1.0f : 1.0f);
            }
            acc.add(exact ? weight : 0.0, blocked ? 0.0 : weight);
        }
    }
    return acc.result();
}

// A Phong lobe cos^e about the mirror direction holds the solid angle integral of cos^e, 2 pi /
// (e + 1); a uniform bundle direction (on the hemisphere the point sees, +-omega) falls in it with
// probability 1 / (e + 1). A mode that meets lobes only through its bundle directions therefore
// sees the lobe about once per e + 1 directions: far fewer directions than that leave the
// highlight dark in most runs (an unbiased but very noisy estimate; the stress suite's phong-1e4
// under a sky reads 0.30 of the reference after 32 directions). Said when e + 1 exceeds
// kLobeDirections, a long run's number of directions. An Ashikhmin-Shirley lobe (exponents nu != nv)
// holds 2 pi / sqrt((nu + 1)(nv + 1)) of half vectors, about 4 times that of reflected directions
// near the normal: one direction in sqrt((nu + 1)(nv + 1)) / 4.
double directionsPerLobeHit(double exponent) { return exponent + 1.0; }

double directionsPerLobeHit(const Material& m) {
    return m.anisotropic() ? 0.25 * std::sqrt((double(m.exponentU) + 1.0) * (double(m.exponentV) + 1.0))
                           : directionsPerLobeHit(double(m.exponentU));
}

std::vector<TradeError> cutPathErrors(const Scene& scene, const std::vector<std::uint32_t>& segments,
                                      std::uint32_t uncutSegments) {
    Scene small = scene;
    const glm::ivec2 full = scene.camera.resolution;
    small.camera.resolution =
        glm::ivec2(kCutPathWidth, std::max(1, int(std::lround(double(kCutPathWidth) * full.y / std::max(1, full.x)))));
    // Per render: the image total (sum of r + g + b) and, per pixel, the totals of the even and
    // odd samples' means (two independent half estimates).
    struct Totals {
        double total = 0.0;
        std::vector<double> halves[2];
    };
    auto render = [&](std::uint32_t maxSegments) {
        ReferenceSettings settings;
        settings.path.maxSegments = int(maxSegments);
        ReferenceRenderer r(small, 0.0, settings);
        for (std::uint32_t i = 0; i < kCutPathSamples; ++i)
            r.renderPass(i, 0x5e77u);
        Totals out;
        const Image mean = r.mean();
        for (const glm::vec3& p : mean.pixels())
            out.total += double(p.x) + double(p.y) + double(p.z);
        for (int h = 0; h < 2; ++h) {
            const Image half = r.halfMean(h);
            for (const glm::vec3& p : half.pixels())
                out.halves[h].push_back(double(p.x) + double(p.y) + double(p.z));
        }
        return out;
    };
    const Totals uncut = render(uncutSegments);
    std::vector<TradeError> errors;
    for (std::uint32_t n : segments) {
        const Totals cut = render(n);
        TradeError e;
        if (uncut.total > 0.0) {
            e.error = (cut.total - uncut.total) / uncut.total;
            // The renders share their samples, so the difference holds the cut-off paths with
            // little noise; its variance per pixel from the two halves, (d_even - d_odd)^2 / 4.
            double variance = 0.0;
            for (std::size_t p = 0; p < uncut.halves[0].size(); ++p) {
                const double d = (cut.halves[0][p] - uncut.halves[0][p]) - (cut.halves[1][p] - uncut.halves[1][p]);
                variance += 0.25 * d * d;
            }
            e.stderr_ = std::sqrt(variance) / uncut.total;
        }
        errors.push_back(e);
    }
    return errors;
}

std::vector<std::string> settingTrades(const Mode& mode, const Scene& scene) {
    const TradeSettings t = mode.trades();
    const std::string name(mode.name());
    std::vector<std::string> out;

    if (t.lobesByBundleDirections) {
        for (const Material& m : scene.materials) {
            if (!m.glossy() || !(directionsPerLobeHit(m) > kLobeDirections)) continue;
            char b[160];
            if (m.anisotropic()) {
                std::snprintf(b, sizeof b, "s of %g and %g, one bundle direction in %.0f falls in its lobe",
                              double(m.exponentU), double(m.exponentV), directionsPerLobeHit(m));
            } else {
                std::snprintf(b, sizeof b, " of %g, one bundle direction in %.0f falls in its lobe",
                              double(m.exponentU), directionsPerLobeHit(m));
            }
            out.push_back(name + ": material '" + m.name + "' has a glossy exponent" + b +
                          ", so its highlights need many times that many iterations (noise, not bias); raster, "
                          "bidir or the reference sample the lobe itself" +
                          (name == "skylight" ? std::string(", as skylight does with glossy_control_variate = on") : ""));
        }
    }

    if (!t.pathKey.empty() && t.pathSegments > 0) {
        // The cut itself and, for the fix, one segment more per unit of the setting up to the
        // value that cuts nothing. Where emitters or the sky light the scene with a shorter cut
        // than point lights, that cut: exact for their paths, an overstatement for the others.
        const SceneFeatures f = scene.features();
        std::uint32_t segments = t.pathSegments;
        std::string shorter; // what ends paths sooner than point lights do
        if (f.emissiveTriangles > 0 && t.pathSegmentsToEmitters < segments) {
            segments = t.pathSegmentsToEmitters;
            shorter = "an emitter";
        }
        if (f.environment && t.pathSegmentsToSky < t.pathSegments) {
            shorter = shorter.empty() || t.pathSegmentsToSky < segments ? std::string("the sky") : shorter + " or the sky";
            segments = std::min(segments, t.pathSegmentsToSky);
        }
        const bool emitters = !shorter.empty();
        std::vector<std::uint32_t> cuts;
        for (std::uint32_t v = t.pathValue; v < t.pathUncutFrom && segments + (v - t.pathValue) < t.pathUncut; ++v)
            cuts.push_back(segments + (v - t.pathValue));
        const std::vector<TradeError> errors = cutPathErrors(scene, cuts, t.pathUncut);
        if (!errors.empty() && errors.front().exceeds()) {
            std::string fix;
            for (std::size_t i = 1; i < errors.size() && fix.empty(); ++i) {
                if (errors[i].within())
                    fix = "fix: " + t.pathKey + "=" + std::to_string(t.pathValue + i) + " (" + describe(errors[i]) + ")";
            }
            if (fix.empty())
                fix = "fix: " + t.pathKey + "=" + std::to_string(t.pathSuggested) + " or more (no path cut)";
            out.push_back(name + ": " + t.pathKey + "=" + std::to_string(t.pathValue) + " ends every path after " +
                          std::to_string(segments) + " segments" +
                          (emitters ? " where it meets " + shorter + " (" + std::to_string(t.pathSegments) +
                                          " with point and spot lights)"
                                    : std::string()) +
                          ", which leaves out " + describe(errors.front()) +
                          " of the image (the reference path tracer at " + std::to_string(kCutPathWidth) +
                          " pixels wide with and without the cut; tolerance 1 %)" +
                          (t.pathNote.empty() ? std::string() : "; " + t.pathNote) + "; " + fix);
        }
    }

    const bool shadows = !t.shadowKey.empty() && !scene.lights.empty();
    const bool bundles = !t.bundleKey.empty() && (!t.bundlesOnlyForEnvironment || scene.features().environment);
    if (!shadows && !bundles)
        return out;
    bool anyTriangles = false;
    for (const Mesh& m : scene.meshes)
        anyTriangles = anyTriangles || !m.triangles.empty();
    if (!anyTriangles)
        return out;

    const EmbreeScene rt(scene, 0.0);
    const std::vector<ViewPoint> points = viewPoints(rt, scene, kViewGrid);
    if (points.size() < 2)
        return out;

    if (shadows) {
        for (std::uint32_t l = 0; l < scene.lights.size(); ++l) {
            const TradeError e = shadowCubeError(rt, points, l, t.shadowResolution);
            if (!e.exceeds())
                continue;
            std::string line =
                name + ": the " + std::to_string(t.shadowResolution) + "^2 shadow cube of light " +
                std::to_string(l) + " misses " + describe(e) +
                " of its direct light at the points the camera sees (4x4 PCF against exact " +
                "shadow rays; tolerance 1 %); ";
            std::string fix;
            for (std::uint32_t r = t.shadowResolution * 2; r <= kMaxShadowResolution && fix.empty();
                 r *= 2) {
                const TradeError f = shadowCubeError(rt, points, l, r);
                if (f.within())
                    fix =
                        "fix: " + t.shadowKey + "=" + std::to_string(r) + " (" + describe(f) + ")";
            }
            if (fix.empty()) {
                fix = "even " + t.shadowKey + "=" + std::to_string(kMaxShadowResolution) +
                      " does not bring it under";
            }
            out.push_back(line + fix);
        }
    }

    if (bundles) {
        const TradeError e = bundleVisibilityError(rt, points, t.bundleResolution, t.fitVisible,
                                                   kBundleDirectionsPerPoint, t.bundleRule);
        if (e.exceeds()) {
            std::string line =
                name + ": " + t.bundleWhat + " of " + std::to_string(t.bundleResolution) + "^2 pixels" +
                (t.fitVisible ? " fitted to the visible points"
                              : " over the scene's bounding sphere") +
                " misjudge the visibility of the points the camera sees by " + describe(e) +
                " (cosine-weighted, against exact rays; tolerance 1 %): ";
            std::string reason = "their pixel is too coarse for the objects in view; ";
            std::string fix;
            const bool canFit = !t.fitKey.empty() && !t.fitVisible;
            for (std::uint32_t r = t.bundleResolution; r <= kMaxBundleResolution && fix.empty();
                 r *= 2) {
                if (canFit) {
                    const TradeError f =
                        bundleVisibilityError(rt, points, r, true, kBundleDirectionsPerPoint, t.bundleRule);
                    if (f.within()) {
                        fix = "fix: " + t.fitKey + "=visible" +
                              (r != t.bundleResolution ? " " + t.bundleKey + "=" + std::to_string(r)
                                                       : std::string()) +
                              " (" + describe(f) + ")";
                        break;
                    }
                }
                if (r == t.bundleResolution)
                    continue;
                const TradeError f =
                    bundleVisibilityError(rt, points, r, t.fitVisible, kBundleDirectionsPerPoint, t.bundleRule);
                if (f.within())
                    fix =
                        "fix: " + t.bundleKey + "=" + std::to_string(r) + " (" + describe(f) + ")";
            }
            if (fix.empty()) {
                fix = "even " + t.bundleKey + "=" + std::to_string(kMaxBundleResolution) +
                      (canFit ? " with " + t.fitKey + "=visible" : std::string()) +
                      " does not bring it under";
            }
            if (t.fitKey.empty())
                fix += " (" + t.wholeSceneWhy + ")";
            out.push_back(line + reason + fix);
        }
    }
    return out;
}

} // namespace bl
