// Wavefront OBJ + MTL. Our own parser rather than tinyobjloader so that every error names the file
// and line, and a NaN coordinate is an error instead of a silent zero.
#include "base/Error.h"
#include "base/Log.h"
#include "scene/MeshFile.h"
#include "scene/MtlLoader.h"
#include "scene/TextParsing.h"

#include <filesystem>
#include <unordered_map>

namespace fs = std::filesystem;

namespace bl {
namespace {

struct MeshBuilder {
    Mesh mesh;
    std::unordered_map<std::uint64_t, std::uint32_t> vertexOf; // (v, vt, vn) -> vertex
    bool anyNormal = false;
    bool anyUv = false;
};

struct CornerIndex {
    long long v = -1, vt = -1, vn = -1; // zero-based, -1 = absent
};

long long resolveIndex(const TextLines& in, std::string_view token, std::size_t count,
                       const char* what) {
    long long i = in.toInteger(token);
    long long r = i > 0 ? i - 1 : static_cast<long long>(count) + i;
    if (i == 0 || r < 0 || r >= static_cast<long long>(count)) {
        in.fail("face refers to " + std::string(what) + " " + std::to_string(i) + " but only " +
                std::to_string(count) + " exist");
    }
    return r;
}

} // namespace

MeshFile loadObj(const std::string& path, bool readMaterials) {
    TextLines in(path);
    std::vector<glm::vec3> v, vn;
    std::vector<glm::vec2> vt;
    MtlLibrary library;
    MeshFile out;
    std::vector<MeshBuilder> builders;
    std::unordered_map<std::string, std::size_t> builderOf; // material name -> builder
    std::string currentMaterial;
    std::size_t faces = 0;

    auto builderFor = [&](const std::string& material) -> MeshBuilder& {
        auto it = builderOf.find(material);
        if (it != builderOf.end()) {
            return builders[it->second];
        }
        builderOf[material] = builders.size();
        MeshBuilder& b = builders.emplace_back();
        b.mesh.name = fs::path(path).filename().string() + ":" + (material.empty() ? "default" : material);
        b.mesh.sourceFile = path;
        b.mesh.material = library.indexOf(material, out, path, in.lineNumber());
        return b;
    };

    std::vector<std::string_view> t;
    std::vector<CornerIndex> corners;
    while (in.next(t)) {
        if (t.empty()) {
            continue;
        }
        const std::string_view key = t[0];
        if (key == "v") {
            if (t.size() < 4) {
                in.fail("vertex needs 3 coordinates");
            }
            v.emplace_back(in.toFloat(t[1]), in.toFloat(t[2]), in.toFloat(t[3]));
        } else if (key == "vn") {
            if (t.size() < 4) {
                in.fail("normal needs 3 coordinates");
            }
            vn.emplace_back(in.toFloat(t[1]), in.toFloat(t[2]), in.toFloat(t[3]));
        } else if (key == "vt") {
            if (t.size() < 2) {
                in.fail("texture coordinate needs at least u");
            }
            vt.emplace_back(in.toFloat(t[1]), t.size() > 2 ? in.toFloat(t[2]) : 0.0f);
        } else if (key == "f") {
            if (t.size() < 4) {
                in.fail("face needs at least 3 vertices");
            }
            corners.clear();
            for (std::size_t k = 1; k < t.size(); ++k) {
                std::string_view s = t[k];
                CornerIndex c;
                std::size_t a = s.find('/');
                c.v = resolveIndex(in, s.substr(0, a), v.size(), "vertex");
                if (a != std::string_view::npos) {
                    std::size_t b = s.find('/', a + 1);
                    std::string_view uv = s.substr(a + 1, b == std::string_view::npos ? s.npos : b - a - 1);
                    if (!uv.empty()) {
                        c.vt = resolveIndex(in, uv, vt.size(), "texture coordinate");
                    }
                    if (b != std::string_view::npos && b + 1 < s.size()) {
                        c.vn = resolveIndex(in, s.substr(b + 1), vn.size(), "normal");
                    }
                }
                corners.push_back(c);
            }
            MeshBuilder& b = builderFor(currentMaterial);
            std::uint32_t ids[3];
            auto vertexId = [&](const CornerIndex& c) {
                std::uint64_t cornerKey = (static_cast<std::uint64_t>(c.v) << 42) ^
                                    (static_cast<std::uint64_t>(c.vt + 1) << 21) ^
                                    static_cast<std::uint64_t>(c.vn + 1);
                auto [it, inserted] = b.vertexOf.try_emplace(cornerKey, 0u);
                if (inserted) {
                    it->second = static_cast<std::uint32_t>(b.mesh.positions.size());
                    b.mesh.positions.push_back(v[c.v]);
                    b.mesh.normals.push_back(c.vn >= 0 ? vn[c.vn] : glm::vec3(0.0f));
                    b.mesh.uvs.push_back(c.vt >= 0 ? vt[c.vt] : glm::vec2(0.0f));
                    b.anyNormal |= c.vn >= 0;
                    b.anyUv |= c.vt >= 0;
                }
                return it->second;
            };
            // Fan triangulation of convex polygons (what OBJ exporters write).
            ids[0] = vertexId(corners[0]);
            for (std::size_t k = 1; k + 1 < corners.size(); ++k) {
                ids[1] = vertexId(corners[k]);
                ids[2] = vertexId(corners[k + 1]);
                b.mesh.triangles.emplace_back(ids[0], ids[1], ids[2]);
            }
            ++faces;
        } else if (!readMaterials && (key == "usemtl" || key == "mtllib")) {
            // The scene gives the material.
        } else if (key == "usemtl") {
            currentMaterial = t.size() > 1 ? std::string(t[1]) : "";
        } else if (key == "mtllib") {
            for (std::size_t k = 1; k < t.size(); ++k) {
                library.load((fs::path(path).parent_path() / std::string(t[k])).string(), path,
                             in.lineNumber());
            }
        }
        // o, g, s, l, p and vendor extensions carry nothing we render.
    }

    for (MeshBuilder& b : builders) {
        if (b.mesh.triangles.empty()) {
            continue;
        }
        // A mesh with only some normals given gets face normals for all (cleanup does it).
        bool complete = b.anyNormal;
        for (const glm::vec3& n : b.mesh.normals) {
            complete = complete && glm::dot(n, n) > 0.0f;
        }
        if (!complete) {
            b.mesh.normals.clear();
        }
        if (!b.anyUv) {
            b.mesh.uvs.clear();
        }
        b.mesh.emission = out.materialEmission[b.mesh.material];
        out.meshes.push_back(std::move(b.mesh));
    }
    log::debug(path + ": " + std::to_string(v.size()) + " vertices, " + std::to_string(faces) +
               " faces, " + std::to_string(out.meshes.size()) + " meshes");
    out.materialFiles = library.files();
    return out;
}

MeshFile loadMeshFile(const std::string& path) {
    std::string ext = fs::path(path).extension().string();
    for (char& c : ext) {
        c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    }
    if (!fs::is_regular_file(path)) {
        throw Error(path + ": file not found");
    }
    if (ext == ".obj") {
        return loadObj(path);
    }
    if (ext == ".ply") {
        return loadPly(path);
    }
    throw Error(path + ": unknown mesh format '" + ext + "' (expected .obj or .ply)");
}

} // namespace bl
