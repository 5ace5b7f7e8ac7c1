// glTF 2.0 scenes (.gltf with its buffers and images, or .glb) read into the scene model, by
// Debian's tinygltf: the default scene's node hierarchy (matrix or translation/rotation/scale,
// composed parent first; a mirroring transform turns the winding back, as glTF's front face
// follows it), triangle primitives (POSITION, NORMAL, TEXCOORD_0; any index type), perspective
// cameras, KHR_lights_punctual point and spot lights, and materials mapped to Lambert + Phong:
//   base colour (factor x texture, the texture's sRGB kept) -> albedo; metallic m, roughness r:
//   albedo = base (1 - m), Phong lobe of reflectance base m and exponent (2 / r^4 - 2) / 4 (the
//   Beckmann width alpha = r^2 matches the half-vector exponent 2 / alpha^2 - 2; our Phong lobe is
//   about the mirror direction, whose angle is twice the half vector's: a quarter of it), a lobe
//   wider than exponent 1 (r above 0.76) read as Lambert with the base colour; the dielectric's 4%
//   specular reflection is dropped;
//   emissive factor x KHR_materials_emissive_strength -> emitted radiance (front face).
// Every approximation is a line in Scene::importNotes (`bundlelab info` prints them). What the
// model cannot hold is refused naming the element and what is supported: non-triangle
// primitives, sparse accessors, directional lights, orthographic cameras, emissive textures,
// texture coordinate sets other than 0, extensions a file requires that are not read here.
#pragma once

#include "scene/Scene.h"

#include <string>

namespace bl {

Scene loadGltfScene(const std::string& path);

// The (mirror-direction) Phong exponent a glTF roughness maps to: (2 / r^4 - 2) / 4, at most 1e6
// (below 1: the lobe is read as Lambert).
double phongExponentOfRoughness(double roughness);

} // namespace bl
