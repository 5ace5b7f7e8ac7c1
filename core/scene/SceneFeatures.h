// What a scene contains and needs. Modes plan their passes from it and skip what is not needed.
#pragma once

#include "base/Bounds.h"

#include <cstddef>
#include <string>

namespace bl {

struct SceneFeatures {
    std::size_t triangles = 0;
    std::size_t meshes = 0;
    std::size_t materials = 0;
    Bounds bounds;            // in the scene's local frame
    glm::dvec3 origin{0.0};   // where that frame sits in the file's world (Scene::origin)
    bool glossy = false;      // any material with a specular lobe
    bool anisotropic = false; // any Ashikhmin-Shirley material
    bool textured = false;    // any albedo texture
    bool environment = false; // any light from infinity
    bool environmentMap = false;
    std::size_t pointLights = 0;
    std::size_t spotLights = 0;
    std::size_t emissiveMeshes = 0;
    std::size_t emissiveTriangles = 0;
    bool animated = false; // any keyframed mesh, camera or light

    std::size_t shadowCastingLights() const { return pointLights + spotLights; }
    // Human-readable multi-line summary (for `bundlelab info`).
    std::string describe() const;
};

} // namespace bl
