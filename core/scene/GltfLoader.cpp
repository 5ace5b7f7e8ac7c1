#include "scene/GltfLoader.h"

#include "base/Error.h"
#include "scene/MeshCleanup.h"
#include "scene/MeshTransform.h"
#include "scene/ShaderConversions.h"

#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <tiny_gltf.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <optional>
#include <set>

namespace bl {

namespace {

constexpr double kPi = 3.14159265358979323846;
// The extensions read here; a file that requires any other is refused.
const std::set<std::string> kReadExtensions = {"KHR_lights_punctual", "KHR_materials_emissive_strength"};
// A camera's image when the file gives only an aspect ratio (glTF has no film size): this many
// pixels on its shorter side (the command line's --width/--height override it).
constexpr int kShortSide = 512;

std::string quoted(const std::string& name) { return name.empty() ? std::string() : " '" + name + "'"; }

std::string formatted(const char* format, double a, double b = 0.0, double c = 0.0) {
    char text[160];
    std::snprintf(text, sizeof(text), format, a, b, c);
    return text;
}

// The names in a glTF file's top-level "extensionsRequired" array, read from its JSON text (the
// .glb's first chunk) with plain string scanning: used only after tinygltf has refused the file,
// because an extension it cannot decode (Draco, meshopt) makes it fail with an accessor error that
// does not name the extension.
std::vector<std::string> requiredExtensionsIn(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (text.size() >= 20 && text.compare(0, 4, "glTF") == 0) {
        std::uint32_t jsonLength = 0;
        std::memcpy(&jsonLength, text.data() + 12, 4);
        text = text.substr(20, std::min<std::size_t>(jsonLength, text.size() - 20));
    }
    std::vector<std::string> names;
    const auto key = text.find("\"extensionsRequired\"");
    if (key == std::string::npos) return names;
    const auto open = text.find('[', key), close = text.find(']', key);
    if (open == std::string::npos || close == std::string::npos || close < open) return names;
    for (auto q = text.find('"', open); q != std::string::npos && q < close;) {
        const auto end = text.find('"', q + 1);
        if (end == std::string::npos || end > close) break;
        names.push_back(text.substr(q + 1, end - q - 1));
        q = text.find('"', end + 1);
    }
    return names;
}

class Importer {
public:
    explicit Importer(const std::string& path) : mPath(path) {}

    Scene run() {
        load();
        for (const std::string& e : mModel.extensionsRequired) refuseUnread(e);
        for (const std::string& e : mModel.extensionsUsed) {
            if (!kReadExtensions.count(e)) note("extension " + e + " (used, not required) ignored");
        }
        if (!mModel.animations.empty()) note(std::to_string(mModel.animations.size()) + " animation(s) ignored: the scene at rest");
        if (!mModel.skins.empty()) note(std::to_string(mModel.skins.size()) + " skin(s) ignored: meshes in their bind pose");
        mScene.path = mPath;
        // External buffers and images (Scene::inputFiles); data URIs and a .glb's own chunk are
        // part of the file.
        for (const tinygltf::Buffer& b : mModel.buffers) {
            if (const std::string f = fileOf(b.uri); !f.empty()) mScene.inputFiles.push_back(f);
        }
        for (const tinygltf::Image& i : mModel.images) {
            if (const std::string f = fileOf(i.uri); !f.empty()) mScene.inputFiles.push_back(f);
        }
        const int sceneIndex = mModel.defaultScene >= 0 ? mModel.defaultScene : 0;
        if (mModel.scenes.empty()) {
            // A file of nodes and no scene: every root node.
            for (std::size_t n = 0; n < mModel.nodes.size(); ++n) {
                if (!isChild(int(n))) node(int(n), glm::dmat4(1.0));
            }
        } else {
            if (sceneIndex >= int(mModel.scenes.size())) fail("scene " + std::to_string(sceneIndex) + " does not exist");
            for (int n : mModel.scenes[std::size_t(sceneIndex)].nodes) node(n, glm::dmat4(1.0));
        }
        if (mScene.meshes.empty()) fail("the scene has no triangles");
        if (!mCameraSet) {
            mScene.camera = fitCamera(mScene.bounds(), mScene.camera.resolution);
            note("no camera in the scene: one fitted to its bounds (as for a bare mesh)");
        }
        if (mScene.materials.empty()) mScene.materials.emplace_back();
        mScene.importNotes = mNotes;
        return std::move(mScene);
    }

private:
    [[noreturn]] void fail(const std::string& what) const { throw Error(mPath + ": " + what); }

