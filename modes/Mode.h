// The interface every rendering strategy implements (ARCHITECTURE.md). A mode turns (Scene,
// settings, budget) into images and per-pass timings. One unit of work (iterate) is what a user
// would stop between: one spp, one frame, one bundle direction. Drivers (the CLI, the experiment
// runner) call setScene once, iterate until a budget or checkpoint, and resolve when they need
// the current estimate.
#pragma once

#include "base/Error.h"
#include "base/PassTime.h"
#include "config/Settings.h"
#include "image/Image.h"
#include "modes/LostWork.h"
#include "modes/PassPlan.h"

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace bl {

struct Scene;
namespace vk {
class Context;
}

// What one iterate() works on. An animated scene runs as a frame schedule (modes/FrameSchedule.h):
// frame f at scene time t_f, with drivers calling setScene before each frame, so every frame is
// its own estimate and `index` restarts at 0.
struct IterationInfo {
    std::uint32_t index = 0;   // 0, 1, 2, … since setScene (within the frame)
    std::uint64_t seed = 0;    // run seed; randomness derives from (seed, pixel, index, dimension)
    double time = 0.0;         // scene time in seconds of this frame, for animated scenes
    double previousTime = 0.0; // scene time of the previous frame (== time in frame 0): reprojection
    std::uint32_t frame = 0;   // animation frame number: 0, 1, 2, …
};

// Named images of one resolve: "" is the radiance estimate, others are AOVs.
struct ImageSet {
    std::vector<std::pair<std::string, Image>> layers;
    std::uint64_t nonFiniteSamples = 0; // samples discarded as NaN/Inf (never averaged in)
    std::uint32_t iterations = 0;
    std::vector<std::pair<std::string, double>> counters; // mode statistics, e.g. {"rays", 1.2e9}
    std::vector<LostWork> lost; // work thrown away; drivers warn and refuse (modes/LostWork.h)
    // What the user should know about this image that is not lost work, e.g. every VPL escaped the
    // scene (zero samples, a valid estimate of no light): drivers say each as a warning.
    std::vector<std::string> notes;

    const Image& radiance() const { return layers.at(0).second; }
};

// How a bundle check's replay answers visibility (SettingTrades.cpp, bundleVisibilityError):
// ListAlongFacetPlanes, every fragment but x's own triangle on its facet's plane where it lies
// ahead of x's, and where that finds nothing the near end's contact taps behind their gate (the
// walks with hit payloads: multibounce, bidir, skylight; bundle/Traversal.glsl,
// shared/BundleContacts.h);
// DepthMapNearestLight, a depth map's one surface nearest the light, with its facet's plane
// (bundle/DepthMapVisibility.glsl: raster's environment maps, skylight's visibility = depth_map;
// atlas, whose sorted lists exchange along exact centre rays).
enum class BundleRule { ListAlongFacetPlanes, DepthMapNearestLight };

// The settings whose accuracy depends on the scene, for the checks of modes/SettingTrades.h
// (what a mode trades, said before rendering). Empty keys: the mode has no such setting.
struct TradeSettings {
    std::string shadowKey;               // shadow cubes of point and spot lights
    std::uint32_t shadowResolution = 0;
    std::string bundleKey;               // global ray-bundles
    std::uint32_t bundleResolution = 0;
    std::string fitKey;                  // the bundle frame's fit, when the mode lets it be set
    bool fitVisible = false;             // frames fitted to the camera's visible points
    bool lobesByBundleDirections = false; // glossy lobes are met only by uniform bundle directions
    bool bundlesOnlyForEnvironment = false; // the mode builds bundles only for an environment's light
    // What bundleKey sizes, as the check names it, and why the frames cover the whole scene when
    // the mode cannot fit them to the visible points (no fitKey); bundleRule, how the check
    // replays their visibility (raster's environment depth maps: DepthMapNearestLight).
    std::string bundleWhat = "bundles";
    BundleRule bundleRule = BundleRule::ListAlongFacetPlanes;
    std::string wholeSceneWhy = "this mode's frames cover the whole scene: its paths leave the visible points";
    // A setting that ends the mode's paths early (multibounce: bundle_count <= 8 cuts a path at
    // K + 2 segments with point and spot lights' direct light and emitter points, K + 1 where it
    // meets an emitter by a bundle alone or the sky): its key and value, the longest path kept from
    // point lights, from emitters and from the sky, the
    // length the mode keeps without the cut (its max_segments), the value from which none is cut
    // (each unit of the value below it keeps one segment more) and the value to suggest when none
    // below that brings the cut under the tolerance. Empty key: no path is cut.
    std::string pathKey;
    std::uint32_t pathValue = 0;
    std::uint32_t pathSegments = 0;
    std::uint32_t pathSegmentsToEmitters = 0;
    std::uint32_t pathSegmentsToSky = 0;
    std::uint32_t pathUncut = 0;
    std::uint32_t pathUncutFrom = 0;
    std::uint32_t pathSuggested = 0;
    std::string pathNote; // a bias the cut comes with besides the paths it leaves out
};

// A mode's TradeSettings from the keys it names (empty: none), their values read from `settings`.
inline TradeSettings tradeSettingsOf(const Settings& settings, const std::string& shadowKey, const std::string& bundleKey,
                                     const std::string& fitKey = {}) {
    TradeSettings t;
    t.shadowKey = shadowKey;
    t.shadowResolution = shadowKey.empty() ? 0u : static_cast<std::uint32_t>(settings.getInt(shadowKey));
    t.bundleKey = bundleKey;
    t.bundleResolution = bundleKey.empty() ? 0u : static_cast<std::uint32_t>(settings.getInt(bundleKey));
    t.fitKey = fitKey;
    t.fitVisible = !fitKey.empty() && settings.getString(fitKey) == "visible";
    return t;
}

// The device a GPU mode's setScene() needs: a clear error naming the mode where it was given none.
inline vk::Context& requireDevice(vk::Context* ctx, std::string_view mode) {
    if (!ctx) {
        throw Error("mode " + std::string(mode) + " needs a Vulkan device");
    }
    return *ctx;
}

// What a mode's setScene() built, for a call that needs it: a clear error naming the mode and the
// call when there is none yet (iterate() or resolve() before setScene()).
template <typename State>
State& sceneState(State* state, std::string_view mode, std::string_view call) {
    if (!state) {
        throw Error(std::string(mode) + ": " + std::string(call) + "() before setScene()");
    }
    return *state;
}
template <typename State>
State& sceneState(const std::unique_ptr<State>& state, std::string_view mode, std::string_view call) {
    return sceneState(state.get(), mode, call);
}

class Mode {
public:
    virtual ~Mode() = default;
    virtual std::string_view name() const = 0;
    // Uploads the scene and builds pipelines (the set-up time drivers report apart from iteration
    // time), and starts a new estimate. `gpu` is null for CPU modes. The scene must outlive the
    // mode.
    virtual void setScene(const Scene& scene, vk::Context* gpu) = 0;
    virtual void iterate(const IterationInfo& info) = 0;
    virtual ImageSet resolve() = 0;
    virtual const Settings& settings() const = 0;
    virtual PassTimes timings() const = 0;
    // The passes this mode runs for the scene given to setScene (or would, before it): the same plan
    // iterate() executes (modes/PassPlan.h).
    virtual PassPlan plan(const Scene& scene) const = 0;
    // The settings modes/SettingTrades.h checks against the scene; none by default.
    virtual TradeSettings trades() const { return {}; }
    // True when what iterate() has accumulated does not depend on the camera, so that a new
    // camera needs resolve() only, not a new estimate (atlas without view-dependent passes). The
    // scene's camera is read at resolve().
    virtual bool viewIndependent() const { return false; }
};

// One warning line per light the scene has and `mode` leaves out (its plan's lightLeftOut passes),
// for drivers to print once per render.
std::vector<std::string> lightsLeftOut(const Mode& mode, const Scene& scene);

} // namespace bl
