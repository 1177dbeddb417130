// The progress line's estimate of the time left (common/progress.h): honest from the start.
#include "common/progress.h"

#include <gtest/gtest.h>

namespace vitrum {
namespace {

TEST(Progress, TheTimeLeftIsEstimatedOnlyOnceThereIsARate) {
    // Under 1% done, or under 2 s: no guess (it said "~0.0s left" for a render of hours).
    EXPECT_NE(progressLine("rendering", 0.0, 30.0).find("estimating the time left"), std::string::npos);
    EXPECT_NE(progressLine("rendering", 0.005, 600.0).find("estimating the time left"), std::string::npos);
    EXPECT_NE(progressLine("rendering", 0.5, 1.5).find("estimating the time left"), std::string::npos);
    // Then the rate so far: 10% in 20 s leaves 180 s.
    const std::string line = progressLine("rendering", 0.1, 20.0);
    EXPECT_NE(line.find(" 10.0%"), std::string::npos) << line;
    EXPECT_NE(line.find("20.0s elapsed, ~180.0s left"), std::string::npos) << line;
    EXPECT_NE(line.find("[###..."), std::string::npos) << line;
    // The estimate's part has one width whatever it says, so a shorter line leaves no tail behind.
    EXPECT_EQ(progressLine("rendering", 0.005, 10.0).size(), progressLine("rendering", 0.1, 20.0).size());
}

}  // namespace
}  // namespace vitrum