    // A node's transformed axis, unit; refused where the transform collapses it (a zero scale).
    glm::dvec3 unitAxis(const glm::dmat4& world, const glm::dvec3& axis, const std::string& what) const {
        const glm::dvec3 v(world * glm::dvec4(axis, 0.0));
        const double length = glm::length(v);
        if (!(length > 0.0 && std::isfinite(length))) fail(what + " is collapsed by its node's transform (a zero scale)");
        return v / length;
    }
    void note(const std::string& line) {
        if (std::find(mNotes.begin(), mNotes.end(), line) == mNotes.end()) mNotes.push_back(line);
    }

    void load() {
        tinygltf::TinyGLTF reader;
        std::string error, warning;
        std::string ext = std::filesystem::path(mPath).extension().string();
        std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
        const bool ok = ext == ".glb" ? reader.LoadBinaryFromFile(&mModel, &error, &warning, mPath)
                                      : reader.LoadASCIIFromFile(&mModel, &error, &warning, mPath);
        if (!warning.empty()) note("tinygltf: " + warning);
        mWarning = warning;
        if (!ok) {
            for (const std::string& e : requiredExtensionsIn(mPath)) refuseUnread(e);
            fail(error.empty() ? std::string("not a readable glTF file") : error);
        }
    }

    // The file a buffer's or image's uri names, beside the glTF file (percent-decoded, as tinygltf
    // reads it); empty for data URIs and for a .glb's own chunk (no uri).
    std::string fileOf(const std::string& uri) const {
        if (uri.empty() || uri.rfind("data:", 0) == 0) return "";
        std::string decoded;
        for (std::size_t i = 0; i < uri.size(); ++i) {
            const auto hex = [&](std::size_t k) { return std::isxdigit(static_cast<unsigned char>(uri[k])) != 0; };
            if (uri[i] == '%' && i + 2 < uri.size() && hex(i + 1) && hex(i + 2)) {
                decoded += static_cast<char>(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
                i += 2;
            } else {
                decoded += uri[i];
            }
        }
        return (std::filesystem::path(mPath).parent_path() / decoded).string();
    }

    void refuseUnread(const std::string& extension) const {
        if (!kReadExtensions.count(extension)) {
            fail("requires extension " + extension + ", which is not supported (read: KHR_lights_punctual, "
                 "KHR_materials_emissive_strength)");
        }
    }

    bool isChild(int n) const {
        for (const tinygltf::Node& p : mModel.nodes) {
            if (std::find(p.children.begin(), p.children.end(), n) != p.children.end()) return true;
        }
        return false;
    }

    // A node's transform relative to its parent: matrix, else translation * rotation * scale.
    static glm::dmat4 localTransform(const tinygltf::Node& n) {
        if (n.matrix.size() == 16) return glm::make_mat4(n.matrix.data()); // column-major, as glm
        glm::dmat4 m(1.0);
        if (n.translation.size() == 3) m = glm::translate(m, glm::dvec3(n.translation[0], n.translation[1], n.translation[2]));
        if (n.rotation.size() == 4) {
            m = m * glm::mat4_cast(glm::dquat(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2])); // (w, x, y, z)
        }
        if (n.scale.size() == 3) m = glm::scale(m, glm::dvec3(n.scale[0], n.scale[1], n.scale[2]));
        return m;
    }

