// Writes glTF 2.0 files for the importer's tests (core/scene/GltfLoader.h): a scene model's
// meshes, diffuse materials, point lights and camera as one .gltf (buffer embedded as a base64
// data URI) or .glb, and the pieces a hand-written test file needs (a binary buffer as a data
// URI, the GLB container around any JSON).
#pragma once

#include "scene/Scene.h"

#include <cstdint>
#include <string>
#include <vector>

namespace bl::test {

// Appends float / uint32 values to a byte buffer (little-endian, as glTF).
void appendFloats(std::vector<unsigned char>& bytes, const std::vector<float>& values);
void appendUints(std::vector<unsigned char>& bytes, const std::vector<std::uint32_t>& values);
std::string base64DataUri(const std::vector<unsigned char>& bytes);

// The GLB container: `json` and the binary chunk `bin` (the JSON's buffer 0 has no uri).
std::vector<unsigned char> glbOf(const std::string& json, const std::vector<unsigned char>& bin);

// `scene` as glTF: one node per mesh (identity transform; positions in world units), one material
// per scene material (Lambert: base colour = albedo, metallic 0, roughness 1; emission as
// emissiveFactor with KHR_materials_emissive_strength), point lights as KHR_lights_punctual, the
// camera as a perspective camera node. Writes `name` (.gltf or .glb) in the test's temporary
// directory and returns its path. Throws for what it cannot write (textures, glossy lobes, spots).
std::string writeGltfScene(const Scene& scene, const std::string& name);

} // namespace bl::test
