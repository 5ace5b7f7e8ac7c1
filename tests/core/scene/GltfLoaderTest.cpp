// glTF 2.0 import (core/scene/GltfLoader.h): what each supported element becomes, and a clear error
// for what the scene model cannot hold. Files are written by the tests (support/GltfWriter.h and
// hand-written JSON); the point-lit Cornell box round trip against its TOML twin is in
// tests/modes/reference/GltfTwinTest.cpp.
#include "scene/GltfLoader.h"
#include "scene/SceneLoader.h"
#include "support/GltfWriter.h"
#include "support/TestFiles.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>

using namespace bl;
using bl::test::errorOf;

namespace {

bool near(const glm::vec3& a, const glm::vec3& b, float tolerance = 1e-5f) {
    return glm::all(glm::lessThanEqual(glm::abs(a - b), glm::vec3(tolerance)));
}

bool noted(const Scene& s, const std::string& text) {
    return std::any_of(s.importNotes.begin(), s.importNotes.end(),
                       [&](const std::string& n) { return n.find(text) != std::string::npos; });
}

// A unit right triangle (0,0,0), (1,0,0), (0,1,0) facing +z, with normals and UVs (u = x, v = y
// in glTF's convention: v runs down the image), as accessors 0 (POSITION), 1 (NORMAL), 2
// (TEXCOORD_0), 3 (indices), and the JSON around `body` (nodes, meshes, materials, ...).
std::string triangleFile(const std::string& name, const std::string& body, const std::string& extra = "") {
    std::vector<unsigned char> bin;
    bl::test::appendFloats(bin, {0, 0, 0, 1, 0, 0, 0, 1, 0});
    bl::test::appendFloats(bin, {0, 0, 1, 0, 0, 1, 0, 0, 1});
    bl::test::appendFloats(bin, {0, 0, 1, 0, 0, 1});
    bl::test::appendUints(bin, {0, 1, 2});
    const std::string json = R"({"asset": {"version": "2.0"}, )" + extra + R"("accessors": [
        {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0,0,0], "max": [1,1,0]},
        {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC3"},
        {"bufferView": 2, "componentType": 5126, "count": 3, "type": "VEC2"},
        {"bufferView": 3, "componentType": 5125, "count": 3, "type": "SCALAR"}],
      "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 36},
                      {"buffer": 0, "byteOffset": 72, "byteLength": 24}, {"buffer": 0, "byteOffset": 96, "byteLength": 12}],
      "buffers": [{"uri": ")" + bl::test::base64DataUri(bin) + R"(", "byteLength": 108}], )" + body + "}";
    return bl::test::writeTempFile(name, json);
}

const char* kTriangleMesh = R"("meshes": [{"name": "tri", "primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3, "material": 0}]}])";

// A 2 x 1 24-bit BMP (stb reads it; tinygltf takes image/bmp data URIs): left texel red 200,
// right texel green 100, as a data URI.
std::string bmpDataUri() {
    std::vector<unsigned char> b = {'B', 'M'};
    const auto u32 = [&](std::uint32_t v) { for (int i = 0; i < 4; ++i) b.push_back(static_cast<unsigned char>(v >> (8 * i))); };
    const auto u16 = [&](std::uint16_t v) { for (int i = 0; i < 2; ++i) b.push_back(static_cast<unsigned char>(v >> (8 * i))); };
    u32(54 + 8); u32(0); u32(54);                 // file size, reserved, pixel offset
    u32(40); u32(2); u32(1); u16(1); u16(24);     // info header: size, width, height, planes, bits
    u32(0); u32(8); u32(2835); u32(2835); u32(0); u32(0);
    b.insert(b.end(), {0, 0, 200, 0, 100, 0, 0, 0}); // BGR BGR + row padding to 4 bytes
    std::string uri = bl::test::base64DataUri(b);
    return "data:image/bmp;base64," + uri.substr(uri.find(',') + 1);
}

} // namespace

