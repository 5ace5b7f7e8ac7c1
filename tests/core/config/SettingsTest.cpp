#include "config/Settings.h"
#include "support/TestFiles.h"

#include <gtest/gtest.h>

using namespace bl;
using bl::test::errorOf;

namespace {
Settings makeSettings() {
    return Settings({{"resolution", std::int64_t{256}, "texels", "side", 16, 4096, {}},
                     {"scale", 1.0, "", "factor", 0.0, 10.0, {}},
                     {"enabled", true, "", "switch", 0, 1, {}},
                     {"method", std::string("halton"), "", "sequence", 0, 0, {"halton", "random"}}});
}
} // namespace

TEST(Settings, DefaultsAndAssignmentsRoundTrip) {
    Settings s = makeSettings();
    EXPECT_EQ(s.getInt("resolution"), 256);
    s.assign("resolution=512");
    s.assign("scale=2.5");
    s.assign("enabled=false");
    s.assign("method=random");
    Settings copy = makeSettings();
    for (const auto& [k, v] : s.resolved()) {
        copy.set(k, v);
    }
    EXPECT_EQ(copy.resolved(), s.resolved());
    EXPECT_EQ(copy.getInt("resolution"), 512);
    EXPECT_DOUBLE_EQ(copy.getDouble("scale"), 2.5);
    EXPECT_FALSE(copy.getBool("enabled"));
    EXPECT_EQ(copy.getString("method"), "random");
}

TEST(Settings, RejectsUnknownKeysBadTypesAndRanges) {
    Settings s = makeSettings();
    EXPECT_NE(errorOf([&] { s.assign("resolutoin=3"); }).find("unknown parameter 'resolutoin' (known: resolution"),
              std::string::npos);
    EXPECT_NE(errorOf([&] { s.assign("resolution=12.5"); }).find("expects a value of type integer"), std::string::npos);
    EXPECT_NE(errorOf([&] { s.assign("resolution=8"); }).find("outside [16, 4096]"), std::string::npos);
    EXPECT_NE(errorOf([&] { s.assign("scale=nan"); }).find("outside"), std::string::npos);
    EXPECT_NE(errorOf([&] { s.assign("method=sobol"); }).find("not one of halton, random"), std::string::npos);
    EXPECT_NE(errorOf([&] { s.assign("novalue"); }).find("expected key=value"), std::string::npos);
    EXPECT_EQ(s.getInt("resolution"), 256); // failed assignments change nothing
}
