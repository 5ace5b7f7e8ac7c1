// Every registered mode refuses work before it has a scene, with an error naming the mode and the
// call (modes/Mode.h: sceneState), instead of dereferencing state setScene() never built. Host
// code only: no mode reaches the device before setScene().
#include "base/Error.h"
#include "modes/Registry.h"

#include <gtest/gtest.h>

#include <string>

using namespace bl;

TEST(ModeLifecycle, EveryModeRefusesIterateAndResolveBeforeSetScene) {
    ASSERT_FALSE(modeRegistry().empty());
    for (const ModeEntry& entry : modeRegistry()) {
        const std::string name(entry.name);
        std::unique_ptr<Mode> mode = createMode(entry.name);
        const auto expectRefusal = [&](const std::string& call, auto&& work) {
            try {
                work();
                ADD_FAILURE() << name << ": " << call << "() before setScene() did not throw";
            } catch (const Error& e) {
                EXPECT_EQ(std::string(e.what()), name + ": " + call + "() before setScene()");
            }
        };
        expectRefusal("iterate", [&] { mode->iterate({0, 1, 0.0}); });
        expectRefusal("resolve", [&] { (void)mode->resolve(); });
    }
}