    void node(int index, const glm::dmat4& parent) {
        if (index < 0 || index >= int(mModel.nodes.size())) fail("node " + std::to_string(index) + " does not exist");
        if (++mDepth > int(mModel.nodes.size())) fail("the node hierarchy has a cycle");
        const tinygltf::Node& n = mModel.nodes[std::size_t(index)];
        const glm::dmat4 world = parent * localTransform(n);
        const std::string where = "node " + std::to_string(index) + quoted(n.name);
        if (n.mesh >= 0) mesh(n.mesh, world, where);
        if (n.camera >= 0) camera(n.camera, world, where);
        if (const auto it = n.extensions.find("KHR_lights_punctual"); it != n.extensions.end()) {
            light(it->second, world, where);
        }
        for (int child : n.children) node(child, world);
        --mDepth;
    }

    // --- Geometry ---------------------------------------------------------------------------------

    // Element `i`'s components of an accessor as doubles (normalized integers scaled to [0, 1]).
    std::vector<double> read(const tinygltf::Accessor& a, std::size_t i, const std::string& what) const {
        if (a.sparse.isSparse) fail(what + ": sparse accessors are not supported");
        if (a.bufferView < 0) fail(what + ": an accessor without a buffer view (all zeros) is not supported");
        if (a.bufferView >= int(mModel.bufferViews.size())) fail(what + ": buffer view " + std::to_string(a.bufferView) + " does not exist");
        const tinygltf::BufferView& view = mModel.bufferViews[std::size_t(a.bufferView)];
        if (view.buffer < 0 || view.buffer >= int(mModel.buffers.size())) fail(what + ": buffer " + std::to_string(view.buffer) + " does not exist");
        const tinygltf::Buffer& buffer = mModel.buffers[std::size_t(view.buffer)];
        const int components = tinygltf::GetNumComponentsInType(std::uint32_t(a.type));
        const int size = tinygltf::GetComponentSizeInBytes(std::uint32_t(a.componentType));
        if (components <= 0 || size <= 0) fail(what + ": unknown accessor type");
        const int stride = a.ByteStride(view);
        const std::size_t start = view.byteOffset + a.byteOffset + i * std::size_t(stride);
        if (stride <= 0 || start + std::size_t(components * size) > buffer.data.size() ||
            start + std::size_t(components * size) > view.byteOffset + view.byteLength) {
            fail(what + ": element " + std::to_string(i) + " lies beyond its buffer");
        }
        std::vector<double> out(static_cast<std::size_t>(components));
        const unsigned char* p = buffer.data.data() + start;
        for (int c = 0; c < components; ++c, p += size) {
            switch (a.componentType) {
            case TINYGLTF_COMPONENT_TYPE_FLOAT: { float v; std::memcpy(&v, p, 4); out[std::size_t(c)] = v; break; }
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: out[std::size_t(c)] = *p / (a.normalized ? 255.0 : 1.0); break;
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
                std::uint16_t v; std::memcpy(&v, p, 2); out[std::size_t(c)] = v / (a.normalized ? 65535.0 : 1.0); break;
            }
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: { std::uint32_t v; std::memcpy(&v, p, 4); out[std::size_t(c)] = v; break; }
            default: fail(what + ": component type " + std::to_string(a.componentType) + " is not supported here");
            }
        }
        return out;
    }

    const tinygltf::Accessor& accessor(int index, const std::string& what) const {
        if (index < 0 || index >= int(mModel.accessors.size())) fail(what + ": accessor " + std::to_string(index) + " does not exist");
        return mModel.accessors[std::size_t(index)];
    }

