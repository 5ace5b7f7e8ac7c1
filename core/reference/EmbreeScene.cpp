#include "reference/EmbreeScene.h"

#include "base/Error.h"
#include "scene/ScenePrecision.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

namespace bl {

namespace {
// Ray offset in units of the triangle's largest coordinate: the clearance every mode keeps
// (ScenePrecision.h), ~140 float ulps, well above the error of a barycentric hit point.
constexpr float kRelativeRayOffset = kRelativeClearance;

void onEmbreeError(void*, RTCError code, const char* message) {
    // Embree calls back from its own threads; errors are re-checked after each build.
    (void)code;
    (void)message;
}

float maxAbs(const glm::vec3& v) { return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)}); }

RTCRay makeRay(const glm::vec3& origin, const glm::vec3& direction, float tMax) {
    RTCRay ray;
    ray.org_x = origin.x;
    ray.org_y = origin.y;
    ray.org_z = origin.z;
    ray.dir_x = direction.x;
    ray.dir_y = direction.y;
    ray.dir_z = direction.z;
    ray.tnear = 0.0f;
    ray.tfar = tMax;
    ray.time = 0.0f;
    ray.mask = ~0u;
    ray.id = 0;
    ray.flags = 0;
    return ray;
}

RTCRayHit makeRayHit(const glm::vec3& origin, const glm::vec3& direction, float tMax, float tNear = 0.0f) {
    RTCRayHit rh;
    rh.ray = makeRay(origin, direction, tMax);
    rh.ray.tnear = tNear;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    return rh;
}
} // namespace

EmbreeScene::EmbreeScene(const Scene& scene, double time)
    : mScene(&scene), mTime(time), mLightClearance(bl::lightClearance(scene.bounds().radius())) {
    mDevice = rtcNewDevice(nullptr);
    if (!mDevice) {
        throw Error("Embree: cannot create a device (" + std::to_string(rtcGetDeviceError(nullptr)) + ")");
    }
    rtcSetDeviceErrorFunction(mDevice, onEmbreeError, nullptr);
    mRtcScene = rtcNewScene(mDevice);
    rtcSetSceneBuildQuality(mRtcScene, RTC_BUILD_QUALITY_HIGH);
    rtcSetSceneFlags(mRtcScene, RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION);
    for (std::uint32_t i = 0; i < scene.meshes.size(); ++i) {
        const Mesh& m = scene.meshes[i];
        glm::mat4 model = m.animation.at(time);
        glm::mat3 normalMatrix = glm::mat3(model); // rigid: rotation only
        std::vector<glm::vec3>& pos = mPositions.emplace_back(m.positions.size());
        std::vector<glm::vec3>& nrm = mNormals.emplace_back(m.normals.size());
        for (std::size_t v = 0; v < m.positions.size(); ++v) {
            pos[v] = glm::vec3(model * glm::vec4(m.positions[v], 1.0f));
        }
        for (std::size_t v = 0; v < m.normals.size(); ++v) {
            nrm[v] = glm::normalize(normalMatrix * m.normals[v]);
        }
        RTCGeometry geom = rtcNewGeometry(mDevice, RTC_GEOMETRY_TYPE_TRIANGLE);
        auto* vb = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                               3 * sizeof(float), pos.size()));
        auto* ib = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                  3 * sizeof(unsigned), m.triangles.size()));
        if (!vb || !ib) {
            rtcReleaseGeometry(geom);
            throw Error("Embree: cannot allocate buffers for mesh " + m.name);
        }
        for (std::size_t v = 0; v < pos.size(); ++v) {
            vb[3 * v] = pos[v].x;
            vb[3 * v + 1] = pos[v].y;
            vb[3 * v + 2] = pos[v].z;
        }
        for (std::size_t t = 0; t < m.triangles.size(); ++t) {
            ib[3 * t] = m.triangles[t].x;
            ib[3 * t + 1] = m.triangles[t].y;
            ib[3 * t + 2] = m.triangles[t].z;
        }
        rtcCommitGeometry(geom);
        rtcAttachGeometryByID(mRtcScene, geom, i); // geomID == mesh index
        rtcReleaseGeometry(geom);
    }
    rtcCommitScene(mRtcScene);
    if (RTCError e = rtcGetDeviceError(mDevice); e != RTC_ERROR_NONE) {
        throw Error("Embree: scene build failed with error " + std::to_string(e));
    }
}

