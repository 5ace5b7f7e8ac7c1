// Scenes with closed-form answers, built in code so that tests state exactly what they assume.
#pragma once

#include "scene/Scene.h"

namespace bl::test {

// A square of side `size` centred at the origin in the plane y = 0, facing +y.
Mesh makeSquare(float size, std::uint32_t material, glm::vec3 centre = glm::vec3(0.0f));
// A rectangle in the plane y = `height` spanning [x0,x1] x [z0,z1], facing down (-y) if `facingDown`.
Mesh makeRectangle(glm::vec2 lo, glm::vec2 hi, float height, bool facingDown, std::uint32_t material);

// The lower half of a sphere of radius 1 centred at (0, 1, 0) (a bowl open at the top, resting on
// the origin), `rings` x `segments` facets with the sphere's smooth normals (outward).
Mesh makeBowl(int rings, int segments, std::uint32_t material);
// The largest angle (radians) between a triangle's geometric normal and one of its vertex normals.
double largestNormalDeviation(const Mesh& mesh);
// The edges of `meshes`, matched by position (across meshes too), over their triangles with a
// plane: the area; the length of borders (edges one triangle has) and of creases (borders, edges
// of more than two triangles, and edges of two whose planes differ: a coplanar diagonal is no
// edge); the largest angle between the planes of two triangles sharing an edge (radians).
struct EdgeStats {
    double area = 0.0, borderLength = 0.0, creaseLength = 0.0, largestDihedral = 0.0;
};
EdgeStats edgeStats(const std::vector<Mesh>& meshes);
// makeBowl(rings, segments) of albedo 0.8 under a constant white sky, seen from above into it
// (every inner point concave: its neighbours rise in front of its plane). For a true hemisphere
// each inner point sees the sky through the opening with form factor 1/2 (a point on a sphere's
// inside sees any part of it in proportion to area), so its direct radiance is 0.4; the outside, 0.8.
Scene bowlUnderSky(int rings, int segments, int resolution);

// A 2 x 2 square about the origin in y = 0 made a heightfield of `cells` x `cells` quads whose
// corners are raised by up to +-`amplitude` (a fixed hash: the same mesh every run), flat shaded
// (each triangle its own vertices, normals its geometric one), albedo 0.8, under a constant white
// sky, seen obliquely: concave creases between facets everywhere, no normal but the facets'.
Scene bumpsUnderSky(int cells, float amplitude, int resolution);

// A Lambertian plane of albedo `albedo` lit by a point light of intensity `intensity` at height h
// above the origin, seen obliquely by a camera of `resolution`.
Scene pointLightOverPlane(float albedo, float intensity, float h, int resolution);

// Where the camera ray through continuous pixel position `pixel` (pixel centre: index + 0.5)
// meets the plane y = planeY (t <= 0: never).
glm::vec3 cameraRayHitY(const Scene& scene, glm::vec2 pixel, float planeY, float& t);

// Radiance of a Lambertian floor (normal +y) of albedo rho at p lit by a point light of intensity
// I at `light`: rho / pi * I cos(theta) / r^2.
float pointLitFloorRadiance(glm::vec3 p, glm::vec3 light, float intensity, float albedo);

// Irradiance at x (normal n) from a convex polygon of constant radiance L seen from x's front
// (Lambert's formula: E = L / 2 sum_i angle(a_i, a_{i+1}) n . unit(a_i x a_{i+1}), a_i = v_i - x,
// the polygon wound so that it appears counter-clockwise from x; no occlusion, no one-sidedness:
// the caller knows which side emits).
float polygonIrradiance(glm::vec3 x, glm::vec3 n, const std::vector<glm::vec3>& polygon, float radiance);

// An area-lit scene (its emitters the only light) as three scenes for additivity tests: itself,
// the same with a point light of 20000 W/sr at `lightPosition` added (`both`), and `both` with
// every emission off (`pointOnly`). A mode linear in its lights renders both = area + pointOnly.
struct AreaAndPointLit {
    Scene area, pointOnly, both;
};
AreaAndPointLit areaAndPointLit(const Scene& areaLit, glm::vec3 lightPosition);

} // namespace bl::test
