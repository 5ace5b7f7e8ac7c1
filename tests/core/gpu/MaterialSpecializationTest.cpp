// The material specialization constants (core/gpu/MaterialSpecialization.h) come from the scene's
// features, while the shaders test each material with blHasGlossyLobe, blIsAnisotropic and its
// texture index. A constant that said "none" while some material had one would compile that
// material's lobe or texture out of a pass (gpu/MaterialSpecialization.glsl). What must hold is
// "constant off => no material has it"; on materials with non-negative specular (the TOML loader
// requires [0, 1]) the two agree exactly, edge cases included (one channel of specular, unequal
// exponents without specular, texture 0), and the test holds them to that.
#include "gpu/MaterialSpecialization.h"
#include "scene/Scene.h"
#include "scene/ShaderConversions.h"

#include <gtest/gtest.h>
#include <shared/Brdf.h>

using namespace bl;

namespace {
Material lambert() {
    Material m;
    m.albedo = glm::vec3(0.5f);
    return m;
}
} // namespace

TEST(MaterialSpecialization, ConstantsSayWhatTheShadersFind) {
    std::vector<Material> cases;
    cases.push_back(lambert());
    Material blueLobe = lambert(); // specular in one channel, isotropic
    blueLobe.specular = glm::vec3(0.0f, 0.0f, 0.1f);
    blueLobe.exponentU = blueLobe.exponentV = 40.0f;
    cases.push_back(blueLobe);
    Material anisotropic = blueLobe;
    anisotropic.exponentV = 400.0f;
    cases.push_back(anisotropic);
    Material unequalWithoutLobe = lambert(); // exponents that no lobe uses
    unequalWithoutLobe.exponentU = 10.0f;
    unequalWithoutLobe.exponentV = 1000.0f;
    cases.push_back(unequalWithoutLobe);
    Material textured = lambert();
    textured.albedoTexture = 0;
    cases.push_back(textured);

    // Every subset of the cases as a scene's materials.
    for (std::uint32_t subset = 0; subset < (1u << cases.size()); ++subset) {
        Scene scene;
        bool glossy = false, anisotropicLobe = false, withTexture = false;
        for (std::size_t i = 0; i < cases.size(); ++i) {
            if ((subset >> i & 1u) == 0u) continue;
            scene.materials.push_back(cases[i]);
            const shader::GpuMaterial g = toGpuMaterial(cases[i]);
            glossy |= shader::blHasGlossyLobe(g);
            anisotropicLobe |= shader::blHasGlossyLobe(g) && shader::blIsAnisotropic(g);
            withTexture |= g.albedoTexture != shader::kNoTexture;
        }
        std::vector<std::uint32_t> spec = {7u}; // a pass's own constant first
        gpu::appendMaterialSpecialization(spec, scene.features());
        ASSERT_EQ(spec.size(), 1u + shader::kMaterialSpecCount);
        EXPECT_EQ(spec[0], 7u);
        EXPECT_EQ(spec[1 + shader::kMaterialSpecGlossy], glossy ? 1u : 0u) << "subset " << subset;
        EXPECT_EQ(spec[1 + shader::kMaterialSpecAnisotropic], anisotropicLobe ? 1u : 0u) << "subset " << subset;
        EXPECT_EQ(spec[1 + shader::kMaterialSpecTextured], withTexture ? 1u : 0u) << "subset " << subset;
    }
}