    // A primitive's vertex attribute `name` (none when absent), each element's components: of
    // accessor type `type`, and `count` elements where count > 0 (the vertices POSITION gave).
    std::vector<std::vector<double>> vertexAttribute(const tinygltf::Primitive& prim, const std::string& name, int type,
                                                     std::size_t count, const std::string& what) const {
        const auto it = prim.attributes.find(name);
        if (it == prim.attributes.end()) return {};
        const std::string label = what + " " + name;
        const tinygltf::Accessor& a = accessor(it->second, label);
        if (a.type != type) fail(label + ": accessor type " + std::to_string(a.type) + ", " + std::to_string(type) + " expected");
        if (count > 0 && a.count != count) {
            fail(label + " has " + std::to_string(a.count) + " elements, POSITION " + std::to_string(count));
        }
        std::vector<std::vector<double>> out;
        // A position or texture coordinate that is not finite has no meaning to repair: refused. A
        // normal that is not finite is replaced by mesh cleanup (counted in "repaired normals").
        const bool mustBeFinite = name != "NORMAL";
        for (std::size_t i = 0; i < a.count; ++i) {
            out.push_back(read(a, i, label));
            for (double v : out.back()) {
                if (mustBeFinite && !std::isfinite(v)) {
                    fail(label + ": element " + std::to_string(i) + " is " + formatNumber(v) + " (not finite)");
                }
            }
        }
        return out;
    }

    void mesh(int index, const glm::dmat4& world, const std::string& where) {
        if (index >= int(mModel.meshes.size())) fail(where + ": mesh " + std::to_string(index) + " does not exist");
        const tinygltf::Mesh& gm = mModel.meshes[std::size_t(index)];
        const bool mirrored = glm::determinant(glm::dmat3(world)) < 0.0;
        for (std::size_t pi = 0; pi < gm.primitives.size(); ++pi) {
            const tinygltf::Primitive& prim = gm.primitives[pi];
            const std::string what = where + " mesh" + quoted(gm.name) + " primitive " + std::to_string(pi);
            if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != -1) {
                fail(what + ": mode " + std::to_string(prim.mode) + " is not supported (triangles only, mode 4)");
            }
            if (!prim.targets.empty()) note("morph targets ignored: meshes in their base shape");
            if (!prim.attributes.count("POSITION")) fail(what + ": no POSITION attribute");
            for (const auto& [name, unused] : prim.attributes) {
                if (name == "TEXCOORD_1" || name == "COLOR_0" || name == "TANGENT" || name.rfind("JOINTS", 0) == 0 ||
                    name.rfind("WEIGHTS", 0) == 0) {
                    note("vertex attribute " + name + " ignored");
                }
            }
            Mesh m;
            m.name = mPath + ":" + (gm.name.empty() ? "mesh" + std::to_string(index) : gm.name) + "." + std::to_string(pi);
            m.sourceFile = mPath;
            for (const std::vector<double>& v : vertexAttribute(prim, "POSITION", TINYGLTF_TYPE_VEC3, 0, what)) {
                m.positions.emplace_back(float(v[0]), float(v[1]), float(v[2]));
            }
            const std::size_t vertices = m.positions.size();
            for (const std::vector<double>& v : vertexAttribute(prim, "NORMAL", TINYGLTF_TYPE_VEC3, vertices, what)) {
                m.normals.emplace_back(float(v[0]), float(v[1]), float(v[2]));
            }
            for (const std::vector<double>& v : vertexAttribute(prim, "TEXCOORD_0", TINYGLTF_TYPE_VEC2, vertices, what)) {
                m.uvs.emplace_back(float(v[0]), float(1.0 - v[1])); // glTF's v runs down the image, ours up
            }
            std::vector<std::uint32_t> indices;
            if (prim.indices >= 0) {
                const tinygltf::Accessor& ia = accessor(prim.indices, what + " indices");
                if (ia.type != TINYGLTF_TYPE_SCALAR) fail(what + ": indices are not SCALAR");
                for (std::size_t i = 0; i < ia.count; ++i) {
                    const double v = read(ia, i, what + " indices")[0];
                    if (!(v >= 0.0 && v < double(vertices))) fail(what + ": index " + formatNumber(v) + " beyond its " + std::to_string(vertices) + " vertices");
                    indices.push_back(std::uint32_t(v));
                }
            } else {
                for (std::size_t i = 0; i < vertices; ++i) indices.push_back(std::uint32_t(i));
            }
            if (indices.size() % 3 != 0) fail(what + ": " + std::to_string(indices.size()) + " indices, not a multiple of 3");
            for (std::size_t i = 0; i + 2 < indices.size(); i += 3) {
                // A mirroring transform turns the winding: glTF's front face follows it, so turn it back.
                m.triangles.emplace_back(indices[i], mirrored ? indices[i + 2] : indices[i + 1],
                                         mirrored ? indices[i + 1] : indices[i + 2]);
            }
            bakeTransform(m, glm::mat4(world));
            NormalOptions normals;
            if (m.normals.empty()) {
                normals.source = NormalSource::Flat;
                note("a primitive without normals is shaded flat (glTF's rule)");
            }
            const CleanupStats stats = cleanupMesh(m, normals);
            mScene.loadStats.degenerateTriangles += stats.degenerateTriangles;
            mScene.loadStats.duplicateTriangles += stats.duplicateTriangles;
            mScene.loadStats.repairedNormals += stats.repairedNormals;
            if (m.triangles.empty()) continue;
            const auto [materialIndex, emission] = material(prim.material, what);
            if (!m.uvs.empty() || mScene.materials[materialIndex].albedoTexture < 0) {
                m.material = materialIndex;
            } else {
                fail(what + ": its material has a base colour texture but the primitive no TEXCOORD_0");
            }
            m.emission = emission;
            mScene.meshes.push_back(std::move(m));
        }
    }

