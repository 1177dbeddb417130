// Running the `vitrum` binary as a user does, for the command-line tests, each in a scratch
// folder of its own.
#pragma once

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <unistd.h>

namespace vitrum::testing {

struct CommandRun {
    int exitCode;        // -1 when the command died of a signal
    std::string output;  // stdout and stderr together
};

// A shell command line, its stderr with its stdout.
inline CommandRun run(const std::string& commandLine) {
    const std::string command = commandLine + " 2>&1";
    FILE* pipe = popen(command.c_str(), "r");
    if (!pipe) return {-1, "popen failed"};
    std::string output;
    std::array<char, 4096> buffer;
    while (std::size_t n = std::fread(buffer.data(), 1, buffer.size(), pipe)) output.append(buffer.data(), n);
    int status = pclose(pipe);
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, output};
}

// `environment` ("NAME=VALUE ...") goes in front of the command.
inline CommandRun vitrum(const std::string& arguments, const std::string& environment = "") {
    return run(environment + " " + std::string(VITRUM_BINARY) + " " + arguments);
}

// A fixture with a fresh folder per test.
class CliTest : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = std::filesystem::temp_directory_path() /
               ("vitrum-cli-" + std::to_string(::getpid()) + "-" +
                ::testing::UnitTest::GetInstance()->current_test_info()->test_suite_name() + "-" +
                ::testing::UnitTest::GetInstance()->current_test_info()->name());
        std::filesystem::remove_all(dir_);
        std::filesystem::create_directories(dir_);
    }
    void TearDown() override { std::filesystem::remove_all(dir_); }
    std::string path(const std::string& name) const { return (dir_ / name).string(); }
    std::string write(const std::string& name, const std::string& contents) const {
        std::ofstream(dir_ / name, std::ios::binary) << contents;
        return path(name);
    }
    std::filesystem::path dir_;
};

}  // namespace vitrum::testing
