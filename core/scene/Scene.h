// The scene model shared by every renderer: meshes in world units, materials, lights, camera,
// environment, and keyframed rigid animation. Loaders fill it; nothing renders from files.
#pragma once

#include "base/Bounds.h"
#include "scene/Camera.h"
#include "scene/Environment.h"
#include "scene/Light.h"
#include "scene/Material.h"
#include "scene/Mesh.h"
#include "scene/SceneFeatures.h"

#include <string>
#include <vector>

namespace bl {

struct LoadStats {
    std::size_t degenerateTriangles = 0;
    std::size_t duplicateTriangles = 0;
    std::size_t repairedNormals = 0;
    std::size_t meshesWithGeneratedNormals = 0;
};

struct Scene {
    std::string path; // the file it was loaded from ("" if built in code)
    // Where the scene's local frame sits in the file's world: every position below is relative to
    // it. Loaders move a far scene near the origin (ScenePrecision.h) so that renderers work in
    // centred floats; zero otherwise.
    glm::dvec3 origin{0.0};
    Camera camera;
    std::vector<Material> materials;
    std::vector<Texture> textures;
    std::vector<Mesh> meshes;
    std::vector<Light> lights;
    Environment environment;
    LoadStats loadStats;
    // How a scene in another format was mapped to this model (MitsubaLoader.h), one line per
    // decision: what was ignored, approximated or tessellated. Empty for the native formats.
    std::vector<std::string> importNotes;
    // Every file read to build it, and every file a loader looked for and did not find (a missing
    // MTL or texture: adding it later changes the scene): the scene file, Mitsuba includes, glTF
    // buffers and images, mesh files, MTLs and their textures, the environment map (sorted, no
    // duplicates; filled by loadScene). What a cache of its renders must hash.
    std::vector<std::string> inputFiles;

    std::size_t triangleCount() const;
    // Bounds of all geometry over its whole motion (rotations' arcs between keys included).
    Bounds bounds() const;
    SceneFeatures features() const;
    // Every light as it is at `time` (keyframed ones moved, the rest as they are), in the order of
    // `lights`: what renderers upload and shade with for an image at that time.
    std::vector<Light> lightsAt(double time) const;
};

// Multiplies every length by `factor` and light intensities by factor^2, so that radiance (and
// therefore every image) stays the same: the check that nothing depends on absolute scale.
void scaleScene(Scene& scene, float factor);

// Moves every position (geometry, its keyframes, lights, camera) by `offset`, each sum rounded
// once to float: the same image, the check that nothing depends on where the scene sits (float
// steps grow with the distance). `origin` is left alone: the scene itself moves.
void translateScene(Scene& scene, const glm::dvec3& offset);

} // namespace bl
