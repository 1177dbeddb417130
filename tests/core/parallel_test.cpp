// common/parallel.h against its sequential meaning: parallelFor visits every index once, whatever
// the number of cores, and passes on a failure; parallelSort gives std::sort's order.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <random>
#include <stdexcept>
#include <vector>

#include "common/parallel.h"

namespace vitrum {
namespace {

TEST(ParallelFor, VisitsEveryIndexOnceInRangesThatCoverTheLoop) {
    for (std::size_t count : {std::size_t(0), std::size_t(1), std::size_t(1000), std::size_t(1) << 20}) {
        std::vector<std::atomic<int>> visits(count);
        parallelFor(count, [&](std::size_t begin, std::size_t end) {
            ASSERT_LE(begin, end);
            ASSERT_LE(end, count);
            for (std::size_t i = begin; i < end; ++i) visits[i].fetch_add(1);
        }, 1000);
        EXPECT_TRUE(std::all_of(visits.begin(), visits.end(), [](const std::atomic<int>& v) { return v == 1; }))
            << count;
    }
}

TEST(ParallelFor, AFailureInAnyChunkReachesTheCaller) {
    const std::size_t count = std::size_t(1) << 20;
    EXPECT_THROW(parallelFor(count, [&](std::size_t, std::size_t end) {
        if (end == count) throw std::runtime_error("the last chunk failed");
    }, 1000), std::runtime_error);
}

struct Keyed {
    std::uint32_t key;
    std::uint32_t payload;  // not compared: equal keys may come in any order
};

TEST(ParallelSort, GivesTheOrderOfStdSort) {
    std::mt19937 rng(5);
    auto check = [](std::vector<std::uint64_t> values, unsigned threads) {
        std::vector<std::uint64_t> expected = values;
        std::sort(expected.begin(), expected.end());
        parallelSort(values.begin(), values.end(), std::less<>(), threads);
        EXPECT_EQ(values, expected) << threads << " threads";
    };
    std::vector<std::uint64_t> random(300'000), fewKeys(300'000), equal(300'000, 7), sorted(300'000);
    for (auto& v : random) v = rng();
    for (auto& v : fewKeys) v = rng() % 3;  // the sample's median is often the smallest
    for (std::size_t i = 0; i < sorted.size(); ++i) sorted[i] = i;
    std::vector<std::uint64_t> reversed(sorted.rbegin(), sorted.rend());
    for (unsigned threads : {1u, 2u, 3u, 8u})
        for (const auto* values : {&random, &fewKeys, &equal, &sorted, &reversed}) check(*values, threads);
    check({}, 2);
    check({3, 1, 2}, 2);
}

TEST(ParallelSort, KeepsEveryElement) {
    std::mt19937 rng(9);
    std::vector<Keyed> values(200'000);
    for (std::uint32_t i = 0; i < values.size(); ++i) values[i] = {std::uint32_t(rng() % 1000), i};
    parallelSort(values.begin(), values.end(), [](const Keyed& a, const Keyed& b) { return a.key < b.key; }, 4);
    EXPECT_TRUE(std::is_sorted(values.begin(), values.end(), [](const Keyed& a, const Keyed& b) { return a.key < b.key; }));
    std::vector<bool> seen(values.size(), false);
    for (const Keyed& v : values) seen[v.payload] = true;
    EXPECT_TRUE(std::all_of(seen.begin(), seen.end(), [](bool s) { return s; }));
}

}  // namespace
}  // namespace vitrum
