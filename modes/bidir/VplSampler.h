// Light sub-paths of mode bidir: one virtual point light (VPL) per pair, the first surface a ray
// from a point or spot light meets ([TO12 §4.1], papers/EQUATIONS.md).
//
// Sampling (the densities the estimator divides by, exactly):
//   source             uniformly among the scene's L point/spot lights and, where it has area
//                      emitters, one more source for all of them: P = 1 / (L + 1) (else 1 / L)
//   omega_{0,1}        point light: uniform on the sphere, p_e = 1 / (4 pi);
//                      spot light: p_e = I(omega) / integral(I), the profile's smoothstep included
//                      ([TO12] 4.1; shaders/modes/bidir/BidirShared.h blBidirEmissionPdf, shared
//                      with the shader, which needs it for MIS)
//   y                  the first hit of that ray (Embree, exact), so its area density is
//                      P(l) p_e (n_y . omega_{y,0}) / |y - x0|^2.
// The area source (light = L in the record): x0 on the emitters by power as the emitter points are
// (gpu/EmitterPointSampler.h, p_A = mean(L_e) / Phi), omega_{0,1} cosine-weighted about the
// emitter's front normal, and the record as if x0 were a point light of intensity
// L_e cos0 / p_A(x0) sampled with the solid-angle density P cos0 / pi: then intensity / pdfLight =
// L_e pi / (P p_A), the path's weight, and areaPdf = P (cos0 / pi) (n_y . omega_{y,0}) / |y - x0|^2
// is y's density given x0 (x0's own density p_A is the same in the bundle strategy's emitter
// points, so the balance heuristic compares the densities of y alone; evaluate.comp.glsl).
// The ray is traced on the CPU against the scene at the frame's time instead of read from a
// reflective shadow map: exact (no texel discretization), and K rays per frame cost nothing beside
// the K shadow cubes. The paper's way, reflective shadow maps on the GPU, is ReflectiveShadowMap.h
// (vpl_source = rsm); this sampler is the exact, independent one it is checked against.
#pragma once

#include "atlas/AlbedoLookup.h"
#include "gpu/EmitterPointSampler.h"
#include "reference/EmbreeScene.h"
#include "scene/Scene.h"

#include <memory>
#include <modes/bidir/BidirShared.h>
#include <vector>

namespace bl {

class VplSampler {
public:
    // `areaSource`: the area emitters are a source too (where the scene has any).
    VplSampler(const Scene& scene, bool areaSource);

    // The K VPLs of pairs [first, first + count) for run seed `seed`, the scene at `time`: a pure
    // function of (seed, pair index, time). Rays that escape or meet a surface from which nothing
    // can reflect give a VPL with valid = 0 (it still counts as a sample: the estimate stays
    // unbiased). `lift`: how far each VPL's shadow cube centre sits off its surface, world units.
    std::vector<shader::BidirVpl> sample(std::uint64_t first, std::uint32_t count, std::uint32_t seed, double time,
                                         float lift);

    // Pair `pair`'s VPL from the area emitters, the source chosen with probability 1 / (L + 1)
    // (VplSampler's own choice, or the reflective shadow map's: vpl_source = rsm traces its area
    // pairs here). Invalid without an area source.
    shader::BidirVpl areaVpl(std::uint64_t pair, std::uint32_t seed, double time, float lift);

    // Whether the area emitters are a VPL source (the scene has emissive triangles).
    bool areaSource() const { return mAreaSource; }

private:
    void bake(double time);
    static std::uint32_t pairKey(std::uint32_t seed, std::uint64_t pair);
    // The record of a light ray along omega that landed at `hit` (its source's fields set).
    void landed(shader::BidirVpl& v, const glm::vec3& omega, const SurfaceHit& hit, float lift) const;

    const Scene* mScene;
    std::unique_ptr<EmbreeScene> mEmbree; // baked at mEmbree->time()
    std::vector<shader::GpuMaterial> mMaterials;
    atlas::AlbedoLookup mAlbedo; // textured albedo at the VPL, as the G-buffer samples it
    gpu::EmitterPointSampler mEmitters; // the area source
    bool mAreaSource = false;
};

} // namespace bl
