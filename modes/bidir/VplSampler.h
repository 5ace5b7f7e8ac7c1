// Light sub-paths of mode bidir: one virtual point light (VPL) per pair, the first surface a ray
// from a point or spot light meets ([TO12 §4.1], papers/EQUATIONS.md).
//
// Sampling (the densities the estimator divides by, exactly):
//   light l            uniformly among the scene's point/spot lights: P(l) = 1 / L
//   omega_{0,1}        point light: uniform on the sphere, p_e = 1 / (4 pi);
//                      spot light: p_e = I(omega) / integral(I), the profile's smoothstep included
//                      ([TO12] 4.1; shaders/modes/bidir/BidirShared.h blBidirEmissionPdf, shared
//                      with the shader, which needs it for MIS)
//   y                  the first hit of that ray (Embree, exact), so its area density is
//                      P(l) p_e (n_y . omega_{y,0}) / |y - x0|^2.
// The ray is traced on the CPU against the scene at the frame's time instead of read from a
// reflective shadow map: exact (no texel discretization), and K rays per frame cost nothing beside
// the K shadow cubes. The paper's way, reflective shadow maps on the GPU, is ReflectiveShadowMap.h
// (vpl_source = rsm); this sampler is the exact, independent one it is checked against.
#pragma once

#include "reference/EmbreeScene.h"
#include "scene/Scene.h"

#include <memory>
#include <modes/bidir/BidirShared.h>
#include <vector>

namespace bl {

class VplSampler {
public:
    explicit VplSampler(const Scene& scene);

    // The K VPLs of pairs [first, first + count) for run seed `seed`, the scene at `time`: a pure
    // function of (seed, pair index, time). Rays that escape or meet a surface from which nothing
    // can reflect give a VPL with valid = 0 (it still counts as a sample: the estimate stays
    // unbiased). `lift`: how far each VPL's shadow cube centre sits off its surface, world units.
    std::vector<shader::BidirVpl> sample(std::uint64_t first, std::uint32_t count, std::uint32_t seed, double time,
                                         float lift);

private:
    const Scene* mScene;
    std::unique_ptr<EmbreeScene> mEmbree; // baked at mEmbree->time()
    std::vector<shader::GpuMaterial> mMaterials;
};

} // namespace bl
