// Wavefront MTL: Kd -> albedo, Ks -> specular, Ns -> Phong exponent, Ke -> emission,
// map_Kd -> albedo texture (replacing Kd, as most renderers do; sRGB-decoded on the GPU).
// Other statements (Ka, Ni, illum, d, Tr, bump maps) do not affect our BRDFs and are skipped.
#pragma once

#include "scene/MeshFile.h"

#include <map>
#include <string>

namespace bl {

class MtlLibrary {
public:
    // Parses an MTL file named by `mtllib` at objPath:objLine. A missing MTL is a warning: its
    // materials then fall back to the default grey.
    void load(const std::string& mtlPath, const std::string& objPath, int objLine);

    // Every MTL and texture file it read or looked for and did not find (Scene::inputFiles: adding
    // a missing one later changes the scene).
    const std::vector<std::string>& files() const { return mFiles; }

    // Index of `name` in out.materials, adding it (and its texture) on first use. An unknown name
    // is a warning and gets a default material of that name.
    std::uint32_t indexOf(const std::string& name, MeshFile& out, const std::string& objPath,
                          int objLine);

private:
    struct Definition {
        Material material;
        glm::vec3 emission{0.0f};
        std::string texturePath; // resolved, or empty
    };
    std::map<std::string, Definition> mDefinitions;
    std::map<std::string, std::uint32_t> mUsed;
    std::map<std::string, int> mTextureOf; // path -> index in out.textures
    std::vector<std::string> mFiles;
};

// Finds `name` (which may use backslashes or another letter case, as in Sponza's MTL) relative to
// `dir`; empty if there is no such file.
std::string resolveAssetPath(const std::string& dir, const std::string& name);

} // namespace bl
