// Work a render did and threw away: samples refused as NaN/Inf, samples that never arrived, VPLs
// that carry no light. Modes report each such counter in ImageSet::lost (with the total it is a
// part of); drivers (the CLI, the experiment runner) turn them into a warning with the count, and
// refuse an image built on none of its work, so that no counter of lost work stays silent.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace bl {

struct ImageSet;

struct LostWork {
    std::string name;        // the counter's name in the JSON record, e.g. "invalid_vpls"
    std::uint64_t count = 0; // lost
    std::uint64_t total = 0; // of this many (0: total unknown, never refused)
    std::string unit;        // "samples", "VPLs": counters of one unit are disjoint parts of one total
    std::string why;         // for the user: "light paths that escaped or met black surfaces"
};

// The per-pixel sample accounting every accumulating mode shares: `nonFinite` refused as NaN/Inf
// and `dropped` never added, of `expected` (pixels x samples per pixel). Fills
// ImageSet::nonFiniteSamples, the "dropped_samples" counter and both lost-work entries.
void addSampleLosses(ImageSet& out, std::uint64_t nonFinite, std::uint64_t dropped, std::uint64_t expected);

struct LostWorkVerdict {
    std::vector<std::string> warnings; // one per counter with a count above zero
    std::string refusal;               // non-empty when some unit lost all of its work
};

// `mode` heads each message; ImageSet::notes come after the lost-work warnings. A unit whose counters add up to its whole total (and the total is not
// zero) means the image holds none of the work it was meant to: that is a refusal.
LostWorkVerdict judgeLostWork(const std::string& mode, const ImageSet& images);

} // namespace bl