EmbreeScene::~EmbreeScene() {
    if (mRtcScene) rtcReleaseScene(mRtcScene);
    if (mDevice) rtcReleaseDevice(mDevice);
}

void EmbreeScene::triangle(std::uint32_t mesh, std::uint32_t tri, glm::vec3& a, glm::vec3& b, glm::vec3& c) const {
    const glm::uvec3& t = mScene->meshes[mesh].triangles[tri];
    const std::vector<glm::vec3>& p = mPositions[mesh];
    a = p[t.x];
    b = p[t.y];
    c = p[t.z];
}

glm::vec3 EmbreeScene::offsetOrigin(const glm::vec3& p, const glm::vec3& normal, float offsetScale) {
    return p + normal * (kRelativeRayOffset * std::max(offsetScale, maxAbs(p)));
}

bool EmbreeScene::intersectFromLight(const glm::vec3& light, const glm::vec3& direction, SurfaceHit& hit) const {
    return intersectBeyond(light, direction, mLightClearance, std::numeric_limits<float>::infinity(), hit);
}

bool EmbreeScene::intersect(const glm::vec3& origin, const glm::vec3& direction, float tMax, SurfaceHit& hit) const {
    return intersectBeyond(origin, direction, 0.0f, tMax, hit);
}

bool EmbreeScene::intersectBeyond(const glm::vec3& origin, const glm::vec3& direction, float tNear, float tMax,
                                  SurfaceHit& hit) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh = makeRayHit(origin, direction, tMax, tNear);
    rtcIntersect1(mRtcScene, &context, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) {
        return false;
    }
    hit.t = rh.ray.tfar;
    fillHit(rh.hit.geomID, rh.hit.primID, rh.hit.u, rh.hit.v, hit);
    return true;
}

SurfaceHit EmbreeScene::surfaceAt(std::uint32_t mesh, std::uint32_t tri, const glm::vec3& point) const {
    glm::vec3 a, b, c;
    triangle(mesh, tri, a, b, c);
    // Barycentrics of the projection (Ericson 3.4), in double: slivers leave little of float.
    const glm::dvec3 e0 = glm::dvec3(b) - glm::dvec3(a), e1 = glm::dvec3(c) - glm::dvec3(a);
    const glm::dvec3 e2 = glm::dvec3(point) - glm::dvec3(a);
    const double d00 = glm::dot(e0, e0), d01 = glm::dot(e0, e1), d11 = glm::dot(e1, e1);
    const double d20 = glm::dot(e2, e0), d21 = glm::dot(e2, e1);
    const double denom = d00 * d11 - d01 * d01;
    double u = denom > 0.0 ? (d11 * d20 - d01 * d21) / denom : 1.0 / 3.0;
    double v = denom > 0.0 ? (d00 * d21 - d01 * d20) / denom : 1.0 / 3.0;
    u = std::max(u, 0.0);
    v = std::max(v, 0.0);
    if (u + v > 1.0) {
        const double sum = u + v;
        u /= sum;
        v /= sum;
    }
    return surfaceAt(mesh, tri, float(u), float(v));
}

SurfaceHit EmbreeScene::surfaceAt(std::uint32_t mesh, std::uint32_t tri, float u, float v) const {
    SurfaceHit hit;
    fillHit(mesh, tri, u, v, hit);
    return hit;
}

