#include "support/GltfWriter.h"

#include "support/TestFiles.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace bl::test {

void appendFloats(std::vector<unsigned char>& bytes, const std::vector<float>& values) {
    const std::size_t at = bytes.size();
    bytes.resize(at + 4 * values.size());
    std::memcpy(bytes.data() + at, values.data(), 4 * values.size());
}

void appendUints(std::vector<unsigned char>& bytes, const std::vector<std::uint32_t>& values) {
    const std::size_t at = bytes.size();
    bytes.resize(at + 4 * values.size());
    std::memcpy(bytes.data() + at, values.data(), 4 * values.size());
}

std::string base64DataUri(const std::vector<unsigned char>& bytes) {
    static const char* kDigits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out = "data:application/octet-stream;base64,";
    for (std::size_t i = 0; i < bytes.size(); i += 3) {
        const std::uint32_t b = std::uint32_t(bytes[i]) << 16 | (i + 1 < bytes.size() ? std::uint32_t(bytes[i + 1]) << 8 : 0u) |
                                (i + 2 < bytes.size() ? std::uint32_t(bytes[i + 2]) : 0u);
        out += kDigits[b >> 18 & 63];
        out += kDigits[b >> 12 & 63];
        out += i + 1 < bytes.size() ? kDigits[b >> 6 & 63] : '=';
        out += i + 2 < bytes.size() ? kDigits[b & 63] : '=';
    }
    return out;
}

std::vector<unsigned char> glbOf(const std::string& json, const std::vector<unsigned char>& bin) {
    std::string text = json;
    while (text.size() % 4) text += ' ';
    std::vector<unsigned char> data = bin;
    while (data.size() % 4) data.push_back(0);
    std::vector<unsigned char> out;
    const auto u32 = [&](std::uint32_t v) {
        for (int i = 0; i < 4; ++i) out.push_back(static_cast<unsigned char>(v >> (8 * i)));
    };
    u32(0x46546C67u); // "glTF"
    u32(2u);
    u32(std::uint32_t(12 + 8 + text.size() + (data.empty() ? 0 : 8 + data.size())));
    u32(std::uint32_t(text.size()));
    u32(0x4E4F534Au); // "JSON"
    out.insert(out.end(), text.begin(), text.end());
    if (!data.empty()) {
        u32(std::uint32_t(data.size()));
        u32(0x004E4942u); // "BIN\0"
        out.insert(out.end(), data.begin(), data.end());
    }
    return out;
}

namespace {

std::string number(double v) {
    std::ostringstream s;
    s.precision(17);
    s << v;
    return s.str();
}

std::string vec(const glm::vec3& v) { return "[" + number(v.x) + ", " + number(v.y) + ", " + number(v.z) + "]"; }

} // namespace

