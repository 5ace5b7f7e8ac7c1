#include "atlas/Charting.h"

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <iostream>
#include <queue>

namespace bl::atlas {

namespace {

using OMesh = OpenMesh::TriMesh_ArrayKernelT<>;

using PositionKey = std::array<float, 3>;

glm::vec3 faceCross(const Mesh& m, std::uint32_t f) {
    const glm::uvec3& t = m.triangles[f];
    return glm::cross(m.positions[t.y] - m.positions[t.x], m.positions[t.z] - m.positions[t.x]);
}

} // namespace

std::vector<std::uint32_t> weldVertices(const Mesh& m, std::uint32_t& count) {
    std::map<PositionKey, std::uint32_t> index;
    std::vector<std::uint32_t> welded(m.positions.size());
    for (std::size_t v = 0; v < m.positions.size(); ++v) {
        const glm::vec3& p = m.positions[v];
        welded[v] = index.try_emplace(PositionKey{p.x, p.y, p.z}, static_cast<std::uint32_t>(index.size())).first->second;
    }
    count = static_cast<std::uint32_t>(index.size());
    return welded;
}

std::vector<ChartFaces> growCharts(const Mesh& mesh, std::uint32_t meshIndex, float coneDegrees, ChartingStats& stats) {
    const float cosCone = std::cos(glm::radians(coneDegrees));
    std::uint32_t weldedCount = 0;
    const std::vector<std::uint32_t> welded = weldVertices(mesh, weldedCount);

    OMesh om;
    std::vector<OMesh::VertexHandle> vh(weldedCount);
    for (std::uint32_t v = 0; v < weldedCount; ++v) vh[v] = om.add_vertex(OMesh::Point(0, 0, 0));
    const std::size_t nf = mesh.triangles.size();
    std::vector<int> omFaceOf(nf, -1);
    std::vector<std::uint32_t> meshFaceOf;
    std::vector<std::uint32_t> isolated;
    {
        // OpenMesh reports every rejected face on stderr; the rejection is counted instead.
        std::streambuf* saved = std::cerr.rdbuf(nullptr);
        for (std::uint32_t f = 0; f < nf; ++f) {
            const glm::uvec3& t = mesh.triangles[f];
            std::uint32_t a = welded[t.x], b = welded[t.y], c = welded[t.z];
            if (a == b || b == c || a == c) {
                ++stats.degenerateFaces;
                isolated.push_back(f);
                continue;
            }
            OMesh::FaceHandle fh = om.add_face(vh[a], vh[b], vh[c]);
            if (!fh.is_valid()) {
                ++stats.nonManifoldFaces;
                isolated.push_back(f);
                continue;
            }
            omFaceOf[f] = fh.idx();
            meshFaceOf.push_back(f);
        }
        std::cerr.rdbuf(saved);
    }

    std::vector<glm::vec3> weighted(nf), normal(nf);
    std::vector<float> area(nf);
    for (std::uint32_t f = 0; f < nf; ++f) {
        weighted[f] = faceCross(mesh, f);
        area[f] = glm::length(weighted[f]);
        normal[f] = area[f] > 0.0f ? weighted[f] / area[f] : glm::vec3(0, 0, 1);
    }

    std::vector<int> chartOf(nf, -1);
    std::vector<ChartFaces> charts;
    for (std::uint32_t f : isolated) {
        chartOf[f] = static_cast<int>(charts.size());
        charts.push_back({meshIndex, {f}});
    }
    std::vector<std::uint32_t> seeds = meshFaceOf;
    std::sort(seeds.begin(), seeds.end(), [&](std::uint32_t a, std::uint32_t b) { return area[a] > area[b]; });
    for (std::uint32_t seed : seeds) {
        if (chartOf[seed] >= 0) continue;
        const int id = static_cast<int>(charts.size());
        ChartFaces chart{meshIndex, {}};
        glm::vec3 sum(0.0f);
        using Item = std::pair<float, std::uint32_t>; // (alignment, face): best first
        std::priority_queue<Item> frontier;
        frontier.push({1.0f, seed});
        while (!frontier.empty()) {
            std::uint32_t f = frontier.top().second;
            frontier.pop();
            if (chartOf[f] >= 0) continue;
            glm::vec3 axis = glm::dot(sum, sum) > 0.0f ? glm::normalize(sum) : normal[f];
            if (glm::dot(normal[f], axis) < cosCone) continue; // may join another chart later
            chartOf[f] = id;
            chart.faces.push_back(f);
            sum += weighted[f];
            axis = glm::normalize(sum);
            OMesh::FaceHandle fh(omFaceOf[f]);
            for (auto ff = om.ff_iter(fh); ff.is_valid(); ++ff) {
                std::uint32_t g = meshFaceOf[static_cast<std::size_t>(ff->idx())];
                if (chartOf[g] < 0) frontier.push({glm::dot(normal[g], axis), g});
            }
        }
        charts.push_back(std::move(chart));
    }
    return charts;
}

std::vector<std::vector<std::uint32_t>> connectedComponents(const Mesh& mesh, const std::vector<std::uint32_t>& welded,
                                                            const std::vector<std::uint32_t>& faces) {
    // Faces sharing a welded edge are connected.
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<std::size_t>> edgeFaces;
    for (std::size_t i = 0; i < faces.size(); ++i) {
        const glm::uvec3& t = mesh.triangles[faces[i]];
        std::uint32_t v[3] = {welded[t.x], welded[t.y], welded[t.z]};
        for (int k = 0; k < 3; ++k) {
            std::uint32_t a = v[k], b = v[(k + 1) % 3];
            edgeFaces[{std::min(a, b), std::max(a, b)}].push_back(i);
        }
    }
    std::vector<int> component(faces.size(), -1);
    std::vector<std::vector<std::uint32_t>> out;
    for (std::size_t start = 0; start < faces.size(); ++start) {
        if (component[start] >= 0) continue;
        const int c = static_cast<int>(out.size());
        out.emplace_back();
        std::vector<std::size_t> stack{start};
        component[start] = c;
        while (!stack.empty()) {
            std::size_t i = stack.back();
            stack.pop_back();
            out[c].push_back(faces[i]);
            const glm::uvec3& t = mesh.triangles[faces[i]];
            std::uint32_t v[3] = {welded[t.x], welded[t.y], welded[t.z]};
            for (int k = 0; k < 3; ++k) {
                std::uint32_t a = v[k], b = v[(k + 1) % 3];
                for (std::size_t j : edgeFaces[{std::min(a, b), std::max(a, b)}]) {
                    if (component[j] < 0) {
                        component[j] = c;
                        stack.push_back(j);
                    }
                }
            }
        }
    }
    return out;
}

} // namespace bl::atlas