// Nodes compose parent first: the parent moves by (0, 0, 5) and turns 90 degrees about +y, the
// child scales by 2: the triangle's (1, 0, 0) lands at (0, 0, 3) (2 along x, turned to -z, moved),
// its normal +z turns to +x; no camera: one is fitted to the bounds (noted).
TEST(GltfLoader, NodeTransformsComposeParentFirst) {
    const Scene s = loadScene(triangleFile("nodes.gltf", std::string(kTriangleMesh) + R"(,
        "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.25, 0.125, 1], "metallicFactor": 0}}],
        "scenes": [{"nodes": [0]}],
        "nodes": [{"translation": [0, 0, 5], "rotation": [0, 0.70710678, 0, 0.70710678], "children": [1]},
                  {"scale": [2, 2, 2], "mesh": 0}])"));
    ASSERT_EQ(s.meshes.size(), 1u);
    const Mesh& m = s.meshes[0];
    ASSERT_EQ(m.positions.size(), 3u);
    EXPECT_TRUE(near(m.positions[0], {0, 0, 5}));
    EXPECT_TRUE(near(m.positions[1], {0, 0, 3}));
    EXPECT_TRUE(near(m.positions[2], {0, 2, 5}));
    EXPECT_TRUE(near(m.normals[0], {1, 0, 0}));
    // glTF's v runs down the image, the scene model's up.
    EXPECT_TRUE(glm::all(glm::equal(m.uvs[2], glm::vec2(0.0f, 0.0f))));
    EXPECT_TRUE(glm::all(glm::equal(m.uvs[0], glm::vec2(0.0f, 1.0f))));
    EXPECT_TRUE(near(s.materials[m.material].albedo, {0.5f, 0.25f, 0.125f}));
    EXPECT_FALSE(s.materials[m.material].glossy());
    EXPECT_TRUE(noted(s, "no camera in the scene"));
    EXPECT_TRUE(noted(s, "dielectric -> Lambert"));
}

// Translation, rotation and scale of one node apply as T * R * S (scale first): the triangle scaled
// by (2, 3, 1), turned 90 degrees about +z (x -> y, y -> -x), moved by (10, 0, 0). T * S * R would
// put (1, 0, 0) at (10, 3, 0) instead of (10, 2, 0).
TEST(GltfLoader, NodeTranslationRotationScaleApplyScaleFirst) {
    const Scene s = loadScene(triangleFile("trs.gltf", std::string(kTriangleMesh) + R"(,
        "materials": [{}], "scenes": [{"nodes": [0]}],
        "nodes": [{"translation": [10, 0, 0], "rotation": [0, 0, 0.70710678, 0.70710678], "scale": [2, 3, 1], "mesh": 0}])"));
    const Mesh& m = s.meshes.at(0);
    EXPECT_TRUE(near(m.positions[0], {10, 0, 0}));
    EXPECT_TRUE(near(m.positions[1], {10, 2, 0}));
    EXPECT_TRUE(near(m.positions[2], {7, 0, 0}));
}

// A mirroring transform (scale -1 in x) turns the winding back, so the front face is where the
// (mirrored) normal points, as glTF says; without it the triangle would face away from its normal.
TEST(GltfLoader, MirroringTransformKeepsTheFrontFace) {
    const Scene s = loadScene(triangleFile("mirror.gltf", std::string(kTriangleMesh) + R"(,
        "materials": [{}], "scenes": [{"nodes": [0]}], "nodes": [{"scale": [-1, 1, 1], "mesh": 0}])"));
    const Mesh& m = s.meshes.at(0);
    const glm::uvec3 t = m.triangles.at(0);
    const glm::vec3 geometric = glm::cross(m.positions[t.y] - m.positions[t.x], m.positions[t.z] - m.positions[t.x]);
    EXPECT_GT(glm::dot(geometric, m.normals[t.x]), 0.0f) << "winding and normal disagree";
}

// Materials: metallic 1, roughness 0.5 -> Phong exponent (2 / 0.5^4 - 2) / 4 = 7.5 with the base colour as
// its reflectance; the default material (none given: metallic 1, roughness 1, a lobe wider than
// Phong's exponent 1) reads as Lambert of albedo 1; emission x KHR_materials_emissive_strength.
TEST(GltfLoader, MaterialsMapToLambertAndPhong) {
    EXPECT_DOUBLE_EQ(phongExponentOfRoughness(0.5), 7.5);
    EXPECT_DOUBLE_EQ(phongExponentOfRoughness(0.0), 1e6);
    const Scene s = loadScene(triangleFile("materials.gltf", R"("meshes": [{"primitives": [
            {"attributes": {"POSITION": 0}, "indices": 3, "material": 0},
            {"attributes": {"POSITION": 0}, "indices": 3, "material": 1},
            {"attributes": {"POSITION": 0}, "indices": 3}]}],
        "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [0.9, 0.6, 0.3, 1], "metallicFactor": 1, "roughnessFactor": 0.5}},
                      {"emissiveFactor": [1, 0.5, 0], "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 4}},
                       "pbrMetallicRoughness": {"metallicFactor": 0}}],
        "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}])", R"("extensionsUsed": ["KHR_materials_emissive_strength"], )"));
    ASSERT_EQ(s.meshes.size(), 3u);
    const Material& metal = s.materials[s.meshes[0].material];
    EXPECT_TRUE(near(metal.specular, {0.9f, 0.6f, 0.3f}));
    EXPECT_TRUE(near(metal.albedo, {0, 0, 0}));
    EXPECT_FLOAT_EQ(metal.exponentU, 7.5f);
    EXPECT_TRUE(near(s.meshes[1].emission, {4, 2, 0}));
    EXPECT_TRUE(near(s.materials[s.meshes[2].material].albedo, {1, 1, 1}));
    EXPECT_FALSE(s.materials[s.meshes[2].material].glossy());
    // A primitive without normals is shaded flat.
    EXPECT_TRUE(near(s.meshes[0].normals[0], {0, 0, 1}));
    EXPECT_TRUE(noted(s, "shaded flat"));
}

