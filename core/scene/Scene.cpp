#include "scene/Scene.h"

#include "base/Error.h"

#include <sstream>

namespace bl {

std::size_t Scene::triangleCount() const {
    std::size_t n = 0;
    for (const Mesh& m : meshes) {
        n += m.triangles.size();
    }
    return n;
}

Bounds Scene::bounds() const {
    Bounds b;
    for (const Mesh& m : meshes) {
        Bounds local;
        for (const glm::vec3& p : m.positions) {
            local.extend(p);
        }
        b.extend(m.animation.sweptBounds(local));
    }
    return b;
}

std::vector<Light> Scene::lightsAt(double time) const {
    std::vector<Light> out;
    out.reserve(lights.size());
    for (const Light& l : lights) {
        out.push_back(l.at(time));
    }
    return out;
}

SceneFeatures Scene::features() const {
    SceneFeatures f;
    f.triangles = triangleCount();
    f.meshes = meshes.size();
    f.materials = materials.size();
    f.bounds = bounds();
    f.origin = origin;
    for (const Material& m : materials) {
        f.glossy |= m.glossy();
        f.anisotropic |= m.glossy() && m.anisotropic();
        f.textured |= m.albedoTexture >= 0;
    }
    f.environment = environment.present;
    f.environmentMap = environment.hasMap();
    for (const Light& l : lights) {
        (l.type == Light::Type::Point ? f.pointLights : f.spotLights)++;
    }
    f.animated = camera.animated();
    for (const Light& l : lights) {
        f.animated |= l.animated();
    }
    for (const Mesh& m : meshes) {
        if (m.emissive()) {
            ++f.emissiveMeshes;
            f.emissiveTriangles += m.triangles.size();
        }
        f.animated |= m.animation.animated();
    }
    return f;
}

std::string SceneFeatures::describe() const {
    std::ostringstream s;
    auto yesNo = [](bool b) { return b ? "yes" : "no"; };
    s << "triangles        " << triangles << "\n"
      << "meshes           " << meshes << "\n"
      << "materials        " << materials << " (glossy: " << yesNo(glossy)
      << ", anisotropic: " << yesNo(anisotropic) << ", textured: " << yesNo(textured) << ")\n";
    if (bounds.empty()) {
        s << "bounds           empty\n";
    } else {
        s << "bounds           [" << bounds.lo.x << ", " << bounds.lo.y << ", " << bounds.lo.z << "] .. ["
          << bounds.hi.x << ", " << bounds.hi.y << ", " << bounds.hi.z << "]  (radius " << bounds.radius()
          << ")\n";
    }
    if (origin != glm::dvec3(0.0)) {
        s << "origin           [" << formatNumber(origin.x) << ", " << formatNumber(origin.y) << ", " << formatNumber(origin.z)
          << "]  (re-centred: bounds and renderers are relative to it)\n";
    }
    s << "point lights     " << pointLights << "\n"
      << "spot lights      " << spotLights << "\n"
      << "emissive meshes  " << emissiveMeshes << " (" << emissiveTriangles << " triangles)\n"
      << "environment      " << (environmentMap ? "map" : environment ? "constant" : "none") << "\n"
      << "animated         " << yesNo(animated) << "\n";
    return s.str();
}

void scaleScene(Scene& scene, float factor) {
    for (Mesh& m : scene.meshes) {
        for (glm::vec3& p : m.positions) {
            p *= factor;
        }
        RigidAnimation scaled;
        for (RigidKeyframe k : m.animation.keys()) {
            k.translate *= factor;
            scaled.addKey(k);
        }
        m.animation = scaled;
    }
    for (Light& l : scene.lights) {
        l.position *= factor;
        l.intensity *= factor * factor;
        for (LightKeyframe& k : l.keys) {
            k.position *= factor;
        }
    }
    auto scalePose = [factor](CameraPose& p) {
        p.position *= factor;
        p.target *= factor;
    };
    scalePose(scene.camera.pose);
    for (CameraKeyframe& k : scene.camera.keys) {
        scalePose(k.pose);
    }
}

void translateScene(Scene& scene, const glm::dvec3& offset) {
    // In double, so that a far scene moved back near the origin (recentreFarScene) keeps every bit
    // its floats had: the difference of two nearby floats is exact.
    auto move = [&offset](glm::vec3& p) { p = glm::vec3(glm::dvec3(p) + offset); };
    for (Mesh& m : scene.meshes) {
        if (m.animation.keys().empty()) {
            for (glm::vec3& p : m.positions) {
                move(p);
            }
            continue;
        }
        // Animated meshes move by their keyframes' translation (applied after their rotation).
        RigidAnimation moved;
        for (RigidKeyframe k : m.animation.keys()) {
            move(k.translate);
            moved.addKey(k);
        }
        m.animation = moved;
    }
    for (Light& l : scene.lights) {
        move(l.position);
        for (LightKeyframe& k : l.keys) {
            move(k.position);
        }
    }
    auto movePose = [&move](CameraPose& p) {
        move(p.position);
        move(p.target);
    };
    movePose(scene.camera.pose);
    for (CameraKeyframe& k : scene.camera.keys) {
        movePose(k.pose);
    }
}

} // namespace bl
