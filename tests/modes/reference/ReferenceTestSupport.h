// Rendering helpers for the reference mode's tests.
#pragma once

#include "modes/Registry.h"
#include "scene/Scene.h"

#include <gtest/gtest.h>

namespace bl::test {

inline ImageSet renderReference(const Scene& scene, std::uint32_t spp, const std::vector<std::string>& settings = {},
                                std::uint64_t seed = 0) {
    std::unique_ptr<Mode> mode = createMode("reference", settings);
    mode->setScene(scene, nullptr);
    for (std::uint32_t i = 0; i < spp; ++i) {
        mode->iterate({i, seed, 0.0});
    }
    return mode->resolve();
}

inline const Image& layerOf(const ImageSet& set, const std::string& name) {
    for (const auto& [n, image] : set.layers) {
        if (n == name) return image;
    }
    throw std::runtime_error("no layer " + name);
}

} // namespace bl::test
