// The Scene as Embree 3 sees it: one triangle geometry per mesh, baked at one scene time.
// Gives closest hits with everything shading needs, and occlusion tests.
#pragma once

#include "scene/Scene.h"

#include <embree3/rtcore.h>
#include <glm/glm.hpp>

namespace bl {

struct SurfaceHit {
    float t = 0.0f;
    glm::vec3 position{0.0f};
    glm::vec3 geometricNormal{0.0f}; // unit, the counter-clockwise (front) side
    glm::vec3 shadingNormal{0.0f};   // unit, interpolated, on the front side
    glm::vec2 uv{0.0f};
    std::uint32_t mesh = 0;
    std::uint32_t triangle = 0;
    float offsetScale = 0.0f; // magnitude of the triangle's coordinates, for ray offsets
};

class EmbreeScene {
public:
    EmbreeScene(const Scene& scene, double time);
    ~EmbreeScene();
    EmbreeScene(const EmbreeScene&) = delete;
    EmbreeScene& operator=(const EmbreeScene&) = delete;

    bool intersect(const glm::vec3& origin, const glm::vec3& direction, float tMax, SurfaceHit& hit) const;
    struct RayHit {
        float t;
        std::uint32_t mesh;
        std::uint32_t triangle;
        glm::vec3 geometricNormal; // unit, front side
    };
    // Every surface crossing along origin + t direction, 0 <= t < tMax, each triangle once,
    // sorted by t (coplanar duplicates are kept: they are distinct triangles).
    std::vector<RayHit> allHits(const glm::vec3& origin, const glm::vec3& direction, float tMax) const;

    // True if anything lies on the open segment origin + t direction, 0 < t < tMax.
    bool occluded(const glm::vec3& origin, const glm::vec3& direction, float tMax) const;
    // The shadow ray to a point or spot light: true if anything lies between `from` (already
    // offset off its surface) and lightClearance() short of `light`. A surface closer to the light
    // than that does not shadow it: the convention every mode shares (ScenePrecision.h).
    bool occludedFromLight(const glm::vec3& from, const glm::vec3& light) const;
    float lightClearance() const { return mLightClearance; }
    // The first surface a ray leaving point light `light` along unit `direction` meets beyond
    // lightClearance(): the same convention seen from the light (a surface the light lies on does
    // not catch the rays that leave into it, as it casts it no shadow). hit.t counts from `light`.
    bool intersectFromLight(const glm::vec3& light, const glm::vec3& direction, SurfaceHit& hit) const;

    // Point `point` of triangle `tri` of mesh `mesh` as a hit, t = 0: its barycentrics from the
    // point's projection onto the triangle's plane, clamped into the triangle (a texel's sample point
    // to path-trace from: reference/TexelBaker.h).
    SurfaceHit surfaceAt(std::uint32_t mesh, std::uint32_t tri, const glm::vec3& point) const;
    // The point at barycentrics (1 - u - v, u, v) of the triangle's corners in the mesh's order.
    SurfaceHit surfaceAt(std::uint32_t mesh, std::uint32_t tri, float u, float v) const;

    // World-space vertices of a triangle (at the baked time).
    void triangle(std::uint32_t mesh, std::uint32_t tri, glm::vec3& a, glm::vec3& b, glm::vec3& c) const;
    const Scene& scene() const { return *mScene; }
    double time() const { return mTime; } // the scene time it is baked at

    // Origin for a ray leaving a surface point on the side of `normal` (oriented toward the ray):
    // pushed off by a few ulps of the triangle's coordinates, so rays never re-hit their own
    // triangle and the offset stays far below any real feature at every scene scale.
    static glm::vec3 offsetOrigin(const glm::vec3& p, const glm::vec3& normal, float offsetScale);

private:
    const Scene* mScene;
    double mTime = 0.0;
    float mLightClearance = 0.0f; // ScenePrecision.h's lightClearance of the scene's radius
    bool intersectBeyond(const glm::vec3& origin, const glm::vec3& direction, float tNear, float tMax,
                         SurfaceHit& hit) const;
    // Everything of `hit` but t at barycentrics (1 - u - v, u, v) of the triangle.
    void fillHit(std::uint32_t meshIndex, std::uint32_t tri, float u, float v, SurfaceHit& hit) const;
    RTCDevice mDevice = nullptr;
    RTCScene mRtcScene = nullptr;
    std::vector<std::vector<glm::vec3>> mPositions; // world space, per mesh
    std::vector<std::vector<glm::vec3>> mNormals;
};

} // namespace bl
