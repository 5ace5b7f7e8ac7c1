#include "atlas/TexelCoverage.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <string>

namespace bl::atlas {

namespace {

// Keeps the part of polygon `in` where sign * (coordinate `axis` - bound) <= 0.
std::vector<glm::dvec2> clipHalfPlane(const std::vector<glm::dvec2>& in, int axis, double bound, double sign) {
    std::vector<glm::dvec2> out;
    for (std::size_t i = 0; i < in.size(); ++i) {
        const glm::dvec2& p = in[i];
        const glm::dvec2& q = in[(i + 1) % in.size()];
        const double dp = sign * (p[axis] - bound), dq = sign * (q[axis] - bound);
        if (dp <= 0.0) out.push_back(p);
        if ((dp < 0.0 && dq > 0.0) || (dp > 0.0 && dq < 0.0)) {
            out.push_back(p + (q - p) * (dp / (dp - dq)));
        }
    }
    return out;
}

} // namespace

double polygonArea(const std::vector<glm::dvec2>& p) {
    double twice = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        const glm::dvec2& u = p[i];
        const glm::dvec2& v = p[(i + 1) % p.size()];
        twice += u.x * v.y - v.x * u.y;
    }
    return 0.5 * std::abs(twice);
}

std::vector<glm::dvec2> clipTriangleToTexel(glm::dvec2 a, glm::dvec2 b, glm::dvec2 c, int x, int y) {
    std::vector<glm::dvec2> poly{a, b, c};
    poly = clipHalfPlane(poly, 0, double(x), -1.0);
    if (poly.size() >= 3) poly = clipHalfPlane(poly, 0, double(x + 1), 1.0);
    if (poly.size() >= 3) poly = clipHalfPlane(poly, 1, double(y), -1.0);
    if (poly.size() >= 3) poly = clipHalfPlane(poly, 1, double(y + 1), 1.0);
    if (poly.size() < 3) poly.clear();
    return poly;
}

double clippedTriangleArea(glm::dvec2 a, glm::dvec2 b, glm::dvec2 c, int x, int y) {
    const std::vector<glm::dvec2> poly = clipTriangleToTexel(a, b, c, x, y);
    return poly.empty() ? 0.0 : polygonArea(poly);
}

// Does triangle (a, b, c) overlap the unit square at (x, y)? Separating axes: the square's
// (covered by iterating the triangle's bounding box) and the triangle's edge normals.
bool overlapsTexel(const glm::vec2 p[3], float x, float y) {
    const glm::vec2 corners[4] = {{x, y}, {x + 1, y}, {x, y + 1}, {x + 1, y + 1}};
    for (int k = 0; k < 3; ++k) {
        glm::vec2 e = p[(k + 1) % 3] - p[k];
        glm::vec2 n(-e.y, e.x);
        float t0 = glm::dot(n, p[k]), t1 = glm::dot(n, p[(k + 2) % 3]);
        float tmin = std::min(t0, t1), tmax = std::max(t0, t1);
        float smin = std::numeric_limits<float>::max(), smax = std::numeric_limits<float>::lowest();
        for (const glm::vec2& c : corners) {
            float s = glm::dot(n, c);
            smin = std::min(smin, s);
            smax = std::max(smax, s);
        }
        if (smax < tmin || smin > tmax) return false;
    }
    return true;
}

// Closest point of triangle p to q, as barycentrics (Ericson, Real-Time Collision Detection 5.1.5).
glm::vec3 closestBarycentric(const glm::vec2 p[3], glm::vec2 q) {
    const glm::vec2 a = p[0], b = p[1], c = p[2];
    glm::vec2 ab = b - a, ac = c - a, ap = q - a;
    float d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
    if (d1 <= 0 && d2 <= 0) return {1, 0, 0};
    glm::vec2 bp = q - b;
    float d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
    if (d3 >= 0 && d4 <= d3) return {0, 1, 0};
    float vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) {
        float v = d1 / (d1 - d3);
        return {1 - v, v, 0};
    }
    glm::vec2 cp = q - c;
    float d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
    if (d6 >= 0 && d5 <= d6) return {0, 0, 1};
    float vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) {
        float w = d2 / (d2 - d6);
        return {1 - w, 0, w};
    }
    float va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
        float w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return {0, 1 - w, w};
    }
    float denom = 1.0f / (va + vb + vc);
    float v = vb * denom, w = vc * denom;
    return {1 - v - w, v, w};
}

