#include "support/AnalyticScenes.h"

#include <shared/Camera.h>

#include <cmath>

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