// The camera node's pose (glTF looks down -z, +y up) turned 180 degrees about y and placed at
// (0, 1, -4): it looks down +z; yfov along y; the image's size from the aspect ratio. Point and
// spot lights by KHR_lights_punctual: colour x intensity, the spot's cones and its axis (-z).
TEST(GltfLoader, CameraAndPunctualLights) {
    const Scene s = loadScene(triangleFile("camera.gltf", std::string(kTriangleMesh) + R"(,
        "materials": [{}],
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.5, "aspectRatio": 2.0, "znear": 0.1}}],
        "extensions": {"KHR_lights_punctual": {"lights": [
            {"type": "point", "color": [1, 0.5, 0.25], "intensity": 8},
            {"type": "spot", "intensity": 2, "spot": {"innerConeAngle": 0.2, "outerConeAngle": 0.5}}]}},
        "scenes": [{"nodes": [0, 1, 2, 3]}],
        "nodes": [{"mesh": 0}, {"camera": 0, "translation": [0, 1, -4], "rotation": [0, 1, 0, 0]},
                  {"translation": [1, 2, 3], "extensions": {"KHR_lights_punctual": {"light": 0}}},
                  {"rotation": [-0.70710678, 0, 0, 0.70710678], "extensions": {"KHR_lights_punctual": {"light": 1}}}])",
        R"("extensionsUsed": ["KHR_lights_punctual"], )"));
    EXPECT_TRUE(near(s.camera.pose.position, {0, 1, -4}));
    EXPECT_TRUE(near(glm::normalize(s.camera.pose.target - s.camera.pose.position), {0, 0, 1}));
    EXPECT_TRUE(near(s.camera.pose.up, {0, 1, 0}));
    EXPECT_EQ(s.camera.fovAxis, FovAxis::Y);
    EXPECT_NEAR(s.camera.fovDegrees, 0.5 * 180.0 / 3.14159265358979323846, 1e-4);
    EXPECT_EQ(s.camera.resolution, glm::ivec2(1024, 512));
    ASSERT_EQ(s.lights.size(), 2u);
    EXPECT_EQ(s.lights[0].type, Light::Type::Point);
    EXPECT_TRUE(near(s.lights[0].position, {1, 2, 3}));
    EXPECT_TRUE(near(s.lights[0].intensity, {8, 4, 2}));
    EXPECT_EQ(s.lights[1].type, Light::Type::Spot);
    EXPECT_TRUE(near(s.lights[1].direction, {0, -1, 0})); // -z turned -90 degrees about x
    EXPECT_NEAR(s.lights[1].coneAngleDegrees, 0.5 * 180.0 / 3.14159265358979323846, 1e-4);
    EXPECT_NEAR(s.lights[1].falloffDegrees, 0.3 * 180.0 / 3.14159265358979323846, 1e-4);
    EXPECT_TRUE(noted(s, "candela"));
}