std::string writeGltfScene(const Scene& scene, const std::string& name) {
    const bool binary = name.size() > 4 && name.substr(name.size() - 4) == ".glb";
    std::vector<unsigned char> bin;
    std::string accessors, views, meshes, nodes, materials, lights;
    int accessorCount = 0;
    // One buffer view and accessor per attribute, in a single buffer.
    const auto add = [&](const std::vector<float>* floats, const std::vector<std::uint32_t>* uints, const char* type,
                         std::size_t count, const std::string& minMax) {
        const std::size_t offset = bin.size();
        if (floats) appendFloats(bin, *floats);
        if (uints) appendUints(bin, *uints);
        if (!views.empty()) views += ",";
        views += "{\"buffer\": 0, \"byteOffset\": " + std::to_string(offset) + ", \"byteLength\": " +
                 std::to_string(bin.size() - offset) + "}";
        if (!accessors.empty()) accessors += ",";
        accessors += "{\"bufferView\": " + std::to_string(accessorCount) + ", \"componentType\": " +
                     (floats ? "5126" : "5125") + ", \"count\": " + std::to_string(count) + ", \"type\": \"" + type +
                     "\"" + minMax + "}";
        return accessorCount++;
    };
    for (std::size_t mi = 0; mi < scene.materials.size(); ++mi) {
        const Material& m = scene.materials[mi];
        if (m.glossy() || m.albedoTexture >= 0) throw std::runtime_error("writeGltfScene: Lambertian untextured materials only");
    }
    int materialCount = 0;
    for (std::size_t i = 0; i < scene.meshes.size(); ++i) {
        const Mesh& m = scene.meshes[i];
        std::vector<float> p, n;
        glm::vec3 lo(INFINITY), hi(-INFINITY);
        for (const glm::vec3& v : m.positions) {
            p.insert(p.end(), {v.x, v.y, v.z});
            lo = glm::min(lo, v);
            hi = glm::max(hi, v);
        }
        for (const glm::vec3& v : m.normals) n.insert(n.end(), {v.x, v.y, v.z});
        std::vector<std::uint32_t> idx;
        for (const glm::uvec3& t : m.triangles) idx.insert(idx.end(), {t.x, t.y, t.z});
        const int pa = add(&p, nullptr, "VEC3", m.positions.size(), ", \"min\": " + vec(lo) + ", \"max\": " + vec(hi));
        const int na = n.empty() ? -1 : add(&n, nullptr, "VEC3", m.normals.size(), "");
        const int ia = add(nullptr, &idx, "SCALAR", idx.size(), "");
        // A material per mesh: the scene's material with this mesh's emission.
        const Material& mat = scene.materials[m.material];
        if (!materials.empty()) materials += ",";
        materials += "{\"name\": \"" + mat.name + "\", \"pbrMetallicRoughness\": {\"baseColorFactor\": [" +
                     number(mat.albedo.x) + ", " + number(mat.albedo.y) + ", " + number(mat.albedo.z) +
                     ", 1], \"metallicFactor\": 0, \"roughnessFactor\": 1}";
        const float strength = std::max({m.emission.x, m.emission.y, m.emission.z});
        if (strength > 0.0f) {
            materials += ", \"emissiveFactor\": " + vec(m.emission / strength) +
                         ", \"extensions\": {\"KHR_materials_emissive_strength\": {\"emissiveStrength\": " +
                         number(strength) + "}}";
        }
        materials += "}";
        if (!meshes.empty()) meshes += ",";
        meshes += "{\"primitives\": [{\"attributes\": {\"POSITION\": " + std::to_string(pa) +
                  (na >= 0 ? ", \"NORMAL\": " + std::to_string(na) : std::string()) + "}, \"indices\": " +
                  std::to_string(ia) + ", \"material\": " + std::to_string(materialCount++) + "}]}";
        if (!nodes.empty()) nodes += ",";
        nodes += "{\"mesh\": " + std::to_string(i) + "}";
    }
    for (std::size_t i = 0; i < scene.lights.size(); ++i) {
        const Light& l = scene.lights[i];
        if (l.type != Light::Type::Point) throw std::runtime_error("writeGltfScene: point lights only");
        const float strength = std::max({l.intensity.x, l.intensity.y, l.intensity.z});
        if (!lights.empty()) lights += ",";
        lights += "{\"type\": \"point\", \"color\": " + vec(strength > 0.0f ? l.intensity / strength : glm::vec3(1.0f)) +
                  ", \"intensity\": " + number(strength) + "}";
        nodes += ",{\"translation\": " + vec(l.position) + ", \"extensions\": {\"KHR_lights_punctual\": {\"light\": " +
                 std::to_string(i) + "}}}";
    }
    // The camera: columns right, up, back (glTF looks down -z), position.
    const Camera& c = scene.camera;
    const glm::vec3 forward = glm::normalize(c.pose.target - c.pose.position);
    const glm::vec3 right = glm::normalize(glm::cross(forward, c.pose.up));
    const glm::vec3 up = glm::cross(right, forward);
    const double aspect = double(c.resolution.x) / double(c.resolution.y);
    const double half = double(c.fovDegrees) * 3.14159265358979323846 / 360.0;
    const double yfov = c.fovAxis == FovAxis::Y ? 2.0 * half : 2.0 * std::atan(std::tan(half) / aspect);
    nodes += ",{\"camera\": 0, \"matrix\": [" + number(right.x) + "," + number(right.y) + "," + number(right.z) + ",0," +
             number(up.x) + "," + number(up.y) + "," + number(up.z) + ",0," + number(-forward.x) + "," +
             number(-forward.y) + "," + number(-forward.z) + ",0," + number(c.pose.position.x) + "," +
             number(c.pose.position.y) + "," + number(c.pose.position.z) + ",1]}";
    const std::size_t nodeCount = scene.meshes.size() + scene.lights.size() + 1;
    std::string sceneNodes;
    for (std::size_t i = 0; i < nodeCount; ++i) sceneNodes += (i ? "," : "") + std::to_string(i);
    std::string json = "{\"asset\": {\"version\": \"2.0\", \"generator\": \"bundlelab tests\"},"
                       "\"extensionsUsed\": [\"KHR_lights_punctual\", \"KHR_materials_emissive_strength\"],"
                       "\"scene\": 0, \"scenes\": [{\"nodes\": [" + sceneNodes + "]}], \"nodes\": [" + nodes +
                       "], \"meshes\": [" + meshes + "], \"materials\": [" + materials +
                       "], \"cameras\": [{\"type\": \"perspective\", \"perspective\": {\"yfov\": " + number(yfov) +
                       ", \"aspectRatio\": " + number(aspect) + ", \"znear\": 0.01}}]," +
                       "\"extensions\": {\"KHR_lights_punctual\": {\"lights\": [" + lights + "]}}," +
                       "\"accessors\": [" + accessors + "], \"bufferViews\": [" + views + "], \"buffers\": [{" +
                       (binary ? std::string() : "\"uri\": \"" + base64DataUri(bin) + "\", ") +
                       "\"byteLength\": " + std::to_string(bin.size()) + "}]}";
    if (!binary) return writeTempFile(name, json);
    const std::vector<unsigned char> glb = glbOf(json, bin);
    const std::string path = writeTempFile(name, "");
    std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(glb.data()), std::streamsize(glb.size()));
    return path;
}

} // namespace bl::test
