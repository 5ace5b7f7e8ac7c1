// The scene's floating-point frame, shared by every renderer (the GPU modes and the reference).
//
// Renderers work in float. A float coordinate x carries an error of up to |x| * 2^-24, so a scene
// far from the origin (a box of 556 mm at 1e6 mm) keeps few bits to describe itself and every
// epsilon below that error turns surfaces into their own occluders. The scene model therefore
// keeps its geometry near the origin: Scene::origin (double) is where its local frame sits in the
// file's world, and loaders move a far scene there (recentreFarScene) so that everything
// downstream (GPU uploads, camera and shadow matrices, bundle frames, Embree) works in centred
// floats without knowing. What float cannot represent is refused (requireRepresentable).
//
// One clearance convention: a ray leaving a surface, and a shadow ray ending at a point light,
// keep kRelativeClearance of the scene's bounding radius (or of the coordinates' magnitude, where
// that is larger) away from the surface or the light. It is the reference's ray offset and
// shadow-ray end (EmbreeScene), the GPU shadow cube's near plane (GpuScene::shadowNear) and the
// bundle depth tolerance (BundleFrame.h). A surface closer to a point light than that (a light
// lying on a floor, or 1e-4 mm above the Cornell box's) casts no shadow from it: the light lights
// both of its sides, as the shadow cube's near plane already made the GPU modes do.
#pragma once

namespace bl {

struct Scene;

// 84 to 168 float steps of the radius: well above the error of a hit point (a few ulps of its
// coordinates, which are at most a few radii in a centred scene), below any modelled detail.
inline constexpr float kRelativeClearance = 1e-5f;

// Distance kept from a point light (and the GPU's shadow near plane), in world units.
inline float lightClearance(float sceneRadius) {
    return kRelativeClearance * sceneRadius;
}

// Limits of what float arithmetic renders. The tightest is the length of a cross product of two
// edges (normals, areas, the mesh cleanup's degeneracy test): it squares L^2, so L^4 must stay in
// float's normal range. 2^30 (~1.07e9) leaves 250x below FLT_MAX for L^4; the point-lit Cornell
// box scaled by 1e7 (coordinates 5.6e9, L^4 ~ 1e39), which the issue saw render black, overflows
// it. A diameter of 2^-20 (~9.5e-7) keeps L^4 of a triangle 1e-3 of the scene's size above
// FLT_MIN.
inline constexpr double kMaxCoordinate = 1073741824.0;     // 2^30
inline constexpr double kMinDiameter = 9.5367431640625e-7; // 2^-20
// Far scenes are re-centred when their centre lies farther than this many bounding radii from
// the origin: up to there every coordinate is below 9 radii, so the clearance (1e-5 of the radius)
// stays above 9 float steps of any coordinate, and renderers see no difference.
inline constexpr double kRecentreRadii = 8.0;
// A scene whose largest coordinate leaves fewer than this many bits of the float mantissa to
// resolve its diameter (float step there > diameter / 2^10) is refused: its triangles, walls and
// shadows would be quantised by more than half a pixel of a 512^2 image of it. The Cornell box
// (966 mm across) keeps 13.9 bits 1e6 mm from the origin and is refused beyond 2^23 mm (~8.4e6,
// where floats step by 1 mm: 9.9 bits); a scene 1e4 radii out keeps ~10.7.
inline constexpr int kMinResolvedBits = 10;

// Throws bl::Error naming the first value float cannot represent well enough: a non-finite or
// too large coordinate (geometry, keyframes, lights, camera), a diameter below kMinDiameter, or
// geometry too far from the origin for its size (kMinResolvedBits).
void requireRepresentable(const Scene& scene);

// When the scene's centre lies farther than kRecentreRadii bounding radii from the origin, moves
// every position by -centre, computed in double, and adds the centre to scene.origin. The images
// are the same; coordinates read back from the scene are then local. Returns whether it moved it.
bool recentreFarScene(Scene& scene);

} // namespace bl
