#include "atlas/Charting.h"

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <iostream>
#include <limits>
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

std::vector<ChartFaces> growCharts(const Mesh& mesh, std::uint32_t meshIndex, const ChartingOptions& options,
                                   ChartingStats& stats) {
    const float cosCone = std::cos(glm::radians(options.coneDegrees));
    std::uint32_t weldedCount = 0;
    const std::vector<std::uint32_t> welded = weldVertices(mesh, weldedCount);

    OMesh om;
    std::vector<OMesh::VertexHandle> vh(weldedCount);
    {
        std::vector<glm::vec3> at(weldedCount);
        for (std::size_t v = 0; v < welded.size(); ++v) at[welded[v]] = mesh.positions[v];
        for (std::uint32_t v = 0; v < weldedCount; ++v) vh[v] = om.add_vertex(OMesh::Point(at[v].x, at[v].y, at[v].z));
    }
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
    // Each face's neighbours across its edges and the edges' lengths (boundary edges: no neighbour).
    struct Side {
        std::int64_t face = -1;
        float length = 0.0f;
    };
    std::vector<std::array<Side, 3>> sides(nf);
    std::vector<float> perimeter(nf, 0.0f);
    for (std::uint32_t f : meshFaceOf) {
        int k = 0;
        for (auto h = om.fh_iter(OMesh::FaceHandle(omFaceOf[f])); h.is_valid() && k < 3; ++h, ++k) {
            const OMesh::FaceHandle g = om.opposite_face_handle(*h);
            sides[f][k] = {g.is_valid() ? std::int64_t(meshFaceOf[std::size_t(g.idx())]) : -1, om.calc_edge_length(*h)};
            perimeter[f] += sides[f][k].length;
        }
    }

    std::vector<int> chartOf(nf, -1);
    std::vector<ChartFaces> charts;
    for (std::uint32_t f : isolated) {
        chartOf[f] = static_cast<int>(charts.size());
        charts.push_back({meshIndex, {f}});
    }
    // The cost of adding face f to chart `id` with normal `axis`: its normal's deviation (1 at the
    // cone's rim) plus the seam it adds, the length of its edges left on the chart's boundary minus
    // those it closes, per perimeter (-1 for a face filling a hole, 1/3 for one sticking out).
    // Faces cheaper than kMaxChartingCost join, cheapest first: charts grow round, their seams
    // short and straight instead of following every wrinkle of a scanned surface.
    auto cost = [&](std::uint32_t f, int id, glm::vec3 axis) {
        const float alignment = glm::dot(normal[f], axis);
        if (alignment < cosCone) return std::numeric_limits<float>::infinity();
        float seam = 0.0f;
        for (const Side& side : sides[f]) seam += (side.face >= 0 && chartOf[std::size_t(side.face)] == id) ? -side.length : side.length;
        const float deviation = (1.0f - alignment) / std::max(1e-6f, 1.0f - cosCone);
        return deviation + options.seamWeight * (perimeter[f] > 0.0f ? seam / perimeter[f] : 0.0f);
    };
    std::vector<std::uint32_t> seeds = meshFaceOf;
    std::sort(seeds.begin(), seeds.end(), [&](std::uint32_t a, std::uint32_t b) { return area[a] > area[b]; });
    for (std::uint32_t seed : seeds) {
        if (chartOf[seed] >= 0) continue;
        const int id = static_cast<int>(charts.size());
        ChartFaces chart{meshIndex, {}};
        glm::vec3 sum(0.0f); // area-weighted normal
        using Item = std::pair<float, std::uint32_t>; // (cost, face): cheapest first
        std::priority_queue<Item, std::vector<Item>, std::greater<>> frontier;
        auto join = [&](std::uint32_t f) {
            chartOf[f] = id;
            chart.faces.push_back(f);
            sum += weighted[f];
            const glm::vec3 grown = glm::normalize(sum);
            for (const Side& side : sides[f]) {
                if (side.face < 0 || chartOf[std::size_t(side.face)] >= 0) continue;
                const float c = cost(std::uint32_t(side.face), id, grown);
                if (c <= kMaxChartingCost) frontier.push({c, std::uint32_t(side.face)});
            }
        };
        join(seed);
        while (!frontier.empty()) {
            const auto [queued, f] = frontier.top();
            frontier.pop();
            if (chartOf[f] >= 0) continue;
            const float now = cost(f, id, glm::normalize(sum));
            if (now > queued + 1e-4f) { // the chart's normal moved since it was queued
                if (now <= kMaxChartingCost) frontier.push({now, f});
                continue; // else it may join when a neighbour does, or start a chart of its own
            }
            join(f);
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
