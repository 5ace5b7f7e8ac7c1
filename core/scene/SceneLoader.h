// Loads a scene: a TOML scene file (format in README.md), a Mitsuba 3 XML scene (MitsubaLoader.h), or a bare .obj/.ply, which becomes a scene
// with a fitted camera (its MTL emitters are area lights; with none, a headlight and a white sky).
// Strict: unknown keys, wrong types, missing files, NaN/Inf, non-positive sizes and out-of-range
// reflectances are errors naming the file, line and key. Degenerate and duplicate triangles are
// dropped and counted in the log.
#pragma once

#include "scene/Scene.h"

#include <string>

namespace bl {

// Resolution used when a bare mesh file is rendered.
inline constexpr int kDefaultResolution = 512;
// Largest accepted image side: beyond this a typo (an extra zero) would allocate gigabytes.
inline constexpr int kMaxResolution = 16384;

Scene loadScene(const std::string& path);

} // namespace bl
