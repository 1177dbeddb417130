// The accuracy study (bench/accuracy_study.cpp): its Pareto front, and a quick run end to end
// whose report must hold what physics says about the settings it measured.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <unistd.h>

#include "bench_support.h"
#include "study/pareto.h"
#include "study/run_count.h"
#include "study/time_difference.h"

namespace vitrum::study {
namespace {

namespace fs = std::filesystem;

TEST(Pareto, KeepsThePointsNothingBeatsOnBothTimeAndError) {
    //            0: fast, bad   1: dominated by 0   2: slower, better   3: dominated by 2   4: slowest, best
    const std::vector<TimeError> points = {{1.0, 0.5}, {2.0, 0.6}, {3.0, 0.1}, {3.5, 0.1}, {9.0, 0.01}};
    EXPECT_EQ(paretoFront(points), (std::vector<std::size_t>{0, 2, 4}));
}

TEST(Pareto, EqualTimesKeepOnlyTheSmallerErrorAndEmptyInputGivesNoFront) {
    EXPECT_EQ(paretoFront({{2.0, 0.3}, {2.0, 0.2}, {1.0, 0.9}}), (std::vector<std::size_t>{2, 1}));
    EXPECT_TRUE(paretoFront({}).empty());
}

// The study's timing noise is the interquartile range: the quartiles of 1..5 are 2 and 4; of
// 1, 2, 3, 4 (interpolated a quarter and three quarters of the way along) 1.75 and 3.25. One
// slow run among many moves the range little, where it would double the slowest-to-fastest one.
TEST(Quantile, InterpolatesBetweenOrderStatisticsWhateverTheOrder) {
    EXPECT_DOUBLE_EQ(bench::quantile({5, 1, 4, 2, 3}, 0.25), 2.0);
    EXPECT_DOUBLE_EQ(bench::quantile({5, 1, 4, 2, 3}, 0.75), 4.0);
    EXPECT_DOUBLE_EQ(bench::quantile({4, 3, 2, 1}, 0.25), 1.75);
    EXPECT_DOUBLE_EQ(bench::quantile({4, 3, 2, 1}, 0.75), 3.25);
    EXPECT_DOUBLE_EQ(bench::median({4, 3, 2, 1}), 2.5);
    EXPECT_DOUBLE_EQ(bench::median({5, 1, 3}), 3.0);
    EXPECT_DOUBLE_EQ(bench::quantile({7}, 0.75), 7.0);
    EXPECT_DOUBLE_EQ(bench::quantile({}, 0.5), 0.0);
    const std::vector<double> steadyButOneSlow = {10, 10, 10, 11, 11, 11, 11, 12, 12, 12, 12, 13, 13, 13, 30};
    EXPECT_LE(bench::quantile(steadyButOneSlow, 0.75) - bench::quantile(steadyButOneSlow, 0.25), 2.0);
}

// Binomial tails worked out by hand: all of n pairs on one side has the chance 2 / 2^n; 12 or
// more of 15 on one side 2 (C(15,12) + C(15,13) + C(15,14) + C(15,15)) / 2^15 = 1152 / 32768.
TEST(SignTest, TwoSidedBinomialTails) {
    EXPECT_DOUBLE_EQ(signTestP(0, 0), 1.0);
    EXPECT_NEAR(signTestP(5, 0), 2.0 / 32.0, 1e-12);
    EXPECT_NEAR(signTestP(0, 6), 2.0 / 64.0, 1e-12);
    EXPECT_NEAR(signTestP(12, 3), 1152.0 / 32768.0, 1e-12);
    EXPECT_NEAR(signTestP(3, 12), 1152.0 / 32768.0, 1e-12);
    EXPECT_NEAR(signTestP(11, 4), 2.0 * (1365.0 + 455.0 + 105.0 + 15.0 + 1.0) / 32768.0, 1e-12);
    EXPECT_DOUBLE_EQ(signTestP(3, 3), 1.0);  // the two tails overlap: capped at 1
}

// Five pairs that all lean one way happen by chance one time in 16: not measured; six, one in 32:
// measured. Ratios of 1 count for neither side; pairs that all differ by 2x or more are measured
// at once (a render timed once, many times the default's); a mix of both sides is not.
TEST(SignTest, WhenTheStudyCallsADifferenceMeasured) {
    EXPECT_FALSE(differenceMeasured({}));
    EXPECT_FALSE(differenceMeasured({1.10, 1.20, 1.05, 1.30, 1.15}));
    EXPECT_TRUE(differenceMeasured({1.10, 1.20, 1.05, 1.30, 1.15, 1.02}));
    EXPECT_FALSE(differenceMeasured({1.10, 1.20, 1.05, 1.30, 1.15, 1.0}));
    EXPECT_TRUE(differenceMeasured({0.8, 0.9, 0.7, 0.95, 0.85, 0.9}));
    EXPECT_FALSE(differenceMeasured({0.9, 1.1, 1.2, 0.95, 1.05, 1.02}));
    EXPECT_TRUE(differenceMeasured({26.7}));
    EXPECT_TRUE(differenceMeasured({0.4, 0.45}));
    EXPECT_FALSE(differenceMeasured({1.9}));
    EXPECT_FALSE(differenceMeasured({2.5, 1.5}));
    // 12 of 15 on one side: p = 0.035; 11 of 15: p = 0.118.
    std::vector<double> ratios(12, 1.01);
    ratios.insert(ratios.end(), 3, 0.99);
    EXPECT_TRUE(differenceMeasured(ratios));
    ratios[0] = 0.99;
    EXPECT_FALSE(differenceMeasured(ratios));
    EXPECT_EQ(kMinPairsToMeasure, 6);
    EXPECT_GE(signTestP(kMinPairsToMeasure - 1, 0), kSignificance);
    EXPECT_LT(signTestP(kMinPairsToMeasure, 0), kSignificance);
}

// The study's rule for how often to render a setting: renders that fill about 1.2 s, at least as
// many as asked and at most 15; one for a render over 3 s or for --runs 1; and settings paired
// with the default at least the 6 pairs the sign test needs (all 6 on one side: p = 1/32).
TEST(RunCount, EnoughRendersToTimeAndEnoughPairsToMeasure) {
    EXPECT_EQ(runsFor(0.1, 3, false), 12);   // 12 x 0.1 s fill 1.2 s
    EXPECT_EQ(runsFor(0.25, 3, false), 5);   // 4.8, rounded up
    EXPECT_EQ(runsFor(0.5, 3, false), 3);    // 2.4 renders would do; never fewer than asked
    EXPECT_EQ(runsFor(0.5, 3, true), 6);     // paired: as many as the sign test needs
    EXPECT_EQ(runsFor(0.1, 3, true), 12);    // already more than 6
    EXPECT_EQ(runsFor(0.001, 3, false), 15);  // capped
    EXPECT_EQ(runsFor(0.0, 3, true), 15);    // a zero time does not divide by zero
    EXPECT_EQ(runsFor(0.1, 20, false), 20);  // asked for more than the cap: the cap gives way
    EXPECT_EQ(runsFor(2.9, 3, true), 6);
    EXPECT_EQ(runsFor(3.1, 3, true), 1);     // long: timed once, judged by the 2x rule
    EXPECT_EQ(runsFor(0.1, 1, true), 1);     // --runs 1: a quick look
}

std::string read(const fs::path& path) {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// The cells of the report's table row that starts with `label`.
std::vector<std::string> rowCells(const std::string& report, const std::string& label) {
    std::istringstream lines(report);
    for (std::string line; std::getline(lines, line);) {
        if (line.rfind("| " + label + " |", 0) != 0 && line.rfind("| " + label + " [front] |", 0) != 0) continue;
        std::vector<std::string> cells;
        std::istringstream row(line.substr(2));
        for (std::string cell; std::getline(row, cell, '|');) cells.push_back(cell.substr(1, cell.size() - 2));
        return cells;
    }
    return {};
}

TEST(Study, QuickRunWritesTheReportItsHeatMapsAndPlots) {
    const fs::path out = fs::temp_directory_path() / ("vitrum-study-test-" + std::to_string(::getpid()));
    fs::remove_all(out);
    const std::string command = std::string(VITRUM_STUDY_BINARY) + " " + out.string() +
                                " --quick --runs 1 --size 40x30 scenes/diamond.json 2>&1";
    ASSERT_EQ(std::system(command.c_str()), 0) << command;
    const std::string report = read(out / "accuracy-vs-time.md");
    ASSERT_FALSE(report.empty());
    EXPECT_NE(report.find("## diamond"), std::string::npos);
    // Every linked heat map and plot exists; nothing partial is left.
    const std::regex link(R"(\((study/[^)]+\.(png|svg))\))");
    int links = 0;
    for (auto it = std::sregex_iterator(report.begin(), report.end(), link); it != std::sregex_iterator(); ++it, ++links)
        EXPECT_TRUE(fs::exists(out / (*it)[1].str())) << (*it)[1].str();
    EXPECT_GE(links, 12);  // the plot, two truths, a heat map per setting
    EXPECT_FALSE(fs::exists(out / "study.partial"));
    EXPECT_NE(read(out / "study" / "diamond.svg").find("Pareto front"), std::string::npos);

    // Columns: setting, backend, time, vs default, compile, rays, Mrays/s, RMSE, PSNR, max, ...
    const auto rmse = [&](const std::string& label) {
        const std::vector<std::string> cells = rowCells(report, label);
        EXPECT_GT(cells.size(), 8u) << label;
        return cells.size() > 8 ? std::stod(cells[7]) : 1.0;
    };
    // The GPU in float with the truth's own settings is the truth up to float rounding, which on
    // this TIR-heavy diamond is 2e-4 RMSE at 128x96 (the study's figure).
    EXPECT_LT(rmse("GPU, truth settings"), 2e-3);
    // At IOR 2.42 Schlick is measurably wrong: at least twice float's rounding, and worse than it.
    EXPECT_GT(rmse("GPU, truth settings, Schlick"), 2.0 * rmse("GPU, truth settings"));
    // Depth 1 sees no reflection or refraction at all: far worse than depth 10.
    EXPECT_GT(rmse("depth 1"), 10.0 * rmse("**depth 10 (default)**"));
    fs::remove_all(out);
}

}  // namespace
}  // namespace vitrum::study
