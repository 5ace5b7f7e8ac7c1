#include "modes/atlas/AtlasBias.h"

#include "modes/reference/ReferenceTestSupport.h"
#include "support/Statistics.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <tuple>

namespace bl::test::atlas {

std::vector<double> interleavedShares(std::uint32_t directions, double k, int maxReflections) {
    const std::size_t m = std::size_t(maxReflections) + 1;
    std::vector<double> previous(m, 0.0), sums(m, 0.0), current(m, 0.0);
    previous[0] = 1.0; // c(0, 0) = 1, c(0, b >= 1) = 0
    double total = 0.0;
    current = previous;
    for (std::uint32_t j = 1; j <= directions; ++j) {
        const double w = std::pow(double(j), k);
        total += w;
        for (std::size_t b = 1; b < m; ++b) sums[b] += w * previous[b - 1];
        current[0] = 1.0;
        for (std::size_t b = 1; b < m; ++b) current[b] = sums[b] / total;
        previous = current;
    }
    return current;
}

double furnaceGivenDirections(const std::vector<glm::vec3>& directions, double k, double albedo, int cells,
                              int samples) {
    // Face f = 2 axis + (side > 0): the plane x_axis = side, inward normal -side e_axis; its cells
    // indexed over the other two axes (u = (axis + 1) % 3, v = (axis + 2) % 3).
    const int perFace = cells * cells, total = 6 * perFace;
    const auto cellOf = [&](int face, double u, double v) {
        const int iu = std::clamp(int((u + 1.0) * 0.5 * cells), 0, cells - 1);
        const int iv = std::clamp(int((v + 1.0) * 0.5 * cells), 0, cells - 1);
        return face * perFace + iu * cells + iv;
    };
    std::vector<double> sum(std::size_t(total), 0.0), received(std::size_t(total), 0.0);
    double weightSum = 0.0;
    for (std::size_t j = 0; j < directions.size(); ++j) {
        const glm::dvec3 omega = glm::normalize(glm::dvec3(directions[j]));
        const double scale = weightSum > 0.0 ? 1.0 / weightSum : 0.0; // the estimate of directions 1..j-1
        for (int face = 0; face < 6; ++face) {
            const int axis = face / 2, u = (axis + 1) % 3, v = (axis + 2) % 3;
            const double side = face % 2 ? 1.0 : -1.0;
            // The inward one of +-omega: light arrives at the face from the surface it points to.
            const glm::dvec3 d = omega[axis] * side < 0.0 ? omega : -omega;
            const double cosine = std::abs(omega[axis]);
            if (cosine == 0.0) { // parallel to the face: it receives nothing (and no ray leaves it)
                std::fill_n(received.begin() + face * perFace, perFace, 0.0);
                continue;
            }
            for (int c = 0; c < perFace; ++c) {
                double sender = 0.0;
                for (int s = 0; s < samples * samples; ++s) {
                    glm::dvec3 x(0.0);
                    x[axis] = side;
                    x[u] = -1.0 + 2.0 * ((c / cells) + (s / samples + 0.5) / samples) / cells;
                    x[v] = -1.0 + 2.0 * ((c % cells) + (s % samples + 0.5) / samples) / cells;
                    // Where x + t d leaves the box: the nearest face ahead.
                    double t = std::numeric_limits<double>::infinity();
                    int exitAxis = -1;
                    for (int b = 0; b < 3; ++b) {
                        if (b == axis || d[b] == 0.0) continue;
                        const double tb = ((d[b] > 0.0 ? 1.0 : -1.0) - x[b]) / d[b];
                        if (tb < t) t = tb, exitAxis = b;
                    }
                    const double ta = (-side - x[axis]) / d[axis]; // the opposite face
                    if (ta < t) t = ta, exitAxis = axis;
                    const glm::dvec3 y = x + t * d;
                    const int exitFace = 2 * exitAxis + (d[exitAxis] > 0.0 ? 1 : 0);
                    const int landed = cellOf(exitFace, y[(exitAxis + 1) % 3], y[(exitAxis + 2) % 3]);
                    sender += 1.0 + sum[std::size_t(landed)] * scale;
                }
                received[std::size_t(face * perFace + c)] = 2.0 * albedo * cosine * sender / double(samples * samples);
            }
        }
        const double w = std::pow(double(j + 1), k);
        for (int c = 0; c < total; ++c) sum[std::size_t(c)] += w * received[std::size_t(c)];
        weightSum += w;
    }
    double mean = 0.0;
    for (int c = 0; c < total; ++c) mean += 1.0 + (weightSum > 0.0 ? sum[std::size_t(c)] / weightSum : 0.0);
    return mean / double(total);
}

namespace {

double meanLuminance(const Image& image) {
    double sum = 0.0;
    for (const glm::vec3& p : image.pixels()) sum += stats::luminance(p);
    return sum / double(image.pixelCount());
}

} // namespace

Deficit interleavedDeficit(const ImageSet& reference, std::uint32_t directions, double k, double albedo, int fromLights,
                           const std::vector<std::string>& layers) {
    constexpr int kReflections = 64;
    const std::vector<double> c = interleavedShares(directions, k, kReflections);
    const auto share = [&](int b) { return c[std::size_t(std::max(b - fromLights, 0))]; };
    const auto wanted = [&](const std::string& name) { return std::find(layers.begin(), layers.end(), name) != layers.end(); };
    double deficit = 0.0, total = 0.0, least = 0.0;
    const char* names[] = {"direct", "indirect1", "indirect2"};
    for (int b = 1; b <= 3; ++b) {
        if (!wanted(names[b - 1])) continue;
        const double layer = meanLuminance(layerOf(reference, names[b - 1]));
        deficit += (1.0 - share(b)) * layer;
        total += layer;
    }
    if (wanted("rest")) {
        // rest = sum_{b >= 4} I_b with I_{b+1} <= albedo I_b: its largest deficit puts the most
        // weight on the long paths, I_b = rest (1 - albedo) albedo^(b - 4).
        const double rest = meanLuminance(layerOf(reference, "rest"));
        double tail = std::pow(albedo, kReflections - 3); // beyond kReflections: all of it
        for (int b = 4; b <= kReflections; ++b) tail += (1.0 - share(b)) * (1.0 - albedo) * std::pow(albedo, b - 4);
        least = deficit + (1.0 - share(4)) * rest;
        deficit += tail * rest;
        total += rest;
    } else {
        least = deficit;
    }
    if (!(total > 0.0)) return {};
    return {least / total, deficit / total};
}

double texelSide(const std::vector<float>& texelAreas) {
    float largest = 0.0f;
    for (float a : texelAreas) largest = std::max(largest, a);
    return std::sqrt(double(largest));
}

namespace {

struct Segment {
    glm::vec3 a, b;
};

// Each mesh's geometric edges: triangle edges with one triangle (borders) or two in different planes.
std::vector<std::vector<Segment>> geometricEdges(const Scene& s) {
    std::vector<std::vector<Segment>> out;
    for (const Mesh& mesh : s.meshes) {
        using Key = std::array<float, 6>;
        std::map<Key, std::vector<glm::vec3>> normals;
        for (const glm::uvec3& t : mesh.triangles) {
            const glm::vec3 p[3] = {mesh.positions[t.x], mesh.positions[t.y], mesh.positions[t.z]};
            const glm::vec3 c = glm::cross(p[1] - p[0], p[2] - p[0]);
            if (glm::length(c) <= 0.0f) continue;
            for (int e = 0; e < 3; ++e) {
                glm::vec3 a = p[e], b = p[(e + 1) % 3];
                if (std::tie(b.x, b.y, b.z) < std::tie(a.x, a.y, a.z)) std::swap(a, b);
                normals[{a.x, a.y, a.z, b.x, b.y, b.z}].push_back(glm::normalize(c));
            }
        }
        std::vector<Segment> edges;
        for (const auto& [key, n] : normals) {
            if (n.size() != 2 || std::abs(glm::dot(n[0], n[1])) < 1.0f - 1e-4f) {
                edges.push_back({{key[0], key[1], key[2]}, {key[3], key[4], key[5]}});
            }
        }
        out.push_back(std::move(edges));
    }
    return out;
}

double distanceToSegment(const glm::dvec3& p, const Segment& s) {
    const glm::dvec3 a(s.a), d = glm::dvec3(s.b) - a;
    const double t = std::clamp(glm::dot(p - a, d) / std::max(glm::dot(d, d), 1e-30), 0.0, 1.0);
    return glm::length(p - (a + t * d));
}

} // namespace

std::vector<ContactSample> contactLines(const Scene& s, double gap) {
    constexpr int kSamplesPerEdge = 16;
    const std::vector<std::vector<Segment>> edges = geometricEdges(s);
    std::vector<ContactSample> out;
    for (std::size_t i = 0; i < s.meshes.size(); ++i) {
        for (const Segment& e : edges[i]) {
            const double length = glm::length(e.b - e.a) / kSamplesPerEdge;
            for (int k = 0; k < kSamplesPerEdge; ++k) {
                const glm::dvec3 p = glm::mix(glm::dvec3(e.a), glm::dvec3(e.b), (k + 0.5) / kSamplesPerEdge);
                bool found = false;
                for (std::size_t j = 0; j < s.meshes.size() && !found; ++j) {
                    if (j == i) continue;
                    const Mesh& m = s.meshes[j];
                    for (const glm::uvec3& t : m.triangles) {
                        const glm::dvec3 a(m.positions[t.x]), b(m.positions[t.y]), c(m.positions[t.z]);
                        glm::dvec3 n = glm::cross(b - a, c - a);
                        if (glm::length(n) <= 0.0) continue;
                        n = glm::normalize(n);
                        const double height = glm::dot(p - a, n);
                        if (std::abs(height) > gap) continue;
                        const glm::dvec3 q = p - height * n;
                        // Inside the triangle: q on the inner side of each of its edges.
                        if (glm::dot(glm::cross(b - a, q - a), n) < 0.0 || glm::dot(glm::cross(c - b, q - b), n) < 0.0 ||
                            glm::dot(glm::cross(a - c, q - c), n) < 0.0) {
                            continue;
                        }
                        double toEdge = INFINITY;
                        for (const Segment& f : edges[j]) toEdge = std::min(toEdge, distanceToSegment(q, f));
                        if (toEdge <= gap) continue;
                        out.push_back({glm::vec3(q), glm::vec3(n), length});
                        found = true;
                        break;
                    }
                }
            }
        }
    }
    return out;
}

Bracket bracket(const Deficit& deficit, const TexelBias& texel, double other) {
    const double lower = 1.0 - deficit.most - texel.hidden - texel.secondOrder - other;
    const double upper = 1.0 - deficit.least + texel.secondOrder + other;
    return {0.5 * (lower + upper), 0.5 * (upper - lower)};
}

TexelBias texelBias(const Scene& s, const Image& light, double h, bool bothSides) {
    // (a) second order.
    const double r = double(s.bounds().radius());
    const double secondOrder = (h / r) * (h / r);
    // (b) the contact strips' light in the image.
    const std::vector<ContactSample> contacts = contactLines(s, h);
    const int width = light.width(), height = light.height();
    const glm::dvec3 eye(s.camera.pose.position);
    const glm::dvec3 forward = glm::normalize(glm::dvec3(s.camera.pose.target) - eye);
    const glm::dvec3 right = glm::normalize(glm::cross(forward, glm::dvec3(s.camera.pose.up)));
    const glm::dvec3 up = glm::cross(right, forward);
    // Half-angle tangents (fov across x or y; the other axis by the aspect).
    const double aspect = double(width) / double(height);
    double tx = std::tan(0.5 * double(s.camera.fovDegrees) * 3.14159265358979323846 / 180.0), ty = tx;
    if (s.camera.fovAxis == FovAxis::X) ty = tx / aspect; else tx = ty * aspect;
    // The image's solid angle: sum of the pixels' (exact for a pinhole up to the pixel size).
    double imageSolidAngle = 0.0;
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const double u = tx * (2.0 * (x + 0.5) / width - 1.0), v = ty * (2.0 * (y + 0.5) / height - 1.0);
            imageSolidAngle += (2.0 * tx / width) * (2.0 * ty / height) / std::pow(1.0 + u * u + v * v, 1.5);
        }
    }
    double contactLength = 0.0, strip = 0.0; // strip: sum of L_near * solid angle
    for (const ContactSample& c : contacts) {
        contactLength += c.length;
        const glm::dvec3 v = glm::dvec3(c.point) - eye;
        const double depth = glm::dot(v, forward);
        if (depth <= 0.0) continue;
        const double u = glm::dot(v, right) / (depth * tx), w = glm::dot(v, up) / (depth * ty);
        if (std::abs(u) > 1.0 || std::abs(w) > 1.0) continue;
        const double d = glm::length(v);
        const double cosine = std::abs(glm::dot(glm::dvec3(c.normal), v / d)) + (bothSides ? 1.0 : 0.0);
        const double solidAngle = h * c.length * cosine / (d * d);
        const int px = std::clamp(int((u + 1.0) * 0.5 * width), 0, width - 1);
        const int py = std::clamp(int((1.0 - w) * 0.5 * height), 0, height - 1);
        double near = 0.0;
        for (int y = std::max(py - 1, 0); y <= std::min(py + 1, height - 1); ++y)
            for (int x = std::max(px - 1, 0); x <= std::min(px + 1, width - 1); ++x)
                near = std::max(near, stats::luminance(light.at(x, y)));
        strip += near * solidAngle;
    }
    const double mean = meanLuminance(light);
    const double firstOrder = strip / (imageSolidAngle * mean);
    std::printf("texel bias: side %.3g, contact lines %.4g long, strip share of the image %.4f, second order %.5f\n",
                h, contactLength, firstOrder, secondOrder);
    return {firstOrder, secondOrder};
}

} // namespace bl::test::atlas
