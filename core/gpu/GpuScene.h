// A Scene uploaded for rasterization: one vertex and index buffer for all meshes, materials,
// lights, albedo textures (sRGB formats, so sampling decodes exactly) and the environment map.
#pragma once

#include "scene/Scene.h"
#include "vk/Buffer.h"
#include "vk/GpuImage.h"

#include <shared/GpuTypes.h>
#include <vector>

namespace bl::gpu {

struct GpuDraw {
    std::uint32_t mesh;
    std::uint32_t firstIndex;
    std::uint32_t indexCount;
    std::int32_t vertexOffset;
};

// Near planes, as a fraction of the scene's bounding radius: small enough that no real geometry is
// clipped, large enough for reversed float depth to keep ~20 bits of precision everywhere.
inline constexpr float kCameraNearFraction = 1e-5f;
inline constexpr float kShadowNearFraction = 1e-5f;

class GpuScene {
public:
    GpuScene(const vk::Context& ctx, const Scene& scene);

    const Scene& scene() const { return *mScene; }
    const SceneFeatures& features() const { return mFeatures; }
    float radius() const { return mRadius; }
    float cameraNear() const { return kCameraNearFraction * mRadius; }
    float shadowNear() const { return kShadowNearFraction * mRadius; }

    VkBuffer vertexBuffer() const { return mVertices.get(); }
    VkBuffer indexBuffer() const { return mIndices.get(); }
    VkBuffer materialBuffer() const { return mMaterials.get(); }
    VkBuffer lightBuffer() const { return mLights.get(); }
    // Per triangle (GpuScene order), in the mesh's own space: vec4(unit front normal, n . p0).
    VkBuffer planeBuffer() const { return mPlanes.get(); }
    const std::vector<GpuDraw>& draws() const { return mDraws; }
    const std::vector<shader::GpuLight>& lights() const { return mGpuLights; }

    // Texture of material m (a white texel when it has none), and the shared sampler.
    VkImageView materialTexture(std::uint32_t material) const;
    VkSampler textureSampler() const { return mTextureSampler.get(); }

    bool environmentPresent() const { return mScene->environment.present; }
    float environmentRotation() const; // radians
    VkImageView environmentView() const { return mEnvironment.view(); }
    VkSampler environmentSampler() const { return mEnvironmentSampler.get(); }

    glm::mat4 modelMatrix(std::uint32_t mesh, double time) const;

    // Binds the vertex and index buffers.
    void bindGeometry(VkCommandBuffer cmd) const;

    static std::vector<VkVertexInputBindingDescription> vertexBindings();
    static std::vector<VkVertexInputAttributeDescription> vertexAttributes();

private:
    const Scene* mScene;
    SceneFeatures mFeatures;
    float mRadius = 1.0f;
    vk::Buffer mVertices;
    vk::Buffer mIndices;
    vk::Buffer mMaterials;
    vk::Buffer mLights;
    vk::Buffer mPlanes;
    std::vector<GpuDraw> mDraws;
    std::vector<shader::GpuLight> mGpuLights;
    std::vector<vk::GpuImage> mTextures; // scene textures, then one white texel
    vk::Sampler mTextureSampler;
    vk::GpuImage mEnvironment;
    vk::Sampler mEnvironmentSampler;
};

} // namespace bl::gpu