std::vector<std::pair<std::size_t, std::size_t>> coverTexels(const std::vector<FlatChart>& charts, int width,
                                                             int height, int pages, std::vector<TexelOwner>& owner,
                                                             std::map<std::pair<int, int>, int>& owned,
                                                             ProgressLog& progress) {
    owner.assign(std::size_t(width) * height * pages, TexelOwner{});
    owned.clear();
    for (std::size_t c = 0; c < charts.size(); ++c) {
        progress.say([&] {
            return "covering texels: chart " + std::to_string(c + 1) + " of " + std::to_string(charts.size());
        });
        const FlatChart& chart = charts[c];
        for (std::size_t i = 0; i < chart.faces.size(); ++i) {
            const glm::vec2 p[3] = {chart.uv[3 * i], chart.uv[3 * i + 1], chart.uv[3 * i + 2]};
            const glm::vec2 lo = glm::min(p[0], glm::min(p[1], p[2])), hi = glm::max(p[0], glm::max(p[1], p[2]));
            const int x0 = std::max(0, int(std::floor(lo.x))), x1 = std::min(width - 1, int(std::floor(hi.x)));
            const int y0 = std::max(0, int(std::floor(lo.y))), y1 = std::min(height - 1, int(std::floor(hi.y)));
            for (int y = y0; y <= y1; ++y) {
                for (int x = x0; x <= x1; ++x) {
                    if (!overlapsTexel(p, float(x), float(y))) continue;
                    const glm::vec2 centre(x + 0.5f, y + 0.5f);
                    const glm::vec3 b = closestBarycentric(p, centre);
                    const float d = glm::distance(b.x * p[0] + b.y * p[1] + b.z * p[2], centre);
                    TexelOwner& o = owner[(std::size_t(chart.page) * height + y) * width + x];
                    if (o.chart >= 0 && o.chart != int(c)) o.otherChart = int(c);
                    if (d < o.distance) {
                        if (o.chart >= 0 && o.chart != int(c)) o.otherChart = o.chart;
                        o.chart = int(c);
                        o.face = int(i);
                        o.distance = d;
                        o.bary = b;
                    }
                }
            }
        }
    }
    for (const TexelOwner& o : owner) {
        if (o.chart >= 0) ++owned[{o.chart, o.face}];
    }
    std::vector<std::pair<std::size_t, std::size_t>> uncovered;
    for (std::size_t c = 0; c < charts.size(); ++c) {
        const FlatChart& chart = charts[c];
        for (std::size_t i = 0; i < chart.faces.size(); ++i) {
            if (owned.count({int(c), int(i)})) continue;
            const glm::vec2 p[3] = {chart.uv[3 * i], chart.uv[3 * i + 1], chart.uv[3 * i + 2]};
            const glm::vec2 lo = glm::min(p[0], glm::min(p[1], p[2])), hi = glm::max(p[0], glm::max(p[1], p[2]));
            bool taken = false;
            for (int y = std::max(0, int(std::floor(lo.y))); !taken && y <= std::min(height - 1, int(std::floor(hi.y))); ++y) {
                for (int x = std::max(0, int(std::floor(lo.x))); !taken && x <= std::min(width - 1, int(std::floor(hi.x))); ++x) {
                    TexelOwner& o = owner[(std::size_t(chart.page) * height + y) * width + x];
                    if (o.chart != int(c) || !overlapsTexel(p, float(x), float(y))) continue;
                    int& count = owned[{o.chart, o.face}];
                    if (count <= 1) continue;
                    --count;
                    const glm::vec2 centre(x + 0.5f, y + 0.5f);
                    o.face = int(i);
                    o.bary = closestBarycentric(p, centre);
                    o.distance = glm::distance(o.bary.x * p[0] + o.bary.y * p[1] + o.bary.z * p[2], centre);
                    owned[{int(c), int(i)}] = 1;
                    taken = true;
                }
            }
            if (!taken) uncovered.emplace_back(c, i);
        }
    }
    return uncovered;
}

} // namespace bl::atlas
