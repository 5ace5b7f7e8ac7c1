// A Scene uploaded for rasterization: one vertex and index buffer for all meshes, materials,
// lights, albedo textures (sRGB formats, so sampling decodes exactly) and the environment map.
//
// With a texture atlas (atlas/AtlasLink.h) the vertex buffer holds the atlas's vertices (split at
// chart seams) and the index buffer draws the same triangles in the same order on them, so every
// pass draws it as before; a second vertex stream (binding kAtlasVertexBinding, GpuAtlasVertex)
// gives each vertex its atlas uv and page, and two buffers map triangles between the numberings.
#pragma once

#include "atlas/AtlasLink.h"
#include "scene/Scene.h"
#include "scene/ScenePrecision.h"
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
// clipped, large enough for reversed float depth to keep ~20 bits of precision everywhere. The
// shadow near plane is the clearance the reference keeps from a point light (ScenePrecision.h):
// a surface nearer the light than that casts no shadow in any mode.
inline constexpr float kCameraNearFraction = 1e-5f;
inline constexpr float kShadowNearFraction = kRelativeClearance;

// The plane of triangle (a, b, c): vec4(unit front normal n, n . a), computed in double so that
// slivers, and triangles near float's range limits, get their exact plane. A triangle without one
// (collinear or coincident corners, non-finite coordinates) gets kNoPlane, which no shader can
// mistake for a plane: its normal is zero. Never NaN or Inf.
inline constexpr glm::vec4 kNoPlane{0.0f};
glm::vec4 trianglePlane(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c);

class GpuScene {
public:
    // `atlas` (optional) must be linked from `scene` (atlas::linkAtlas); it is uploaded, not kept.
    GpuScene(const vk::Context& ctx, const Scene& scene, const atlas::AtlasLink* atlas = nullptr);

    const Scene& scene() const { return *mScene; }
    const SceneFeatures& features() const { return mFeatures; }
    float radius() const { return mRadius; }
    float cameraNear() const { return kCameraNearFraction * mRadius; }
    float shadowNear() const { return lightClearance(mRadius); }

    VkBuffer vertexBuffer() const { return mVertices.get(); }
    VkBuffer indexBuffer() const { return mIndices.get(); }
    VkBuffer materialBuffer() const { return mMaterials.get(); }
    VkBuffer lightBuffer() const { return mLights.get(); }
    // Per triangle (GpuScene order), in the mesh's own space: vec4(unit front normal, n . p0), or
    // kNoPlane (zero normal: test for it before dividing by n . direction) where the triangle has none.
    VkBuffer planeBuffer() const { return mPlanes.get(); }
    std::uint32_t triangleCount() const { return mTriangleCount; }

    // The atlas link (only when built with an atlas; the accessors throw bl::Error otherwise).
    bool hasAtlas() const { return mHasAtlas; }
    VkBuffer atlasVertexBuffer() const;   // GpuAtlasVertex per vertex of vertexBuffer()
    VkBuffer atlasTriangleBuffer() const; // uint per GpuScene triangle: its atlas triangle
    VkBuffer sceneTriangleBuffer() const; // uint per atlas triangle: its GpuScene triangle
    const std::vector<GpuDraw>& draws() const { return mDraws; }
    const std::vector<shader::GpuLight>& lights() const { return mGpuLights; }
    // Moves keyframed lights to `time` (Scene::lightsAt) in lights() and the light buffer, which
    // start at time 0. A host write: call it between submissions, not while one may read it.
    void setLightTime(const vk::Context& ctx, double time);

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
    // Binds the atlas stream at kAtlasVertexBinding, for pipelines made with the atlas layout.
    void bindAtlasStream(VkCommandBuffer cmd) const;

    // Binding 0: GpuVertex at locations 0 (position + u) and 1 (normal + v).
    static std::vector<VkVertexInputBindingDescription> vertexBindings();
    static std::vector<VkVertexInputAttributeDescription> vertexAttributes();
    // The same plus the atlas stream: GpuAtlasVertex at kAtlasVertexLocationUv (vec2) and
    // kAtlasVertexLocationPage (uint).
    static std::vector<VkVertexInputBindingDescription> atlasVertexBindings();
    static std::vector<VkVertexInputAttributeDescription> atlasVertexAttributes();

private:
    const Scene* mScene;
    SceneFeatures mFeatures;
    float mRadius = 1.0f;
    vk::Buffer mVertices;
    vk::Buffer mIndices;
    vk::Buffer mMaterials;
    vk::Buffer mLights;
    vk::Buffer mPlanes;
    std::uint32_t mTriangleCount = 0;
    bool mHasAtlas = false;
    vk::Buffer mAtlasVertices;
    vk::Buffer mAtlasTriangles;
    vk::Buffer mSceneTriangles;
    std::vector<GpuDraw> mDraws;
    std::vector<shader::GpuLight> mGpuLights;
    std::vector<vk::GpuImage> mTextures; // scene textures, then one white texel
    vk::Sampler mTextureSampler;
    vk::GpuImage mEnvironment;
    vk::Sampler mEnvironmentSampler;
};

} // namespace bl::gpu
