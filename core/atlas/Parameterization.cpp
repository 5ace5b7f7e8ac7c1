#include "atlas/Parameterization.h"

#include <Eigen/Sparse>
#include <cmath>
#include <limits>
#include <shared/Frame.h>
#include <unordered_map>

namespace bl::atlas {

namespace {

glm::vec3 corner(const Mesh& m, std::uint32_t f, int k) { return m.positions[m.triangles[f][k]]; }

float area3(const Mesh& m, std::uint32_t f) {
    return 0.5f * glm::length(glm::cross(corner(m, f, 1) - corner(m, f, 0), corner(m, f, 2) - corner(m, f, 0)));
}

float signedArea2(glm::vec2 a, glm::vec2 b, glm::vec2 c) {
    return 0.5f * ((b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y));
}

// Least squares conformal map over the chart's welded vertices; false if the solve fails.
bool lscm(const Mesh& mesh, const std::vector<std::uint32_t>& faces, const std::vector<std::uint32_t>& welded,
          std::vector<glm::vec2>& uv) {
    std::unordered_map<std::uint32_t, int> local;
    std::vector<glm::vec3> points;
    for (std::uint32_t f : faces) {
        for (int k = 0; k < 3; ++k) {
            std::uint32_t w = welded[mesh.triangles[f][k]];
            if (local.emplace(w, static_cast<int>(points.size())).second) points.push_back(corner(mesh, f, k));
        }
    }
    const int n = static_cast<int>(points.size());
    // Pins: the two vertices farthest apart along the chart's longest bounding-box axis.
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
    for (const glm::vec3& p : points) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    glm::vec3 extent = hi - lo;
    int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
    int pin0 = 0, pin1 = 0;
    for (int i = 0; i < n; ++i) {
        if (points[i][axis] < points[pin0][axis]) pin0 = i;
        if (points[i][axis] > points[pin1][axis]) pin1 = i;
    }
    if (pin0 == pin1) return false;
    const glm::vec2 pinUv0(0.0f), pinUv1(glm::length(points[pin1] - points[pin0]), 0.0f);

    // Unknowns: (u, v) of every vertex but the pins. Two rows per face (real, imaginary).
    auto column = [&](int vertex) {
        int c = vertex;
        if (vertex > pin0) --c;
        if (vertex > pin1) --c;
        return c;
    };
    const int unknowns = n - 2;
    std::vector<Eigen::Triplet<double>> triplets;
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(2 * static_cast<Eigen::Index>(faces.size()));
    for (std::size_t r = 0; r < faces.size(); ++r) {
        const std::uint32_t f = faces[r];
        glm::vec3 p0 = corner(mesh, f, 0), p1 = corner(mesh, f, 1), p2 = corner(mesh, f, 2);
        glm::vec3 x = p1 - p0;
        const float len = glm::length(x);
        glm::vec3 nrm = glm::cross(p1 - p0, p2 - p0);
        const float a2 = glm::length(nrm); // twice the area
        if (!(len > 0.0f) || !(a2 > 0.0f)) continue;
        x /= len;
        glm::vec3 y = glm::cross(nrm / a2, x);
        // The triangle in its own plane: (0,0), (len,0), (qx,qy).
        const double lx[3] = {0.0, len, glm::dot(p2 - p0, x)};
        const double ly[3] = {0.0, 0.0, glm::dot(p2 - p0, y)};
        const double scale = 1.0 / std::sqrt(a2);
        for (int k = 0; k < 3; ++k) {
            // W_k = (x_{k+2} - x_{k+1}) + i (y_{k+2} - y_{k+1}), the rotated opposite edge.
            const double wr = (lx[(k + 2) % 3] - lx[(k + 1) % 3]) * scale;
            const double wi = (ly[(k + 2) % 3] - ly[(k + 1) % 3]) * scale;
            const int vertex = local[welded[mesh.triangles[f][k]]];
            const Eigen::Index re = static_cast<Eigen::Index>(2 * r), im = re + 1;
            if (vertex == pin0 || vertex == pin1) {
                const glm::vec2 fixed = vertex == pin0 ? pinUv0 : pinUv1;
                rhs[re] -= wr * fixed.x - wi * fixed.y;
                rhs[im] -= wi * fixed.x + wr * fixed.y;
                continue;
            }
            const int c = column(vertex);
            triplets.emplace_back(re, 2 * c, wr);
            triplets.emplace_back(re, 2 * c + 1, -wi);
            triplets.emplace_back(im, 2 * c, wi);
            triplets.emplace_back(im, 2 * c + 1, wr);
        }
    }
    Eigen::SparseMatrix<double> a(2 * static_cast<Eigen::Index>(faces.size()), 2 * unknowns);
    a.setFromTriplets(triplets.begin(), triplets.end());
    Eigen::SparseMatrix<double> normal = a.transpose() * a;
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(normal);
    if (solver.info() != Eigen::Success) return false;
    Eigen::VectorXd solution = solver.solve(a.transpose() * rhs);
    if (solver.info() != Eigen::Success || !solution.allFinite()) return false;

    std::vector<glm::vec2> vertexUv(n);
    for (int i = 0; i < n; ++i) {
        if (i == pin0) vertexUv[i] = pinUv0;
        else if (i == pin1) vertexUv[i] = pinUv1;
        else vertexUv[i] = glm::vec2(float(solution[2 * column(i)]), float(solution[2 * column(i) + 1]));
    }
    uv.clear();
    for (std::uint32_t f : faces) {
        for (int k = 0; k < 3; ++k) uv.push_back(vertexUv[local[welded[mesh.triangles[f][k]]]]);
    }
    return true;
}

} // namespace

void measure(const Mesh& mesh, FlatChart& c) {
    c.flipped = 0;
    double weighted = 0.0, total = 0.0;
    for (std::size_t i = 0; i < c.faces.size(); ++i) {
        const std::uint32_t f = c.faces[i];
        const glm::vec2 s0 = c.uv[3 * i], s1 = c.uv[3 * i + 1], s2 = c.uv[3 * i + 2];
        const float a = signedArea2(s0, s1, s2);
        const float a3 = area3(mesh, f);
        total += a3;
        if (!(a > 0.0f)) {
            ++c.flipped;
            weighted += 1e30;
            continue;
        }
        // Sander et al.: S_s and S_t, the surface's derivatives along u and v.
        const glm::vec3 q0 = corner(mesh, f, 0), q1 = corner(mesh, f, 1), q2 = corner(mesh, f, 2);
        const glm::vec3 ss = (q0 * (s1.y - s2.y) + q1 * (s2.y - s0.y) + q2 * (s0.y - s1.y)) / (2.0f * a);
        const glm::vec3 st = (q0 * (s2.x - s1.x) + q1 * (s0.x - s2.x) + q2 * (s1.x - s0.x)) / (2.0f * a);
        weighted += 0.5 * (double(glm::dot(ss, ss)) + glm::dot(st, st)) * a3;
    }
    c.stretch = total > 0.0 ? float(std::sqrt(weighted / total)) : 1.0f;
}

FlatChart flatten(const Mesh& mesh, std::uint32_t meshIndex, const std::vector<std::uint32_t>& faces,
                  const std::vector<std::uint32_t>& welded) {
    FlatChart c;
    c.mesh = meshIndex;
    c.faces = faces;
    glm::vec3 sum(0.0f);
    for (std::uint32_t f : faces) {
        sum += glm::cross(corner(mesh, f, 1) - corner(mesh, f, 0), corner(mesh, f, 2) - corner(mesh, f, 0));
    }
    const glm::vec3 axis = glm::dot(sum, sum) > 0.0f ? glm::normalize(sum) : glm::vec3(0, 0, 1);
    float worst = 0.0f;
    for (std::uint32_t f : faces) {
        glm::vec3 n = glm::cross(corner(mesh, f, 1) - corner(mesh, f, 0), corner(mesh, f, 2) - corner(mesh, f, 0));
        float len = glm::length(n);
        if (len > 0.0f) worst = std::max(worst, std::acos(std::clamp(glm::dot(n / len, axis), -1.0f, 1.0f)));
    }
    c.planar = worst <= kPlanarToleranceRadians || faces.size() == 1;
    bool ok = false;
    if (!c.planar) {
        ok = lscm(mesh, faces, welded, c.uv);
        if (ok) {
            // A conformal map may come out mirrored: make the total signed area positive.
            double signedTotal = 0.0;
            for (std::size_t i = 0; i < faces.size(); ++i) signedTotal += signedArea2(c.uv[3 * i], c.uv[3 * i + 1], c.uv[3 * i + 2]);
            if (signedTotal < 0.0) {
                for (glm::vec2& p : c.uv) p.x = -p.x;
            }
            // Scale the flat area to the surface area.
            double flat = 0.0, surface = 0.0;
            for (std::size_t i = 0; i < faces.size(); ++i) {
                flat += std::abs(signedArea2(c.uv[3 * i], c.uv[3 * i + 1], c.uv[3 * i + 2]));
                surface += area3(mesh, faces[i]);
            }
            if (flat > 0.0) {
                const float s = float(std::sqrt(surface / flat));
                for (glm::vec2& p : c.uv) p *= s;
            }
        }
    }
    if (!ok) {
        // Orthogonal projection onto the chart's plane (exact for planar charts).
        glm::vec3 t, b;
        shader::blOrthonormalBasis(axis, t, b);
        c.uv.clear();
        for (std::uint32_t f : faces) {
            for (int k = 0; k < 3; ++k) {
                glm::vec3 p = corner(mesh, f, k);
                c.uv.emplace_back(glm::dot(p, t), glm::dot(p, b));
            }
        }
        double signedTotal = 0.0;
        for (std::size_t i = 0; i < faces.size(); ++i) signedTotal += signedArea2(c.uv[3 * i], c.uv[3 * i + 1], c.uv[3 * i + 2]);
        if (signedTotal < 0.0) {
            for (glm::vec2& p : c.uv) p.x = -p.x;
        }
    }
    measure(mesh, c);
    return c;
}

} // namespace bl::atlas
