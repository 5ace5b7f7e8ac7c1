#include "modes/LostWork.h"

#include "modes/Mode.h"

#include <map>

namespace bl {

void addSampleLosses(ImageSet& out, std::uint64_t nonFinite, std::uint64_t dropped, std::uint64_t expected) {
    out.nonFiniteSamples = nonFinite;
    out.counters.emplace_back("dropped_samples", double(dropped));
    out.lost.push_back({"non_finite_samples", nonFinite, expected, "samples", "refused as NaN or infinite"});
    out.lost.push_back({"dropped_samples", dropped, expected, "samples", "never added to their pixel"});
}

LostWorkVerdict judgeLostWork(const std::string& mode, const ImageSet& images) {
    LostWorkVerdict v;
    std::map<std::string, std::pair<std::uint64_t, std::uint64_t>> units; // unit -> (lost, total)
    for (const LostWork& l : images.lost) {
        if (l.count == 0) continue;
        std::string line = mode + ": " + std::to_string(l.count) + " " + l.unit;
        if (l.total > 0) line += " of " + std::to_string(l.total);
        line += " " + l.why + " (" + l.name + ")";
        v.warnings.push_back(line);
        if (l.total > 0) {
            auto& [lost, total] = units[l.unit];
            lost += l.count;
            total = l.total;
        }
    }
    for (const std::string& note : images.notes) v.warnings.push_back(mode + ": " + note);
    for (const auto& [unit, counts] : units) {
        if (counts.first >= counts.second) {
            v.refusal = mode + ": every one of its " + std::to_string(counts.second) + " " + unit +
                        " was lost (see the warnings above): the image holds none of the work it was meant to, "
                        "so it is not written";
            break;
        }
    }
    return v;
}

} // namespace bl
