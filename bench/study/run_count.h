// How many times the study renders a setting: enough renders to time it, and enough pairs with
// the default's renders for the sign test of time_difference.h to be able to call a difference
// measured.
#pragma once

#include <algorithm>
#include <cmath>

#include "study/time_difference.h"

namespace vitrum::study {

// A render longer than this is timed once: its run-to-run noise is small against its length.
// Shorter ones are repeated until they have filled about kTimedSeconds, up to kMaxRuns times:
// lavapipe's run-to-run noise on a 2-core machine is 10-30% for a render of 0.1 s, and a render
// of 10 ms at the study's size now and then takes twice as long (the hypervisor takes a CPU).
inline constexpr double kTimeOnceSeconds = 3.0;
inline constexpr double kTimedSeconds = 1.2;
inline constexpr int kMaxRuns = 15;

// The runs of a setting whose first render took firstSeconds, when the study was asked for `runs`:
// at least `runs`, more for short renders, one for long ones (and for --runs 1, a quick look).
// Runs paired with the default's are at least kMinPairsToMeasure.
inline int runsFor(double firstSeconds, int runs, bool paired) {
    if (runs == 1 || firstSeconds > kTimeOnceSeconds) return 1;
    const int least = paired ? std::max(runs, kMinPairsToMeasure) : runs;
    return std::clamp(int(std::ceil(kTimedSeconds / std::max(firstSeconds, 1e-3))), least, std::max(least, kMaxRuns));
}

}  // namespace vitrum::study
