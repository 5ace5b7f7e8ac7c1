#include "scene/MeshCleanup.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>
#include <unordered_map>

namespace bl {
namespace {

// Area below this fraction of the squared longest edge counts as zero: such slivers have no
// well-defined normal, and 1e-12 is far below anything a modeller makes on purpose.
constexpr float kDegenerateRelativeArea = 1e-12f;

glm::vec3 faceCross(const Mesh& m, const glm::uvec3& t) {
    return glm::cross(m.positions[t.y] - m.positions[t.x], m.positions[t.z] - m.positions[t.x]);
}

bool degenerate(const Mesh& m, const glm::uvec3& t) {
    if (t.x == t.y || t.y == t.z || t.x == t.z) {
        return true;
    }
    const glm::vec3& a = m.positions[t.x];
    const glm::vec3& b = m.positions[t.y];
    const glm::vec3& c = m.positions[t.z];
    float longest = std::max({glm::dot(b - a, b - a), glm::dot(c - b, c - b), glm::dot(a - c, a - c)});
    float area2 = glm::length(glm::cross(b - a, c - a));
    return !(area2 > kDegenerateRelativeArea * longest);
}

using PositionKey = std::array<float, 9>;

PositionKey sortedPositions(const Mesh& m, const glm::uvec3& t) {
    std::array<glm::vec3, 3> p = {m.positions[t.x], m.positions[t.y], m.positions[t.z]};
    std::sort(p.begin(), p.end(), [](const glm::vec3& a, const glm::vec3& b) {
        return std::tie(a.x, a.y, a.z) < std::tie(b.x, b.y, b.z);
    });
    return {p[0].x, p[0].y, p[0].z, p[1].x, p[1].y, p[1].z, p[2].x, p[2].y, p[2].z};
}

// Flat: each corner takes its face's normal. Smooth: the area-weighted sum of the normals of the
// faces around the corner's position within the crease angle. Vertices are split where their
// corners' normals differ (shared where equal, so coplanar neighbours keep sharing them).
void generateNormals(Mesh& mesh, NormalSource source, float creaseDegrees) {
    const bool flat = source != NormalSource::Smooth;
    const float cosCrease = std::cos(glm::radians(creaseDegrees));
    const std::size_t nt = mesh.triangles.size();
    std::vector<glm::vec3> faceNormal(nt), weighted(nt);
    for (std::size_t i = 0; i < nt; ++i) {
        weighted[i] = faceCross(mesh, mesh.triangles[i]); // length = 2 * area: area weighting
        faceNormal[i] = glm::normalize(weighted[i]);
    }
    // Vertices may be split by the OBJ (v/vt/vn) keys; smooth over equal positions instead.
    std::map<std::array<float, 3>, std::vector<std::uint32_t>> facesAt;
    for (std::size_t i = 0; i < nt && !flat; ++i) {
        for (int k = 0; k < 3; ++k) {
            const glm::vec3& p = mesh.positions[mesh.triangles[i][k]];
            facesAt[{p.x, p.y, p.z}].push_back(static_cast<std::uint32_t>(i));
        }
    }
    Mesh out;
    std::map<std::tuple<std::uint32_t, float, float, float>, std::uint32_t> vertexOf;
    std::vector<glm::uvec3> triangles(nt);
    for (std::size_t i = 0; i < nt; ++i) {
        for (int k = 0; k < 3; ++k) {
            std::uint32_t v = mesh.triangles[i][k];
            const glm::vec3& p = mesh.positions[v];
            glm::vec3 n = faceNormal[i];
            if (!flat) {
                n = glm::vec3(0.0f);
                for (std::uint32_t j : facesAt[{p.x, p.y, p.z}]) {
                    if (glm::dot(faceNormal[j], faceNormal[i]) >= cosCrease) {
                        n += weighted[j];
                    }
                }
                n = glm::normalize(n);
            }
            auto [it, inserted] = vertexOf.try_emplace({v, n.x, n.y, n.z}, 0u);
            if (inserted) {
                it->second = static_cast<std::uint32_t>(out.positions.size());
                out.positions.push_back(p);
                out.normals.push_back(n);
                if (!mesh.uvs.empty()) {
                    out.uvs.push_back(mesh.uvs[v]);
                }
            }
            triangles[i][k] = it->second;
        }
    }
    mesh.positions = std::move(out.positions);
    mesh.normals = std::move(out.normals);
    mesh.uvs = std::move(out.uvs);
    mesh.triangles = std::move(triangles);
}

} // namespace

CleanupStats cleanupMesh(Mesh& mesh, const NormalOptions& normals) {
    CleanupStats stats;
    std::set<PositionKey> seen;
    std::vector<glm::uvec3> kept;
    kept.reserve(mesh.triangles.size());
    for (const glm::uvec3& t : mesh.triangles) {
        if (degenerate(mesh, t)) {
            ++stats.degenerateTriangles;
        } else if (!seen.insert(sortedPositions(mesh, t)).second) {
            ++stats.duplicateTriangles;
        } else {
            kept.push_back(t);
        }
    }
    mesh.triangles = std::move(kept);

    if (mesh.normals.empty() || normals.source != NormalSource::File) {
        mesh.normals.clear();
        generateNormals(mesh, normals.source, normals.creaseDegrees);
        stats.generatedNormals = true;
    } else {
        // A zero or broken normal in the file would become NaN in shading: use the face normal.
        std::vector<glm::vec3> faceOf(mesh.positions.size(), glm::vec3(0.0f));
        for (const glm::uvec3& t : mesh.triangles) {
            glm::vec3 c = faceCross(mesh, t);
            for (int k = 0; k < 3; ++k) faceOf[t[k]] += c;
        }
        for (std::size_t v = 0; v < mesh.normals.size(); ++v) {
            glm::vec3& n = mesh.normals[v];
            float len = glm::length(n);
            if (!(len > 1e-20f) || !std::isfinite(len)) {
                n = glm::dot(faceOf[v], faceOf[v]) > 0.0f ? glm::normalize(faceOf[v]) : glm::vec3(0, 1, 0);
                ++stats.repairedNormals;
            } else {
                n /= len;
            }
        }
    }
    return stats;
}

} // namespace bl
