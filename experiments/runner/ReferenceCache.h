// The reference image of each scene: a given EXR, or rendered once by the `reference` mode and
// cached under DIR/references/<hash>.exr, the hash covering every file the scene loads, the
// resolution, the reference settings and spp. Also its own noise level (from its variance
// layer), drawn on convergence plots: no method can be judged below it.
#pragma once

#include "image/Image.h"
#include "runner/ExperimentConfig.h"

#include <map>
#include <string>

namespace bl {

struct ReferenceImage {
    Image image;
    std::string path;
    double noiseMse = 0.0;    // mean variance of the reference's pixel means
    double noiseRelMse = 0.0; // the same, relative (epsilon 0.01)
    bool rendered = false;    // false: taken from a file (noise unknown: 0)
};

class ReferenceCache {
public:
    ReferenceCache(const ExperimentConfig& config, std::string outDir);

    // Renders (or loads from the cache) every reference the given tasks are judged against.
    void prepare(const std::vector<const Task*>& tasks);
    const ReferenceImage* find(const Task& task) const;
    // How many distinct references the given tasks need that are neither given files nor cached
    // yet (what prepare() would render).
    std::size_t toRender(const std::vector<const Task*>& tasks) const;

private:
    std::string key(const Task& task) const;
    std::string cachePath(const SceneEntry& scene, const std::vector<std::pair<std::string, ParamValue>>& settings) const;
    ReferenceImage make(const SceneEntry& scene, const std::vector<std::pair<std::string, ParamValue>>& settings) const;

    const ExperimentConfig* mConfig;
    std::string mOutDir;
    std::map<std::string, ReferenceImage> mImages; // by key(task)
};

} // namespace bl