    // --- Materials --------------------------------------------------------------------------------

    struct MaterialUse {
        std::uint32_t index;
        glm::vec3 emission;
    };

    MaterialUse material(int index, const std::string& what) {
        if (index < 0) {
            if (!mDefaultMaterial) {
                Material m;
                m.name = "default";
                m.albedo = glm::vec3(1.0f); // glTF's default: base colour 1, metallic 1, roughness 1
                mScene.materials.push_back(m);
                mDefaultMaterial = std::uint32_t(mScene.materials.size() - 1);
                note("primitives without a material: glTF's default (base colour 1, metallic 1, roughness 1), "
                     "a lobe that wide read as Lambert of albedo 1");
            }
            return {*mDefaultMaterial, glm::vec3(0.0f)};
        }
        if (index >= int(mModel.materials.size())) fail(what + ": material " + std::to_string(index) + " does not exist");
        if (const auto it = mMaterialOf.find(index); it != mMaterialOf.end()) return it->second;
        const tinygltf::Material& gm = mModel.materials[std::size_t(index)];
        const std::string name = "material " + std::to_string(index) + quoted(gm.name);
        const tinygltf::PbrMetallicRoughness& pbr = gm.pbrMetallicRoughness;
        const glm::dvec3 base(pbr.baseColorFactor[0], pbr.baseColorFactor[1], pbr.baseColorFactor[2]);
        const double metallic = std::clamp(pbr.metallicFactor, 0.0, 1.0);
        const double roughness = std::clamp(pbr.roughnessFactor, 0.0, 1.0);
        Material m;
        m.name = gm.name.empty() ? "material" + std::to_string(index) : gm.name;
        const double exponent = phongExponentOfRoughness(roughness);
        const bool lobe = metallic > 0.0 && exponent >= 1.0;
        if (lobe) {
            m.albedo = glm::vec3(base * (1.0 - metallic));
            m.specular = glm::vec3(base * metallic);
            m.exponentU = m.exponentV = float(exponent);
            note(name + ": metallic " + formatNumber(metallic) + ", roughness " + formatNumber(roughness) +
                 " -> Lambert of base x " + formatNumber(1.0 - metallic) + " + Phong lobe of base x " +
                 formatNumber(metallic) + ", exponent " + formatted("%.4g", exponent) + " ((2 / r^4 - 2) / 4)");
        } else {
            m.albedo = glm::vec3(base);
            note(name + (metallic > 0.0 ? ": roughness " + formatNumber(roughness) + " gives a lobe wider than Phong "
                                              "exponent 1: read as Lambert with the base colour"
                                        : ": dielectric -> Lambert with the base colour (its 4% specular reflection dropped)"));
        }
        if (pbr.baseColorTexture.index >= 0) {
            if (pbr.baseColorTexture.texCoord != 0) {
                fail(name + ": base colour texture on TEXCOORD_" + std::to_string(pbr.baseColorTexture.texCoord) +
                     " (only TEXCOORD_0 is read)");
            }
            if (lobe) {
                fail(name + ": a base colour texture on a metallic material (the glossy lobe's reflectance is not "
                     "textured here); metallic 0 is read");
            }
            m.albedoTexture = texture(pbr.baseColorTexture.index, glm::vec3(base), name);
        }
        if (pbr.metallicRoughnessTexture.index >= 0) note(name + ": metallic-roughness texture ignored (its factors used)");
        if (gm.normalTexture.index >= 0) note(name + ": normal texture ignored (the mesh's normals used)");
        if (gm.occlusionTexture.index >= 0) note(name + ": occlusion texture ignored (light transport computes occlusion)");
        if (gm.alphaMode != "OPAQUE" && !gm.alphaMode.empty()) note(name + ": alpha mode " + gm.alphaMode + " ignored (opaque)");
        if (gm.emissiveTexture.index >= 0) fail(name + ": emissive textures are not supported (emissive factors are)");
        double strength = 1.0;
        if (const auto it = gm.extensions.find("KHR_materials_emissive_strength"); it != gm.extensions.end() &&
                                                                                    it->second.Has("emissiveStrength")) {
            strength = it->second.Get("emissiveStrength").GetNumberAsDouble();
        }
        const glm::vec3 emission(glm::dvec3(gm.emissiveFactor[0], gm.emissiveFactor[1], gm.emissiveFactor[2]) * strength);
        if (!(emission.x >= 0.0f && emission.y >= 0.0f && emission.z >= 0.0f && std::isfinite(emission.x) &&
              std::isfinite(emission.y) && std::isfinite(emission.z))) {
            fail(name + ": emission must be finite and non-negative");
        }
        if ((emission.x > 0.0f || emission.y > 0.0f || emission.z > 0.0f) && gm.doubleSided) {
            note(name + ": double-sided emitter emits from its front face only (emission is one-sided here)");
        }
        mScene.materials.push_back(m);
        const MaterialUse use{std::uint32_t(mScene.materials.size() - 1), emission};
        mMaterialOf[index] = use;
        return use;
    }