// What the model cannot hold is refused, naming the element and what is supported.
TEST(GltfLoader, RefusesWhatItCannotHold) {
    const auto error = [](const std::string& name, const std::string& body, const std::string& extra = "") {
        return errorOf([&] { loadScene(triangleFile(name, body, extra)); });
    };
    const std::string nodes = R"(, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}])";
    EXPECT_NE(error("lines.gltf", R"("meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "mode": 1}]}])" + nodes)
                  .find("mode 1 is not supported (triangles only"),
              std::string::npos);
    EXPECT_NE(error("draco.gltf", std::string(kTriangleMesh) + ", \"materials\": [{}]" + nodes,
                    R"("extensionsRequired": ["KHR_draco_mesh_compression"], "extensionsUsed": ["KHR_draco_mesh_compression"], )")
                  .find("requires extension KHR_draco_mesh_compression"),
              std::string::npos);
    EXPECT_NE(error("sun.gltf", std::string(kTriangleMesh) + R"(, "materials": [{}],
                    "extensions": {"KHR_lights_punctual": {"lights": [{"type": "directional"}]}},
                    "scenes": [{"nodes": [0, 1]}], "nodes": [{"mesh": 0}, {"extensions": {"KHR_lights_punctual": {"light": 0}}}])")
                  .find("directional lights are not supported"),
              std::string::npos);
    EXPECT_NE(error("ortho.gltf", std::string(kTriangleMesh) + R"(, "materials": [{}],
                    "cameras": [{"type": "orthographic", "orthographic": {"xmag": 1, "ymag": 1, "znear": 0, "zfar": 1}}],
                    "scenes": [{"nodes": [0, 1]}], "nodes": [{"mesh": 0}, {"camera": 0}])")
                  .find("camera type orthographic is not supported"),
              std::string::npos);
    const std::string index = error("index.gltf", R"("meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 7}]}],
                    "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}])");
    EXPECT_NE(index.find("index.gltf: primitive indices accessor out of bounds"), std::string::npos) << index; // tinygltf's check
    const std::string emissive = error("emissive.gltf", std::string(kTriangleMesh) + R"(, "materials": [{"emissiveFactor": [1, 1, 1],
                    "emissiveTexture": {"index": 0}}], "textures": [{"source": 0}], "images": [{"uri": "none.png"}])" + nodes);
    EXPECT_NE(emissive.find("material 0: emissive textures are not supported"), std::string::npos) << emissive;
    const std::string missing = errorOf([] { loadScene(bl::test::tempDir() + "/no-such.glb"); });
    EXPECT_NE(missing.find("no-such.glb"), std::string::npos) << missing;
    const std::string broken = errorOf([] { loadScene(bl::test::writeTempFile("broken.gltf", "{\"asset\": ")); });
    EXPECT_NE(broken.find("broken.gltf"), std::string::npos) << broken;
}

