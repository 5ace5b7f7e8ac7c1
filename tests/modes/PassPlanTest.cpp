// Plans as data (modes/PassPlan.h): every mode's plan on scenes of every light kind has unique,
// kebab-case pass ids and reason codes and a text for each; a pass the plan lacks is an error
// naming the passes it has, never a silent "skipped". Host code only: plan() needs no device.
#include "base/Error.h"
#include "modes/PassPlan.h"
#include "modes/Registry.h"
#include "scene/SceneLoader.h"
#include "support/TestFiles.h"

#include <gtest/gtest.h>

#include <regex>
#include <set>
#include <string>

using namespace bl;

TEST(PassPlan, UnknownAndDuplicateIdsAreErrors) {
    PassPlan plan;
    plan.add("vpls", "VPLs", true, "rsm", "from reflective shadow cubes");
    EXPECT_TRUE(plan.runs("vpls"));
    EXPECT_EQ(plan.pass("vpls").code, "rsm");
    try {
        (void)plan.runs("vlps");
        ADD_FAILURE() << "an unknown id read as a pass";
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()), "pass plan: no pass 'vlps' (passes: vpls)");
    }
    EXPECT_THROW(plan.add("vpls", "again", false, "x", "y"), Error);
}

TEST(PassPlan, EveryModesPlanHasStableIdsAndCodes) {
    const std::regex kebab("[a-z0-9]+(-[a-z0-9]+)*");
    for (const char* file : {"data/cornell-box/cornell-point.toml", "data/cornell-box/cornell.toml",
                             "data/analytic/sky-blocks.toml", "data/cornell-box/cornell-animated.toml"}) {
        const Scene scene = loadScene(bl::test::sourcePath(file));
        for (const ModeEntry& entry : modeRegistry()) {
            const PassPlan plan = createMode(entry.name)->plan(scene);
            const std::string where = std::string(entry.name) + " on " + file;
            ASSERT_GT(plan.size(), 0u) << where;
            std::set<std::string> ids;
            for (const PlannedPass& p : plan) {
                EXPECT_TRUE(std::regex_match(p.id, kebab)) << where << ": id '" << p.id << "'";
                EXPECT_TRUE(std::regex_match(p.code, kebab)) << where << ": " << p.id << " code '" << p.code << "'";
                EXPECT_FALSE(p.reason.empty()) << where << ": " << p.id;
                EXPECT_FALSE(p.name.empty()) << where << ": " << p.id;
                EXPECT_TRUE(ids.insert(p.id).second) << where << ": id " << p.id << " twice";
            }
        }
    }
}
