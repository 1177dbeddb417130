// Reading the files a user names (common/input_file.h): regular files only, refused at once
// otherwise, and never more than the limit read.
#include "common/input_file.h"

#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include "common/error.h"

namespace vitrum {
namespace {

namespace fs = std::filesystem;

class InputFile : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() / ("vitrum-input-file-" + std::to_string(::getpid()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }

    // The message of the InputError that reading `path` throws ("" when it throws none).
    static std::string refusal(const fs::path& path, std::uint64_t maxBytes = 1000) {
        try {
            readInputText(path, "the test file", maxBytes);
        } catch (const InputError& e) {
            return e.what();
        }
        return "";
    }

    fs::path dir_;
};

TEST_F(InputFile, ARegularFileIsReadWhole) {
    const std::string text(1000, 'x');
    std::ofstream(dir_ / "a.txt", std::ios::binary) << text;
    EXPECT_EQ(readInputText(dir_ / "a.txt", "the test file", 1000), text);
    std::ofstream(dir_ / "empty.txt", std::ios::binary);
    EXPECT_EQ(readInputText(dir_ / "empty.txt", "the test file", 1000), "");
}

TEST_F(InputFile, AFileOverTheLimitIsRefusedNamingItAndTheLimit) {
    std::ofstream(dir_ / "big.txt", std::ios::binary) << std::string(1001, 'x');
    const std::string message = refusal(dir_ / "big.txt");
    EXPECT_NE(message.find("big.txt: the test file is larger than 1000 bytes, the most vitrum reads"), std::string::npos)
        << message;
    EXPECT_EQ(refusal(dir_ / "big.txt", 1001), "");
}

// /proc files report a size of 0 and hold more: read on, and still bounded.
TEST_F(InputFile, AFileThatHoldsMoreThanItsSizeSaysIsReadToTheLimit) {
    EXPECT_EQ(refusal("/proc/self/maps", std::uint64_t(1) << 30), "");
    EXPECT_NE(refusal("/proc/self/maps", 16).find("larger than"), std::string::npos);
}

TEST_F(InputFile, WhatIsNoRegularFileIsRefusedAtOnceSayingWhatItIs) {
    ASSERT_EQ(::mkfifo((dir_ / "fifo").c_str(), 0600), 0);
    fs::create_directories(dir_ / "folder");
    EXPECT_NE(refusal(dir_ / "fifo").find("fifo: cannot read the test file: not a regular file (a FIFO)"),
              std::string::npos);
    EXPECT_NE(refusal("/dev/zero").find("/dev/zero: cannot read the test file: not a regular file (a character device)"),
              std::string::npos);
    EXPECT_NE(refusal(dir_ / "folder").find("not a regular file (a directory)"), std::string::npos);
    EXPECT_NE(refusal(dir_ / "missing").find("missing: cannot open the test file (no such file)"), std::string::npos);
    EXPECT_THROW(requireRegularFile(dir_ / "fifo", "the test file"), InputError);
    EXPECT_NO_THROW(requireRegularFile("/proc/self/maps", "the test file"));
}

}  // namespace
}  // namespace vitrum
