// A mode's pass plan as data: which passes run for a scene and why. Each pass has a stable id and
// each decision a stable reason code (tests, tools and the viewer check those; the text is for
// people). A mode builds its plan once per scene from its typed options; iterate() runs what the
// plan says (PassPlan::runs) and `bundlelab plan` prints the same object, so the two cannot
// disagree.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace bl {

struct PlannedPass {
    std::string id;     // stable, kebab-case: "vpls", "bundles", "light-shadow-cubes"
    std::string name;   // for people: "VPL rays + VPL shadow cubes"
    bool runs = true;
    std::string code;   // stable reason code, kebab-case: "no-point-or-spot-lights", "strategy-vpl"
    std::string reason; // the code's text for this scene and these settings
    // The scene has a light this mode leaves out of its image (an area light in raster, a point
    // light in skylight): drivers warn at render time, not only in `bundlelab plan`.
    bool lightLeftOut = false;
};

class PassPlan {
public:
    // Appends a pass; its id must be new (a plan with two passes of one id is a mode's bug).
    PassPlan& add(PlannedPass pass);
    PassPlan& add(std::string id, std::string name, bool runs, std::string code, std::string reason,
                  bool lightLeftOut = false);

    bool has(std::string_view id) const;
    // The pass of that id; an id the plan lacks throws (a typo must not read as "skipped").
    const PlannedPass& pass(std::string_view id) const;
    bool runs(std::string_view id) const { return pass(id).runs; }

    const std::vector<PlannedPass>& passes() const { return mPasses; }
    std::vector<PlannedPass>::const_iterator begin() const { return mPasses.begin(); }
    std::vector<PlannedPass>::const_iterator end() const { return mPasses.end(); }
    std::size_t size() const { return mPasses.size(); }

private:
    std::vector<PlannedPass> mPasses;
};

} // namespace bl
