// Every input the fuzzer ever crashed on stays a test: each fuzz target's entry function
// (tests/fuzz/fuzz_targets.h) runs over every file of tests/fuzz/regressions/TARGET/ and of the
// seed corpus tests/fuzz/corpus/TARGET/. The only requirement is "no crash": loading succeeds or
// ends in an InputError (which the entry function catches); any other exception fails the test,
// and a crash, under `make sanitize` also any ASan or UBSan report, ends the test executable.
#include <algorithm>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "../fuzz/fuzz_targets.h"

namespace vitrum {
namespace {

namespace fs = std::filesystem;

const fs::path kFuzzDir = fs::path(VITRUM_SOURCE_DIR) / "tests/fuzz";

std::vector<fs::path> inputsOf(const fs::path& folder) {
    std::vector<fs::path> files;
    std::error_code ec;
    if (!fs::is_directory(folder, ec)) return files;
    for (const auto& entry : fs::directory_iterator(folder)) {
        const std::string name = entry.path().filename().string();
        if (entry.is_regular_file() && !name.starts_with(".") && name != "README.md") files.push_back(entry.path());
    }
    std::sort(files.begin(), files.end());
    return files;
}

std::vector<std::uint8_t> readBytes(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Runs the target over every input of `folder`; returns how many there were.
std::size_t runAll(const FuzzTarget& target, const fs::path& folder) {
    std::size_t count = 0;
    for (const fs::path& file : inputsOf(folder)) {
        SCOPED_TRACE(file.string());
        std::vector<std::uint8_t> bytes = readBytes(file);
        try {
            EXPECT_EQ(target.run(bytes.data(), bytes.size()), 0);
        } catch (const std::exception& e) {
            ADD_FAILURE() << target.name << " threw something other than an InputError: " << e.what();
        }
        ++count;
    }
    return count;
}

class FuzzRegression : public ::testing::TestWithParam<FuzzTarget> {};

TEST_P(FuzzRegression, CrashInputsStayFixed) {
    runAll(GetParam(), kFuzzDir / "regressions" / GetParam().name);
}

TEST_P(FuzzRegression, SeedCorpusLoads) {
    EXPECT_GT(runAll(GetParam(), kFuzzDir / "corpus" / GetParam().name), 0u) << "the seed corpus is missing";
}

TEST(FuzzTargets, EmptyAndTinyInputs) {
    for (const FuzzTarget& target : kFuzzTargets) {
        SCOPED_TRACE(target.name);
        for (std::string bytes : {std::string(), std::string(1, '\0'), std::string("\0\0\0", 3), std::string("PF"),
                                  std::string("#?"), std::string("{"), std::string("f 1 2 3")}) {
            EXPECT_NO_THROW(target.run(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()));
        }
    }
}

INSTANTIATE_TEST_SUITE_P(Targets, FuzzRegression, ::testing::ValuesIn(kFuzzTargets),
                         [](const ::testing::TestParamInfo<FuzzTarget>& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace vitrum