    // A texture's image as sRGB RGBA8, the base colour factor multiplied in (in linear).
    int texture(int index, const glm::vec3& factor, const std::string& what) {
        if (index >= int(mModel.textures.size())) fail(what + ": texture " + std::to_string(index) + " does not exist");
        const int source = mModel.textures[std::size_t(index)].source;
        if (const int s = mModel.textures[std::size_t(index)].sampler; s >= 0 && s < int(mModel.samplers.size())) {
            const tinygltf::Sampler& sampler = mModel.samplers[std::size_t(s)];
            if (sampler.wrapS != TINYGLTF_TEXTURE_WRAP_REPEAT || sampler.wrapT != TINYGLTF_TEXTURE_WRAP_REPEAT) {
                note(what + ": its sampler's clamp or mirrored wrap ignored (textures repeat here)");
            }
        }
        if (source < 0 || source >= int(mModel.images.size())) fail(what + ": texture " + std::to_string(index) + " has no image");
        const tinygltf::Image& image = mModel.images[std::size_t(source)];
        if (image.image.empty() || image.width <= 0 || image.height <= 0) {
            fail(what + ": image " + std::to_string(source) + quoted(image.uri) + " could not be decoded" +
                 (mWarning.empty() ? std::string() : " (tinygltf: " + mWarning + ")"));
        }
        if (image.bits != 8 || image.component < 1 || image.component > 4) {
            fail(what + ": image " + std::to_string(source) + quoted(image.uri) + " has " + std::to_string(image.component) +
                 " channels of " + std::to_string(image.bits) + " bits (8-bit images are read)");
        }
        Rgba8Image out{image.width, image.height, std::vector<unsigned char>(std::size_t(image.width) * image.height * 4, 255)};
        const bool scale = factor != glm::vec3(1.0f);
        for (std::size_t p = 0; p < std::size_t(image.width) * image.height; ++p) {
            const unsigned char* in = &image.image[p * std::size_t(image.component)];
            for (int c = 0; c < 3; ++c) {
                unsigned char v = in[image.component < 3 ? 0 : c]; // grey images: one channel for all
                if (scale) {
                    const float linear = srgbToLinear(v / 255.0f) * factor[c];
                    v = static_cast<unsigned char>(std::lround(std::clamp(linearToSrgb(linear), 0.0f, 1.0f) * 255.0f));
                }
                out.texels[p * 4 + std::size_t(c)] = v;
            }
        }
        if (scale) note(what + ": base colour factor multiplied into its texture (in linear, re-encoded as sRGB 8-bit)");
        const std::string file = fileOf(image.uri);
        mScene.textures.push_back({file.empty() ? mPath + "#image" + std::to_string(source) : file, std::move(out)});
        return int(mScene.textures.size() - 1);
    }

