#include "support/AnalyticScenes.h"

#include <shared/Camera.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <tuple>

namespace bl::test {

Mesh makeRectangle(glm::vec2 lo, glm::vec2 hi, float height, bool facingDown, std::uint32_t material) {
    Mesh m;
    m.name = "rectangle";
    m.positions = {{lo.x, height, lo.y}, {hi.x, height, lo.y}, {hi.x, height, hi.y}, {lo.x, height, hi.y}};
    glm::vec3 n(0.0f, facingDown ? -1.0f : 1.0f, 0.0f);
    m.normals.assign(4, n);
    // (lo,lo) -> (lo,hi) -> (hi,hi) has normal +y; the reverse order faces down.
    m.triangles = facingDown ? std::vector<glm::uvec3>{{0, 1, 2}, {0, 2, 3}}
                             : std::vector<glm::uvec3>{{0, 3, 2}, {0, 2, 1}};
    m.material = material;
    return m;
}

Mesh makeSquare(float size, std::uint32_t material, glm::vec3 centre) {
    Mesh m = makeRectangle(glm::vec2(centre.x, centre.z) - size * 0.5f, glm::vec2(centre.x, centre.z) + size * 0.5f,
                           centre.y, false, material);
    m.name = "square";
    return m;
}

Mesh makeBowl(int rings, int segments, std::uint32_t material) {
    Mesh m;
    m.name = "bowl";
    for (int i = 0; i < rings; ++i) {
        const float theta = 0.5f * shader::kPi * (1.0f + float(i) / float(rings)); // from +y: equator to bottom
        for (int j = 0; j < segments; ++j) {
            const float phi = 2.0f * shader::kPi * float(j) / float(segments);
            const glm::vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
            m.positions.push_back(n + glm::vec3(0.0f, 1.0f, 0.0f));
            m.normals.push_back(n);
        }
    }
    const std::uint32_t pole = std::uint32_t(m.positions.size()); // one vertex: the last ring fans to it
    m.positions.push_back(glm::vec3(0.0f));
    m.normals.push_back(glm::vec3(0.0f, -1.0f, 0.0f));
    for (int i = 0; i < rings; ++i) {
        for (int j = 0; j < segments; ++j) {
            const auto at = [&](int r, int k) { return r == rings ? pole : std::uint32_t(r * segments + (k % segments)); };
            m.triangles.push_back({at(i, j), at(i + 1, j), at(i, j + 1)});
            if (i + 1 < rings) {
                m.triangles.push_back({at(i, j + 1), at(i + 1, j), at(i + 1, j + 1)});
            }
        }
    }
    m.material = material;
    return m;
}

double largestNormalDeviation(const Mesh& mesh) {
    double largest = 0.0;
    for (const glm::uvec3& t : mesh.triangles) {
        const glm::vec3 c = glm::cross(mesh.positions[t.y] - mesh.positions[t.x], mesh.positions[t.z] - mesh.positions[t.x]);
        if (!(glm::dot(c, c) > 0.0f)) continue; // no plane: draws nothing
        const glm::vec3 g = glm::normalize(c);
        for (int k = 0; k < 3; ++k) {
            const float cosine = std::abs(glm::dot(g, glm::normalize(mesh.normals[t[k]])));
            largest = std::max(largest, std::acos(double(std::min(cosine, 1.0f))));
        }
    }
    return largest;
}

EdgeStats edgeStats(const std::vector<Mesh>& meshes) {
    // Each edge (its end points, ordered) with the unit normals of the triangles that have it.
    std::map<std::array<float, 6>, std::vector<glm::vec3>> edges;
    EdgeStats out;
    for (const Mesh& mesh : meshes) {
        for (const glm::uvec3& t : mesh.triangles) {
            const glm::vec3 p[3] = {mesh.positions[t.x], mesh.positions[t.y], mesh.positions[t.z]};
            const glm::vec3 c = glm::cross(p[1] - p[0], p[2] - p[0]);
            if (!(glm::dot(c, c) > 0.0f)) continue; // no plane: draws nothing
            out.area += 0.5 * double(glm::length(c));
            const glm::vec3 n = glm::normalize(c);
            for (int e = 0; e < 3; ++e) {
                glm::vec3 a = p[e], b = p[(e + 1) % 3];
                if (std::tie(b.x, b.y, b.z) < std::tie(a.x, a.y, a.z)) std::swap(a, b);
                edges[{a.x, a.y, a.z, b.x, b.y, b.z}].push_back(n);
            }
        }
    }
    for (const auto& [e, normals] : edges) {
        const double length = glm::length(glm::vec3(e[0], e[1], e[2]) - glm::vec3(e[3], e[4], e[5]));
        const float cosine = normals.size() == 2 ? std::abs(glm::dot(normals[0], normals[1])) : 0.0f;
        if (normals.size() == 1) out.borderLength += length;
        if (normals.size() != 2 || cosine < 1.0f - 1e-4f) out.creaseLength += length;
        if (normals.size() == 2) {
            out.largestDihedral = std::max(out.largestDihedral, std::acos(double(std::min(cosine, 1.0f))));
        }
    }
    return out;
}

Scene bowlUnderSky(int rings, int segments, int resolution) {
    Scene s;
    Material m;
    m.name = "white";
    m.albedo = glm::vec3(0.8f);
    s.materials.push_back(m);
    s.meshes.push_back(makeBowl(rings, segments, 0));
    s.environment.present = true;
    s.environment.radiance = glm::vec3(1.0f);
    s.camera.pose.position = glm::vec3(0.0f, 3.5f, 0.8f);
    s.camera.pose.target = glm::vec3(0.0f, 0.6f, 0.0f);
    s.camera.pose.up = glm::vec3(0.0f, 1.0f, 0.0f);
    s.camera.fovDegrees = 50.0f;
    s.camera.resolution = glm::ivec2(resolution);
    return s;
}

Scene bumpsUnderSky(int cells, float amplitude, int resolution) {
    Scene s = bowlUnderSky(1, 3, resolution);
    Mesh& m = s.meshes[0];
    m = Mesh{};
    m.name = "bumps";
    const auto height = [&](int i, int j) {
        std::uint32_t h = std::uint32_t(i) * 73856093u ^ std::uint32_t(j) * 19349663u;
        h = (h ^ (h >> 16)) * 0x45d9f3bu;
        h = (h ^ (h >> 16)) * 0x45d9f3bu;
        h ^= h >> 16;
        return amplitude * (2.0f * float(h & 0xffffu) / 65535.0f - 1.0f);
    };
    const auto corner = [&](int i, int j) {
        return glm::vec3(-1.0f + 2.0f * float(i) / float(cells), height(i, j), -1.0f + 2.0f * float(j) / float(cells));
    };
    for (int i = 0; i < cells; ++i) {
        for (int j = 0; j < cells; ++j) {
            const glm::vec3 a = corner(i, j), b = corner(i + 1, j), c = corner(i, j + 1), d = corner(i + 1, j + 1);
            for (const auto& [p, q, r] : {std::tuple{a, c, b}, std::tuple{b, c, d}}) {
                const std::uint32_t first = std::uint32_t(m.positions.size());
                const glm::vec3 n = glm::normalize(glm::cross(q - p, r - p));
                m.positions.insert(m.positions.end(), {p, q, r});
                m.normals.insert(m.normals.end(), {n, n, n});
                m.triangles.push_back({first, first + 1, first + 2});
            }
        }
    }
    s.camera.pose.position = glm::vec3(0.0f, 2.5f, 1.5f);
    s.camera.pose.target = glm::vec3(0.0f);
    return s;
}

Scene pointLightOverPlane(float albedo, float intensity, float h, int resolution) {
    Scene s;
    Material m;
    m.name = "plane";
    m.albedo = glm::vec3(albedo);
    s.materials.push_back(m);
    s.meshes.push_back(makeSquare(8.0f * h, 0));
    Light l;
    l.position = glm::vec3(0.0f, h, 0.0f);
    l.intensity = glm::vec3(intensity);
    s.lights.push_back(l);
    s.camera.pose.position = glm::vec3(0.4f * h, 2.5f * h, 1.5f * h);
    s.camera.pose.target = glm::vec3(0.0f);
    s.camera.pose.up = glm::vec3(0.0f, 1.0f, 0.0f);
    s.camera.fovDegrees = 60.0f;
    s.camera.resolution = glm::ivec2(resolution);
    return s;
}

glm::vec3 cameraRayHitY(const Scene& scene, glm::vec2 pixel, float planeY, float& t) {
    shader::GpuCamera cam = makeGpuCamera(scene.camera, 0.0, 1.0f);
    glm::vec3 d = shader::blCameraRayDirection(cam, pixel);
    t = (planeY - cam.position.y) / d.y;
    return cam.position + t * d;
}

float pointLitFloorRadiance(glm::vec3 p, glm::vec3 light, float intensity, float albedo) {
    glm::vec3 toLight = light - p;
    float r2 = glm::dot(toLight, toLight);
    float cosine = toLight.y / std::sqrt(r2);
    return albedo / shader::kPi * intensity * cosine / r2;
}

float polygonIrradiance(glm::vec3 x, glm::vec3 n, const std::vector<glm::vec3>& polygon, float radiance) {
    double sum = 0.0;
    for (std::size_t i = 0; i < polygon.size(); ++i) {
        const glm::dvec3 a = glm::normalize(glm::dvec3(polygon[i] - x));
        const glm::dvec3 b = glm::normalize(glm::dvec3(polygon[(i + 1) % polygon.size()] - x));
        const glm::dvec3 c = glm::cross(a, b);
        const double length = glm::length(c);
        if (length > 0.0) {
            sum += std::atan2(length, glm::dot(a, b)) * glm::dot(glm::dvec3(n), c / length);
        }
    }
    return static_cast<float>(0.5 * radiance * std::abs(sum));
}

AreaAndPointLit areaAndPointLit(const Scene& areaLit, glm::vec3 lightPosition) {
    AreaAndPointLit out{areaLit, areaLit, areaLit};
    Light point;
    point.position = lightPosition;
    point.intensity = glm::vec3(20000.0f);
    out.both.lights.push_back(point);
    out.pointOnly = out.both;
    for (Mesh& m : out.pointOnly.meshes) m.emission = glm::vec3(0.0f);
    return out;
}

} // namespace bl::test
