// Whether a setting's time differs from the default's, judged from the ratios of renders taken in
// turns (each setting's render over the default's beside it). The machine's noise moves single
// renders by 10-30% and now and then by 2x, so a few pairs can all lean one way by chance: with
// five pairs, the middle half of their ratios misses 1 in more than a third of the studies of two
// equally fast settings. The study calls a difference measured only when an exact two-sided sign
// test puts the chance of the ratios leaning so far one way below kSignificance, or when every
// pair differs by more than kClearFactor either way (a render timed once, many times slower).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace vitrum::study {

inline constexpr double kSignificance = 0.05;
inline constexpr double kClearFactor = 2.0;

// The chance that n = above + below fair coin flips fall max(above, below) or more times on one
// side, either side (the two-sided p-value of the sign test); 1 when there are none.
inline double signTestP(std::size_t above, std::size_t below) {
    const std::size_t n = above + below;
    const std::size_t k = std::max(above, below);
    if (n == 0) return 1.0;
    double tail = 0.0;  // P(X >= k) for X ~ Binomial(n, 1/2), by log-binomials (no overflow for large n)
    for (std::size_t i = k; i <= n; ++i)
        tail += std::exp(std::lgamma(double(n) + 1) - std::lgamma(double(i) + 1) - std::lgamma(double(n - i) + 1) -
                         double(n) * std::log(2.0));
    return std::min(1.0, 2.0 * tail);
}

// Ratios equal to 1 count for neither side.
inline bool differenceMeasured(const std::vector<double>& ratios) {
    if (ratios.empty()) return false;
    const bool allSlower = std::all_of(ratios.begin(), ratios.end(), [](double r) { return r >= kClearFactor; });
    const bool allFaster = std::all_of(ratios.begin(), ratios.end(), [](double r) { return r <= 1.0 / kClearFactor; });
    if (allSlower || allFaster) return true;
    const auto above = std::size_t(std::count_if(ratios.begin(), ratios.end(), [](double r) { return r > 1.0; }));
    const auto below = std::size_t(std::count_if(ratios.begin(), ratios.end(), [](double r) { return r < 1.0; }));
    return signTestP(above, below) < kSignificance;
}

// The fewest pairs with which the sign test can call a difference measured: all of them on one
// side has the chance 2 / 2^n, under kSignificance from n = 6.
inline constexpr int kMinPairsToMeasure = 6;

}  // namespace vitrum::study