    // --- Cameras and lights -----------------------------------------------------------------------

    void camera(int index, const glm::dmat4& world, const std::string& where) {
        if (index >= int(mModel.cameras.size())) fail(where + ": camera " + std::to_string(index) + " does not exist");
        if (mCameraSet) {
            note("more than one camera: the first in the node order used");
            return;
        }
        const tinygltf::Camera& c = mModel.cameras[std::size_t(index)];
        if (c.type != "perspective") fail(where + ": camera type " + c.type + " is not supported (perspective only)");
        const double yfov = c.perspective.yfov;
        if (!(yfov > 0.0 && yfov < kPi)) fail(where + ": yfov " + formatNumber(yfov) + " outside (0, pi)");
        Camera& cam = mScene.camera;
        cam.fovAxis = FovAxis::Y;
        cam.fovDegrees = float(yfov * 180.0 / kPi);
        const double aspect = c.perspective.aspectRatio > 0.0 ? c.perspective.aspectRatio : 1.0;
        cam.resolution = aspect >= 1.0 ? glm::ivec2(int(std::lround(kShortSide * aspect)), kShortSide)
                                       : glm::ivec2(kShortSide, int(std::lround(kShortSide / aspect)));
        note("camera: " + std::to_string(cam.resolution.x) + "x" + std::to_string(cam.resolution.y) +
             " pixels (glTF gives the aspect ratio only; --width/--height set the size)");
        // glTF's camera looks down its local -z with +y up.
        const glm::dvec3 position(world * glm::dvec4(0.0, 0.0, 0.0, 1.0));
        const glm::dvec3 forward = unitAxis(world, {0.0, 0.0, -1.0}, where + ": the camera's view axis");
        const glm::dvec3 up = unitAxis(world, {0.0, 1.0, 0.0}, where + ": the camera's up axis");
        cam.pose.position = glm::vec3(position);
        cam.pose.target = glm::vec3(position + forward);
        cam.pose.up = glm::vec3(up);
        mCameraSet = true;
    }

