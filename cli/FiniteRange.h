// A CLI11 check for floating-point options. CLI::Range lets NaN through (every comparison with
// it is false), so `--cone nan` used to run with a NaN cone; this one refuses non-finite values
// and names the value it refused.
#pragma once

#include <CLI/CLI.hpp>
#include <cmath>
#include <string>

namespace bl::cli {

inline CLI::Validator finiteRange(double lo, double hi) {
    const std::string range = "[" + CLI::detail::to_string(lo) + ", " + CLI::detail::to_string(hi) + "]";
    return CLI::Validator(
        [lo, hi, range](std::string& text) -> std::string {
            double value = 0.0;
            if (!CLI::detail::lexical_cast(text, value)) return "value '" + text + "' is not a number";
            if (!std::isfinite(value)) return "value '" + text + "' is not finite";
            if (value < lo || value > hi) return "value " + text + " outside " + range;
            return {};
        },
        "FLOAT in " + range);
}

} // namespace bl::cli
