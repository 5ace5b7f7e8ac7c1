// Mode `multibounce`: global illumination of any path length by reusing K resident omnidirectional
// global ray-bundles ([TO12 §7], [TO12p]; papers/EQUATIONS.md; papers/tokuyoshi-ogaki-2012-poster.md).
//
// One iteration = K bundles + paths_per_pixel camera paths per pixel. The K bundles are built first, all kept
// in one BundlePool with the hit payload and depth-sorted lists, each frame covering the scene's
// bounding sphere along a direction omega_k uniform on the sphere (Halton or independent random,
// randomly rotated about omega_k). Then every camera path starts at the G-buffer's visible point
// and, at each vertex x with normal n, picks a bundle k uniformly (directions = random, or any
// sequence with K <= 8: among those its last 8 segments did not use, never the one it arrived by;
// with K <= 8 the path ends once it has used all K), uses
// d = omega_k or -omega_k (whichever lies on n's side), and finds the next vertex as the fragment
// after x's depth along d in x's bundle pixel. For uniform directions the density of d on the hemisphere is
//   p_r(d) = q(d) + q(-d) = 1 / (2 pi),
// so the path weight gains f(x, d, wo) |n.d| / p_r(d) per bounce. At each vertex it adds the
// emission of an emitter's front face it arrived at, direct light from point and spot lights
// (cube shadow maps, 4x4 PCF), area emitters by next-event estimation through `emitter_points`
// points drawn on them each iteration (gpu/EmitterPointPass.h), combined with the bundles' hits of
// emitters by the balance heuristic (emitter_sampling = mis; the "first shot", which a
// bundle direction alone rarely finds for a small emitter), and the environment when the path escapes; Russian roulette after
// `rr_segments` segments. Contributions go to the reference's path-length layers.
//
// Bias: the next vertex is found along the bundle pixel's centre ray, up to half a pixel diagonal
// beside the exact ray from x, and placed where x's ray crosses that fragment's plane; it vanishes
// as bundle_resolution grows (measured in the README). Halton directions with K > 8 draw with
// replacement: a path goes back along the bundle it arrived by with probability 1 / K (a point mass
// standing for its stratum; the reason and numbers in MultibounceShared.h); random directions draw
// without replacement, which is exact. With K <= 8 every sequence draws without replacement and
// paths end after K + 2 segments (K + 1 on emitters and the sky): SettingTrades states the cut.
//
// Memory: K bundles of R^2 pixels each need heads (4 bytes per pixel per bundle) and nodes (36
// bytes: node, hit payload, predecessor) for every surface crossing; the pool grows to what an
// iteration needed and refuses (bl::Error, with the numbers) what the device or memory_cap_mib
// cannot hold.
//
// Imperfect bundles ([TO12p], bundles = imperfect): each bundle is built from its own set of
// `points` points uniform by area over all surfaces (SurfacePoints: a GPU pass over an area CDF),
// drawn as tangent-plane triangle splats cut to discs of radius splat_scale * sqrt(A / (pi N)).
// Paths step through them exactly as through perfect bundles; a vertex on a splat takes the
// point's shading normal, material and triangle (emission). Holes let light leak through surfaces
// and overlapping discs add redundant nodes (the trade-off over splat_scale: README).
//
// Textured albedo at every vertex: the path pass reads all of the scene's albedo textures from one
// storage buffer (gpu::PackedTextures: no descriptor indexing, which the core device does not
// enable), bilinearly as the reference does, at the bundle payload's UV (perfect bundles) or at the
// UV a splat carries where the path meets it (imperfect bundles: the poster's texture coordinates
// at each splat corner, stored per point as the UV at the centre and its world-space gradient).
//
// Parameters (`bundlelab modes`):
//   bundle_count       32      bundles       resident bundles per iteration (K)
//   paths_per_pixel    8       paths         camera paths per pixel through each iteration's bundles
//   bundle_resolution  128     pixels        side of each bundle
//   directions         halton                halton or random directions on the sphere
//   max_segments       64      segments      at most this many per path (1 emitters, 2 direct light)
//   rr_segments        5       segments      Russian roulette from this path length on
//   shadow_resolution  512     texels        side of each shadow cube face
//   memory_cap_mib     0       MiB           node storage limit of the bundle pool (0: half the
//                                            largest device-local heap)
//   bundles            perfect               perfect (the scene's triangles) or imperfect (point splats)
//   points             16384   points        imperfect: points per direction (a different set each)
//   splat_scale        2.0                   imperfect: disc radius in units of sqrt(A / (pi N))
//   splat_uv           corners               imperfect: corners (UV interpolated over the splat) or
//                                            centre (the splat's centre texel everywhere, for comparison)
//   emitter_sampling   mis                   area emitters and the environment after a bounce: mis (bundle
//                                            hits and escapes, emitter points and environment directions,
//                                            balance heuristic), bundles (hits and escapes alone, as
//                                            [TO12]), points (points and directions alone)
//   emitter_points     4       points        on the emitters per iteration, by power (gpu/EmitterPointPass.h)
//   emitter_shadow_resolution 256 texels     side of each emitter point's shadow cube face
//   environment_shots  4       directions    toward the environment per iteration, by its importance, a
//                                            depth map each (bundle/EnvironmentShadowPass.h; 0: escapes alone)
//   environment_shadow_resolution 512 texels side of each direction's depth map
#pragma once