    void light(const tinygltf::Value& extension, const glm::dmat4& world, const std::string& where) {
        if (!extension.Has("light")) fail(where + ": KHR_lights_punctual without a light index");
        const int index = extension.Get("light").GetNumberAsInt();
        const auto it = mModel.extensions.find("KHR_lights_punctual");
        if (it == mModel.extensions.end() || !it->second.Has("lights") || index < 0 ||
            index >= int(it->second.Get("lights").ArrayLen())) {
            fail(where + ": KHR_lights_punctual light " + std::to_string(index) + " does not exist");
        }
        const tinygltf::Value& gl = it->second.Get("lights").Get(index);
        const std::string type = gl.Has("type") ? gl.Get("type").Get<std::string>() : "";
        glm::dvec3 colour(1.0);
        if (gl.Has("color")) {
            for (int c = 0; c < 3; ++c) colour[c] = gl.Get("color").Get(c).GetNumberAsDouble();
        }
        const double intensity = gl.Has("intensity") ? gl.Get("intensity").GetNumberAsDouble() : 1.0;
        const std::string what = where + " light " + std::to_string(index);
        if (type == "directional") {
            fail(what + ": directional lights are not supported (point and spot are; a distant light is a far point light or "
                 "an environment)");
        }
        if (type != "point" && type != "spot") fail(what + ": light type '" + type + "' is not supported (point, spot)");
        Light l;
        l.intensity = glm::vec3(colour * intensity);
        if (!(l.intensity.x >= 0.0f && l.intensity.y >= 0.0f && l.intensity.z >= 0.0f)) {
            fail(what + ": intensity must be non-negative");
        }
        l.position = glm::vec3(world * glm::dvec4(0.0, 0.0, 0.0, 1.0));
        note("KHR_lights_punctual intensity (candela) read as radiant intensity, W/sr per unit, colour x intensity");
        if (gl.Has("range")) note(what + ": range ignored (inverse square to infinity)");
        if (type == "spot") {
            l.type = Light::Type::Spot;
            l.direction = glm::vec3(unitAxis(world, {0.0, 0.0, -1.0}, what + ": the spot's axis"));
            double inner = 0.0, outer = kPi / 4.0;
            if (gl.Has("spot")) {
                const tinygltf::Value& s = gl.Get("spot");
                if (s.Has("innerConeAngle")) inner = s.Get("innerConeAngle").GetNumberAsDouble();
                if (s.Has("outerConeAngle")) outer = s.Get("outerConeAngle").GetNumberAsDouble();
            }
            if (!(inner >= 0.0 && inner < outer && outer <= kPi / 2.0)) {
                fail(what + ": spot cones inner " + formatNumber(inner) + ", outer " + formatNumber(outer) +
                     " (0 <= inner < outer <= pi/2)");
            }
            l.coneAngleDegrees = float(outer * 180.0 / kPi);
            if (spotConeSteps(l.coneAngleDegrees) < kMinSpotConeSteps) {
                fail(what + ": outer cone " + formatNumber(outer) + " rad is too narrow for 32-bit floats to render its "
                     "lit area within 10 % (the narrowest is about 0.063 degrees)");
            }
            l.falloffDegrees = float((outer - inner) * 180.0 / kPi);
            note(what + ": spot edge between the cones (inner " + formatted("%.4g", inner * 180.0 / kPi) + ", outer " +
                 formatted("%.4g", outer * 180.0 / kPi) + " degrees) is a smoothstep in cosine here, glTF's reference a "
                 "squared linear ramp in cosine: the same cones, a slightly different edge");
        }
        mScene.lights.push_back(l);
    }

    std::string mPath;
    std::string mWarning; // tinygltf's warnings while reading (a missing image is one, not an error)
    tinygltf::Model mModel;
    Scene mScene;
    std::vector<std::string> mNotes;
    std::map<int, MaterialUse> mMaterialOf;
    std::optional<std::uint32_t> mDefaultMaterial;
    bool mCameraSet = false;
    int mDepth = 0;
};

} // namespace

double phongExponentOfRoughness(double roughness) {
    const double alpha = roughness * roughness;
    // Walter et al.'s Blinn-Phong match 2 / alpha^2 - 2 is about the half vector; the scene model's
    // Phong lobe (shared/Brdf.h) is about the mirror direction, at twice the angle: a quarter.
    // Sharper than 1e6 (the scene files' limit, the sharpest lobe the stress suite checks) is held there.
    return alpha > 0.0 ? std::min((2.0 / (alpha * alpha) - 2.0) / 4.0, 1e6) : 1e6;
}

Scene loadGltfScene(const std::string& path) { return Importer(path).run(); }

} // namespace bl
