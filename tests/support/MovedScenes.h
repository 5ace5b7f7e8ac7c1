// Scene files moved and scaled as a user would write them (the [[mesh]] translate / scale keys,
// camera and light positions in the file), for the precision tests: what reaches the renderers
// goes through the loader, as it does from the command line.
#pragma once

#include <glm/glm.hpp>
#include <string>

namespace bl::test {

// A copy of the scene file `relative` (to the repository root) in a temporary directory, every
// [[mesh]] given `translate = offset` and `scale = scale` (none of the files may have them), and
// every camera/light position and target written as scale * p + offset. Light intensities are
// multiplied by scale^2 (radiance, so every image, stays the same). Returns the new file's path.
std::string writeMovedScene(const std::string& relative, const glm::dvec3& offset,
                            double scale = 1.0, const std::string& name = "moved.toml");

} // namespace bl::test