#include "modes/Mode.h"
#include "modes/multibounce/MultibounceOptions.h"

#include <vulkan/vulkan.h>

#include <memory>
#include <optional>

namespace bl {

class MultibounceMode final : public Mode {
public:
    static constexpr const char* kBundleCount = "bundle_count";
    static constexpr const char* kPathsPerPixel = "paths_per_pixel";
    static constexpr const char* kBundleResolution = "bundle_resolution";
    static constexpr const char* kDirections = "directions";
    static constexpr const char* kMaxSegments = "max_segments";
    static constexpr const char* kRrSegments = "rr_segments";
    static constexpr const char* kShadowResolution = "shadow_resolution";
    static constexpr const char* kMemoryCap = "memory_cap_mib";
    static constexpr const char* kBundles = "bundles";
    static constexpr const char* kPoints = "points";
    static constexpr const char* kSplatScale = "splat_scale";
    static constexpr const char* kSplatUv = "splat_uv";
    static constexpr const char* kEmitterSampling = "emitter_sampling";
    static constexpr const char* kEmitterPoints = "emitter_points";
    static constexpr const char* kEmitterShadowResolution = "emitter_shadow_resolution";

    // The ids of the plan's passes that setScene() and iterate() execute.
    static constexpr const char* kPassSurfacePoints = "surface-points";
    static constexpr const char* kPassEmitterPoints = "emitter-points";
    static constexpr const char* kPassEnvironment = "environment";
    static constexpr const char* kPassEnvironmentShadows = "environment-shadows";
    static constexpr const char* kPassTextures = "textures";

    static std::vector<ParamSpec> parameters();
    static std::unique_ptr<Mode> create(const Settings& settings);

    explicit MultibounceMode(const Settings& settings);
    ~MultibounceMode() override;

    std::string_view name() const override { return "multibounce"; }
    void setScene(const Scene& scene, vk::Context* gpu) override;
    void iterate(const IterationInfo& info) override;
    ImageSet resolve() override;
    const Settings& settings() const override { return mSettings; }
    PassTimes timings() const override;
    PassPlan plan(const Scene& scene) const override;
    TradeSettings trades() const override;

private:
    bool distinctBundles() const; // a path draws its bundles without replacement
    struct Gpu;
    void buildBundles(const IterationInfo& info);
    void recordBundles(VkCommandBuffer cmd, std::uint32_t iteration, const IterationInfo& info);

    Settings mSettings;
    MultibounceOptions mOptions; // mSettings, typed, read once
    PassPlan mPlan;              // plan(scene) of the scene given to setScene: what iterate() runs
    const Scene* mScene = nullptr;
    vk::Context* mContext = nullptr;
    std::unique_ptr<Gpu> mGpu;
    std::uint32_t mIterations = 0;
};

} // namespace bl
