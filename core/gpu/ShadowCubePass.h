// Omnidirectional shadow maps: six faces per cube, in one rgba16ui 2D-array image (layers 6 c .. 6 c + 5
// = cube c), each texel the distance from the cube's centre to the nearest surface along its centre
// ray (+inf where nothing) and that surface's normal (shaders/gpu/ShadowTexel.glsl). Cubes 0 .. L-1 belong to the scene's point and spot lights (record with
// a time); any cube can instead be rendered from an arbitrary point (record with a position), e.g.
// a virtual point light. Face bases are CubeFaces.h's, shared with the lookups
// (shaders/gpu/ShadowCubeLookup.glsl). After a record the image is in VK_IMAGE_LAYOUT_GENERAL.
#pragma once

#include "gpu/GpuScene.h"
#include "vk/GpuTimer.h"
#include "vk/Pipeline.h"

#include <optional>

namespace bl::gpu {

class ShadowCubePass {
public:
    // `cubes`: how many cubes the image holds; at least the scene's light count for the
    // per-light record.
    ShadowCubePass(const vk::Context& ctx, const GpuScene& scene, std::uint32_t resolution);
    ShadowCubePass(const vk::Context& ctx, const GpuScene& scene, std::uint32_t resolution, std::uint32_t cubes);
    // `cubes` cubes for record(cmd, position, ...) alone, however many lights the scene has: the
    // per-light record and refreshFor do nothing (e.g. points sampled on emitters). Without
    // `normals` the texels hold no normal (ShadowTexel.glsl's "none"): enough for cubes read by
    // one-tap lookups only, which have no crease rule, and cheaper to render.
    static ShadowCubePass forPositions(const vk::Context& ctx, const GpuScene& scene, std::uint32_t resolution,
                                       std::uint32_t cubes, bool normals = true);

    // Renders every light's cube (cube l = light l) at scene `time`.
    void record(VkCommandBuffer cmd, double time, vk::GpuTimer* timer);
    // Renders cube `cube` from `position` (world space) with the scene at `time`; the other cubes
    // keep their contents. `front` (unit, or zero): the cube lights only receivers x with
    // (x - position) . front >= 0 (a one-sided emitter's point), so only each face's front part
    // (frontTexels) is rendered and the rest cleared to "nothing in the way": a face-on emitter
    // renders one whole face and four halves instead of six faces.
    void record(VkCommandBuffer cmd, const glm::vec3& position, std::uint32_t cube, double time, vk::GpuTimer* timer,
                const glm::vec3& front = glm::vec3(0.0f));

    // The refresh rule every mode shares: a static scene's light cubes are rendered once, a scene
    // that moves (keyframed meshes or lights) needs them again whenever the scene time changes.
    // True when the caller's next submission must record(cmd, time, ...): the keyframed lights
    // have then been moved to `time` on the GPU (GpuScene::setLightTime) and the cubes count as
    // rendered for `time`. False without lights.
    bool refreshFor(const vk::Context& ctx, GpuScene& scene, double time);

    const vk::GpuImage& maps() const { return mMaps; }
    std::uint32_t resolution() const { return mResolution; }
    std::uint32_t lightCount() const { return mLightCount; }
    std::uint32_t cubeCount() const { return mCubes; }

    static constexpr std::uint32_t kFaces = 6;

    // The texels of face `face` of a `resolution`^2 cube whose centre rays d can have
    // d . front >= 0, as one rectangle with a texel's margin on every side (clamped to the face);
    // nullopt where no ray of the face can. front = 0: the whole face.
    static std::optional<VkRect2D> frontTexels(std::uint32_t face, const glm::vec3& front, std::uint32_t resolution);
    static constexpr std::uint32_t kBytesPerTexel = 8; // ShadowTexel.glsl: distance and normal

    // Device memory of `cubes` cubes of `resolution`^2 texels a face and the depth buffer they are
    // rendered with (for Context::requireDeviceMemory).
    static VkDeviceSize bytesFor(std::uint32_t resolution, std::uint64_t cubes) {
        const VkDeviceSize face = VkDeviceSize(resolution) * resolution;
        return face * kFaces * kBytesPerTexel * cubes + face * sizeof(float);
    }

private:
    ShadowCubePass(const vk::Context& ctx, const GpuScene& scene, std::uint32_t resolution, std::uint32_t cubes,
                   std::uint32_t lights, bool normals);
    // Renders the six faces of `cube` from `position` (their front parts, see record), leaving its
    // layers in GENERAL.
    void recordCube(VkCommandBuffer cmd, const glm::vec3& position, std::uint32_t cube, double time,
                    const glm::vec3& front = glm::vec3(0.0f));

    const GpuScene* mScene;
    std::uint32_t mResolution;
    std::uint32_t mLightCount;
    std::uint32_t mCubes;
    std::optional<double> mLightsTime; // scene time the light cubes were last recorded for
    vk::GpuImage mMaps;
    vk::GpuImage mDepth;
    vk::PipelineLayout mPipelineLayout;
    vk::Pipeline mPipeline;
};

} // namespace bl::gpu