// A base colour texture: its sRGB texels kept where the factor is 1, the factor multiplied in
// (in linear, re-encoded) where it is not; the UVs flipped to the scene model's v-up.
TEST(GltfLoader, BaseColourTexturesKeepTheirTexels) {
    const std::string images = R"("textures": [{"source": 0}], "images": [{"uri": ")" + bmpDataUri() + R"("}])";
    const Scene s = loadScene(triangleFile("textured.gltf", std::string(kTriangleMesh) + R"(,
        "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0}}], )" + images + R"(,
        "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}])"));
    const Material& m = s.materials.at(s.meshes.at(0).material);
    ASSERT_GE(m.albedoTexture, 0);
    const Rgba8Image& t = s.textures.at(std::size_t(m.albedoTexture)).image;
    ASSERT_EQ(t.width, 2);
    ASSERT_EQ(t.height, 1);
    EXPECT_EQ(std::vector<unsigned char>(t.texels.begin(), t.texels.begin() + 8),
              (std::vector<unsigned char>{200, 0, 0, 255, 0, 100, 0, 255}));
    const Scene half = loadScene(triangleFile("textured-half.gltf", std::string(kTriangleMesh) + R"(,
        "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "baseColorFactor": [0.5, 1, 1, 1], "metallicFactor": 0}}], )" +
        images + R"(, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}])"));
    const Rgba8Image& h = half.textures.at(0).image;
    EXPECT_EQ(h.texels[0], static_cast<unsigned char>(std::lround(linearToSrgb(0.5f * srgbToLinear(200 / 255.0f)) * 255.0f)));
    EXPECT_EQ(h.texels[5], 100); // green untouched by a red factor
    EXPECT_TRUE(noted(half, "base colour factor multiplied into its texture"));
}

// The GLB container holds the same scene as the .gltf: written both ways, read back the same.
TEST(GltfLoader, GlbAndGltfReadTheSame) {
    Scene s;
    Mesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
    m.normals.assign(4, glm::vec3(0, 0, 1));
    m.triangles = {{0, 1, 2}, {1, 3, 2}};
    m.emission = glm::vec3(2.0f, 1.0f, 0.5f);
    s.meshes.push_back(m);
    s.materials.push_back(Material{});
    s.materials[0].albedo = glm::vec3(0.3f, 0.4f, 0.5f);
    Light l;
    l.position = glm::vec3(0.5f, 0.5f, 1.0f);
    l.intensity = glm::vec3(3.0f, 2.0f, 1.0f);
    s.lights.push_back(l);
    s.camera.pose = {{0.5f, 0.5f, 3.0f}, {0.5f, 0.5f, 0.0f}, {0, 1, 0}};
    s.camera.fovDegrees = 40.0f;
    s.camera.fovAxis = FovAxis::X;
    s.camera.resolution = {64, 32};
    const Scene a = loadScene(bl::test::writeGltfScene(s, "quad.gltf"));
    const Scene b = loadScene(bl::test::writeGltfScene(s, "quad.glb"));
    for (const Scene* r : {&a, &b}) {
        ASSERT_EQ(r->meshes.size(), 1u);
        EXPECT_EQ(r->meshes[0].positions, m.positions);
        EXPECT_EQ(r->meshes[0].triangles, m.triangles);
        EXPECT_TRUE(near(r->meshes[0].emission, m.emission));
        EXPECT_TRUE(near(r->materials[r->meshes[0].material].albedo, s.materials[0].albedo));
        ASSERT_EQ(r->lights.size(), 1u);
        EXPECT_TRUE(near(r->lights[0].intensity, l.intensity));
        EXPECT_TRUE(near(r->camera.pose.position, s.camera.pose.position));
        EXPECT_EQ(r->camera.resolution, glm::ivec2(1024, 512)); // the aspect ratio only
    }
}
