// What a mesh file (OBJ+MTL or PLY) yields: meshes split by material, the materials and textures
// they use (mesh.material indexes `materials`; material.albedoTexture indexes `textures`).
#pragma once

#include "scene/Material.h"
#include "scene/Mesh.h"

#include <string>
#include <vector>

namespace bl {

struct MeshFile {
    std::vector<Mesh> meshes;
    std::vector<Material> materials;
    std::vector<Texture> textures;
    std::vector<glm::vec3> materialEmission; // MTL Ke per material
    std::vector<std::string> materialFiles;  // MTL and texture files read or looked for (Scene::inputFiles)
};

// `readMaterials` false: mtllib and usemtl are skipped (Mitsuba's OBJ shapes take their bsdf from
// the scene, and a missing or malformed MTL must not refuse them); one mesh, one default material.
MeshFile loadObj(const std::string& path, bool readMaterials = true);
MeshFile loadPly(const std::string& path);
// By extension (.obj or .ply, any case).
MeshFile loadMeshFile(const std::string& path);

} // namespace bl