void EmbreeScene::fillHit(std::uint32_t meshIndex, std::uint32_t primitive, float u, float v, SurfaceHit& hit) const {
    const Mesh& mesh = mScene->meshes[meshIndex];
    const glm::uvec3& tri = mesh.triangles[primitive];
    glm::vec3 a, b, c;
    triangle(meshIndex, primitive, a, b, c);
    const float w = 1.0f - u - v;
    hit.mesh = meshIndex;
    hit.triangle = primitive;
    hit.position = w * a + u * b + v * c;
    hit.geometricNormal = glm::normalize(glm::cross(b - a, c - a));
    const std::vector<glm::vec3>& n = mNormals[meshIndex];
    glm::vec3 ns = w * n[tri.x] + u * n[tri.y] + v * n[tri.z];
    float len = glm::length(ns);
    hit.shadingNormal = len > 1e-20f ? ns / len : hit.geometricNormal;
    if (glm::dot(hit.shadingNormal, hit.geometricNormal) < 0.0f) {
        hit.shadingNormal = -hit.shadingNormal;
    }
    hit.uv = mesh.uvs.empty() ? glm::vec2(0.0f) : w * mesh.uvs[tri.x] + u * mesh.uvs[tri.y] + v * mesh.uvs[tri.z];
    hit.offsetScale = std::max({maxAbs(a), maxAbs(b), maxAbs(c)});
}

namespace {
struct AllHitsContext {
    RTCIntersectContext base; // first: Embree hands this pointer back to the filter
    std::vector<EmbreeScene::RayHit>* hits;
};

void collectHit(const RTCFilterFunctionNArguments* args) {
    auto* context = reinterpret_cast<AllHitsContext*>(args->context);
    RTCRay ray = rtcGetRayFromRayN(args->ray, args->N, 0);
    RTCHit hit = rtcGetHitFromHitN(args->hit, args->N, 0);
    context->hits->push_back({ray.tfar, hit.geomID, hit.primID, glm::vec3(0.0f)});
    args->valid[0] = 0; // reject, so the traversal goes on to every other crossing
}
} // namespace

std::vector<EmbreeScene::RayHit> EmbreeScene::allHits(const glm::vec3& origin, const glm::vec3& direction,
                                                      float tMax) const {
    std::vector<RayHit> hits;
    AllHitsContext context;
    rtcInitIntersectContext(&context.base);
    context.base.filter = collectHit;
    context.hits = &hits;
    RTCRayHit rh = makeRayHit(origin, direction, tMax);
    rtcIntersect1(mRtcScene, &context.base, &rh);
    // Spatial splits can report a triangle once per leaf that holds it.
    std::sort(hits.begin(), hits.end(), [](const RayHit& a, const RayHit& b) {
        return std::tie(a.mesh, a.triangle, a.t) < std::tie(b.mesh, b.triangle, b.t);
    });
    hits.erase(std::unique(hits.begin(), hits.end(),
                           [](const RayHit& a, const RayHit& b) { return a.mesh == b.mesh && a.triangle == b.triangle; }),
               hits.end());
    for (RayHit& h : hits) {
        glm::vec3 a, b, c;
        triangle(h.mesh, h.triangle, a, b, c);
        h.geometricNormal = glm::normalize(glm::cross(b - a, c - a));
    }
    std::sort(hits.begin(), hits.end(), [](const RayHit& a, const RayHit& b) { return a.t < b.t; });
    return hits;
}

bool EmbreeScene::occludedFromLight(const glm::vec3& from, const glm::vec3& light) const {
    const glm::vec3 d = light - from;
    const float length = glm::length(d);
    const float reach = length - mLightClearance;
    // Within the clearance of the light nothing can stand between them (a light lying on a
    // surface lights both of its sides, as the GPU's shadow near plane makes it).
    return reach > 0.0f && occluded(from, d / length, reach);
}

bool EmbreeScene::occluded(const glm::vec3& origin, const glm::vec3& direction, float tMax) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay ray = makeRay(origin, direction, tMax);
    rtcOccluded1(mRtcScene, &context, &ray);
    return ray.tfar < 0.0f;
}

} // namespace bl
