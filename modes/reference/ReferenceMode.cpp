#include "modes/reference/ReferenceMode.h"

#include "base/Error.h"
#include "scene/Scene.h"

namespace bl {

std::vector<ParamSpec> ReferenceMode::parameters() {
    return {
        {kMaxSegments, std::int64_t{64}, "segments",
         "longest path (1: emitters only, 2: direct light; the shared references use 64)", 1, 100000, {}},
        {kRrDepth, std::int64_t{5}, "segments", "path length after which Russian roulette may end a path", 1, 100000, {}},
        {kThreads, std::int64_t{0}, "threads", "CPU worker threads (0: all hardware threads)", 0, 4096, {}},
        {kEnvSampling, std::string("luminance"), "", "environment-map light sampling", 0, 0, {"luminance", "uniform"}},
        {kEmitterSampling, std::string("area"), "",
         "emissive triangles: uniform in area, or in solid angle (Arvo 1995: 4% less relMSE, 30% more time on the "
         "Cornell box)",
         0, 0, {"area", "solid_angle"}},
    };
}

std::unique_ptr<Mode> ReferenceMode::create(const Settings& settings) { return std::make_unique<ReferenceMode>(settings); }

ReferenceMode::ReferenceMode(const Settings& settings) : mSettings(settings) {}
ReferenceMode::~ReferenceMode() = default;

ReferenceSettings ReferenceMode::rendererSettings() const {
    ReferenceSettings s;
    s.path.maxSegments = static_cast<int>(mSettings.getInt(kMaxSegments));
    s.path.rrDepth = static_cast<int>(mSettings.getInt(kRrDepth));
    s.threads = static_cast<int>(mSettings.getInt(kThreads));
    s.environmentImportance = mSettings.getString(kEnvSampling) == "luminance";
    s.emitterSampling =
        mSettings.getString(kEmitterSampling) == "area" ? EmitterSampling::Area : EmitterSampling::SolidAngle;
    return s;
}

PassPlan ReferenceMode::plan(const Scene& scene) const {
    SceneFeatures f = scene.features();
    PassPlan p;
    p.add("bvh", "build BVH", true, "always", std::to_string(f.triangles) + " triangles (Embree, high quality)");
    p.add("trace", "trace", true, "always",
          "1 path per pixel per iteration, at most " + std::to_string(mSettings.getInt(kMaxSegments)) + " segments");
    p.add("emitter-sampling", "emitter sampling", f.emissiveTriangles > 0,
          f.emissiveTriangles ? "emitter-sampling-" + mSettings.getString(kEmitterSampling) : "no-area-emitters",
          f.emissiveTriangles ? std::to_string(f.emissiveTriangles) + " emissive triangles, chosen by power, sampled by " +
                                    mSettings.getString(kEmitterSampling)
                              : "no emissive triangles");
    p.add("environment-sampling", "environment sampling", f.environment,
          !f.environment ? "no-environment" : f.environmentMap ? "environment-map" : "constant-environment",
          f.environment ? (f.environmentMap ? "by " + mSettings.getString(kEnvSampling) : "constant: uniform")
                        : "no environment");
    p.add("point-lights", "point/spot lights", f.shadowCastingLights() > 0,
          f.shadowCastingLights() > 0 ? "every-light-every-vertex" : "no-point-or-spot-lights",
          std::to_string(f.shadowCastingLights()) + " delta light(s), every one at every vertex");
    return p;
}

void ReferenceMode::setScene(const Scene& scene, vk::Context*) {
    mScene = &scene;
    mRenderer.reset();
    mTime.reset();
    mTimes.clear();
}

void ReferenceMode::iterate(const IterationInfo& info) {
    sceneState(mScene, name(), "iterate");
    using Clock = std::chrono::steady_clock;
    if (!mRenderer || !mTime || *mTime != info.time) {
        // A new scene time is a new image: the accumulation restarts.
        auto start = Clock::now();
        mRenderer = std::make_unique<ReferenceRenderer>(*mScene, info.time, rendererSettings());
        mTime = info.time;
        double ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
        mTimes = {{"build BVH", ms, 1}, {"trace", 0.0, 0}};
    }
    auto start = Clock::now();
    mRenderer->renderPass(mRenderer->samples(), static_cast<std::uint32_t>(info.seed));
    mTimes[1].totalMs += std::chrono::duration<double, std::milli>(Clock::now() - start).count();
    mTimes[1].count += 1;
}

ImageSet ReferenceMode::resolve() {
    sceneState(mScene, name(), "resolve");
    if (!mRenderer) {
        mRenderer = std::make_unique<ReferenceRenderer>(*mScene, 0.0, rendererSettings());
        mTime = 0.0;
    }
    ImageSet out;
    out.iterations = mRenderer->samples();
    out.layers.emplace_back("", mRenderer->mean());
    // Every path sample lands in its pixel unless it is NaN/Inf: none is dropped.
    addSampleLosses(out, mRenderer->nonFiniteSamples(), 0,
                    std::uint64_t(out.iterations) * out.layers.front().second.pixelCount());
    for (int l = 0; l < kPathLayerCount; ++l) {
        out.layers.emplace_back(kPathLayerNames[l], mRenderer->layer(l));
    }
    out.layers.emplace_back("variance", mRenderer->varianceOfMean());
    out.counters.emplace_back("rays", static_cast<double>(mRenderer->rays()));
    return out;
}

PathSample ReferenceMode::replay(int x, int y, std::uint32_t sampleIndex, std::uint32_t seed,
                                 std::vector<std::string>& log) {
    if (!mRenderer) {
        mRenderer = std::make_unique<ReferenceRenderer>(*mScene, mTime.value_or(0.0), rendererSettings());
    }
    return mRenderer->replay(x, y, sampleIndex, seed, log);
}

} // namespace bl
