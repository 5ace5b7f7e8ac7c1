// Light sub-paths of mode bidir from reflective shadow maps on the GPU ([TO12 §4.1],
// papers/EQUATIONS.md; `vpl_source = rsm`): per frame, each point/spot light's cube of N^2
// faces is rendered by the G-buffer pass from the light (position, normal, textured albedo,
// material) with a fresh uniform sub-texel jitter per face, and VPL k is sampled on the GPU
// (shaders/modes/bidir/rsm_sample.comp.glsl): light l uniformly (P(l) = 1 / L), then a texel by the
// light's flux through it (p_e proportional to I(omega) times the texel's solid angle: the spot
// light's p_e follows its profile), the VPL the surface that texel holds. Densities, exactly
// (shaders/modes/bidir/Rsm.h): p_e(omega) = P(t) J(omega) / A, the jitter making it a density over
// every direction of the texel, so the RSM adds no discretization bias; only where the rasterizer's
// sample point differs from the exact first hit (sub-ulp) and where a spot light's profile is zero
// at a texel's centre and four corners but not inside it (a sliver at the cone's edge, where the
// smooth-step profile is ~0) is anything not sampled.
//
// The host completes each VPL (densities, intensity, validity) from what the pass gathered, as
// VplSampler does for traced rays (same record, same validity rules), and the evaluation pass
// reads the same CDF (cdf()) for the MIS density of directions it did not sample.
#pragma once

#include "gpu/GBufferPass.h"
#include "scene/Scene.h"
#include "vk/Buffer.h"
#include "vk/BoundSet.h"
#include "vk/GpuTimer.h"
#include "vk/ComputePass.h"

#include <memory>
#include <modes/bidir/BidirShared.h>
#include <modes/bidir/Rsm.h>
#include <optional>
#include <vector>

namespace bl {

class ReflectiveShadowMap {
public:
    // `resolution`: N, texels per face side.
    ReflectiveShadowMap(const vk::Context& ctx, const gpu::GpuScene& scene, std::uint32_t resolution);

    // The K VPLs of pairs [first, first + count) for run seed `seed`, the scene at `time`: renders
    // the cubes (submits and waits) and gathers the chosen texels. Rays that escape, or surfaces
    // nothing reflects from, give valid = 0 (still samples). `lift` as VplSampler::sample.
    // `areaSource`: the area emitters are one more source (P = 1 / (L + 1)); the pairs that draw it
    // are left invalid here and listed in `areaPairs` for the host to trace (VplSampler::areaVpl).
    std::vector<shader::BidirVpl> sample(std::uint64_t first, std::uint32_t count, std::uint32_t seed, double time,
                                         float lift, vk::GpuTimer* timer, bool areaSource,
                                         std::vector<std::uint32_t>& areaPairs);

    // The CDF block the evaluation pass binds (header: N, then the starts of every light's texels).
    VkBuffer cdf() const { return mCdf.get(); }
    // VPLs whose direction fell in another texel than the one chosen (the rasterizer's sample
    // point at a texel's edge): their density is taken at the direction's texel, as MIS does.
    std::uint64_t texelMismatches() const { return mMismatches; }

    // The host mirror of p_e(omega | light l) (Rsm.h), omega unit.
    float directionPdf(std::uint32_t light, const glm::vec3& omega) const;

private:
    void buildCdf(const std::vector<shader::GpuLight>& lights);

    const vk::Context* mCtx;
    const gpu::GpuScene* mScene;
    std::uint32_t mResolution;
    std::unique_ptr<gpu::GBufferPass> mFace; // one face at a time
    vk::Buffer mCdf;                          // header + start[] (Upload)
    vk::Buffer mTexels;                       // BidirRsmTexel[count] (Readback)
    std::uint32_t mCapacity = 0;
    std::vector<std::uint32_t> mStart;        // host copy of start[]
    std::optional<double> mCdfTime;           // lights at this time built the CDF
    std::vector<shader::GpuMaterial> mMaterials;
    vk::BoundSet mBound;
    vk::ComputePass<shader::BidirRsmPush> mSample;
    std::uint64_t mMismatches = 0;
};

} // namespace bl
