#include "support/TexturedScenes.h"

namespace bl::test {

bool texturePlanar(Scene& s, const std::string& meshName, const Rgba8Image& texture) {
    s.textures.push_back({meshName + "-texture", texture});
    bool found = false;
    for (Mesh& m : s.meshes) {
        if (m.name.find(meshName) == std::string::npos) continue;
        found = true;
        Material textured = s.materials[m.material];
        textured.albedoTexture = int(s.textures.size()) - 1;
        s.materials.push_back(textured);
        m.material = std::uint32_t(s.materials.size() - 1);
        glm::vec3 lo(1e30f), hi(-1e30f);
        for (const glm::vec3& p : m.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
        m.uvs.clear();
        for (const glm::vec3& p : m.positions) m.uvs.emplace_back((p.x - lo.x) / (hi.x - lo.x), (p.z - lo.z) / (hi.z - lo.z));
    }
    return found;
}

Rgba8Image redGreenTexture() {
    Rgba8Image texture{64, 2, std::vector<unsigned char>(64 * 2 * 4, 255)};
    for (int y = 0; y < 2; ++y) {
        for (int x = 0; x < 64; ++x) {
            unsigned char* t = &texture.texels[std::size_t(4 * (y * 64 + x))];
            t[0] = x < 32 ? 230 : 60;
            t[1] = x < 32 ? 60 : 230;
            t[2] = 20;
        }
    }
    return texture;
}

} // namespace bl::test
