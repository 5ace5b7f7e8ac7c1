// Surface materials: Lambert + a glossy lobe (Brdf.h evaluates them).
#pragma once

#include "image/Image.h"

#include <glm/glm.hpp>
#include <string>

namespace bl {

struct Material {
    std::string name;
    glm::vec3 albedo{0.8f};   // Lambertian reflectance, BRDF = albedo / pi
    glm::vec3 specular{0.0f}; // reflectance of the glossy lobe
    float exponentU = 1.0f;   // Phong exponent, or Ashikhmin-Shirley n_u
    float exponentV = 1.0f;   // Ashikhmin-Shirley n_v (== exponentU: isotropic Phong)
    int albedoTexture = -1;   // index into Scene::textures

    bool glossy() const { return specular.x > 0.0f || specular.y > 0.0f || specular.z > 0.0f; }
    bool anisotropic() const { return exponentU != exponentV; }
};

// An albedo texture, sRGB-encoded as on disk.
struct Texture {
    std::string path;
    Rgba8Image image;
};

} // namespace bl
