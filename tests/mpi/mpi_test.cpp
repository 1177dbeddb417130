// `mpirun -np N vitrum render ...` as a user runs it (docs/distributed.md): the image is the one
// process's, bit for bit, however many ranks share it and whichever rank renders which tile; a
// rank that fails or is killed ends the job with a message that names it, and no image.
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <string>
#include <thread>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_support.h"
#include "image/image.h"

namespace {

namespace fs = std::filesystem;
using vitrum::testing::CommandRun;
using Mpi = vitrum::testing::CliTest;

// CI runs as root; ranks may outnumber the cores.
const std::string kMpirun = std::string(VITRUM_MPIRUN) + " --allow-run-as-root --oversubscribe";
const std::string kVitrum = VITRUM_BINARY;
// Glass (refraction, reflection, a medium), a floor and two lights: tiles of every kind of work.
const std::string kDemo = std::string(VITRUM_SOURCE_DIR) + "/scenes/demo.json";
// 160 x 120 in tiles of 32: 5 x 4 = 20 tiles, the last row and column of them whole.
const std::string kRender = "render " + kDemo + " --width 150 --height 110 --tile 32";

// Under `make sanitize` (libasan preloaded) mpirun itself runs without it: Open MPI 4.1's mpirun
// reads freed memory in its logging (found so, in orte_rml_oob_send_buffer_nb), which is not
// ours to fix. The ranks, vitrum's sanitizer build, keep ASan and UBSan but not leak detection:
// Open MPI unloads its components at MPI_Finalize, so their allocations have no module name a
// suppression could match (docs/testing.md, "Sanitizers").
CommandRun mpirun(const std::string& ranks) {
    std::string environment;
    const char* preload = std::getenv("LD_PRELOAD");
    if (preload && std::string(preload).find("libasan") != std::string::npos) {
        const char* asan = std::getenv("ASAN_OPTIONS");
        environment = "env -u LD_PRELOAD ASAN_OPTIONS=" + std::string(asan ? asan : "") + (asan ? ":" : "") +
                      "detect_leaks=0 ";
    }
    return vitrum::testing::run(environment + kMpirun + " " + ranks);
}

std::uint64_t tilesOf(const nlohmann::json& stats, int rank) {
    return stats["distributed"]["ranks"][rank]["tiles"].get<std::uint64_t>();
}

TEST_F(Mpi, DevicesSaysThisBuildSharesAnImage) {
    const CommandRun devices = vitrum::testing::vitrum("devices");
    ASSERT_EQ(devices.exitCode, 0) << devices.output;
    EXPECT_NE(devices.output.find("MPI: Open MPI"), std::string::npos) << devices.output;
    EXPECT_NE(devices.output.find("renders one image with N processes"), std::string::npos) << devices.output;
}

TEST_F(Mpi, TheImageIsTheSingleProcessOneBitForBitWithAnyNumberOfRanks) {
    const CommandRun one = vitrum::testing::vitrum(kRender + " -o " + path("one.pfm") + " --stats " + path("one.json"));
    ASSERT_EQ(one.exitCode, 0) << one.output;
    const vitrum::Image expected = vitrum::readImage(path("one.pfm"));
    const nlohmann::json single = nlohmann::json::parse(std::ifstream(path("one.json")));
    ASSERT_GT(single["rays"]["refraction"].get<int>(), 0);  // the glass is in view
    for (int n : {1, 2, 3}) {
        SCOPED_TRACE(std::to_string(n) + " ranks");
        const std::string out = path(std::to_string(n) + "-ranks.pfm");
        const std::string stats = path(std::to_string(n) + "-ranks.json");
        const CommandRun job = mpirun("-np " + std::to_string(n) + " " + kVitrum + " " + kRender + " -o " + out +
                                      " --stats " + stats);
        ASSERT_EQ(job.exitCode, 0) << job.output;
        EXPECT_EQ(vitrum::readImage(out).pixels, expected.pixels);
        const nlohmann::json s = nlohmann::json::parse(std::ifstream(stats));
        ASSERT_EQ(s["distributed"]["ranks"].size(), std::size_t(n));
        std::uint64_t tiles = 0;
        for (int r = 0; r < n; ++r) tiles += tilesOf(s, r);
        EXPECT_EQ(tiles, 20u);
        EXPECT_EQ(s["distributed"]["tiles"], 20);
        // The statistics are summed over the ranks: the same rays as one process traced.
        EXPECT_EQ(s["rays"], single["rays"]);
        // Every tile rank 0 did not render came to it as 12 bytes a pixel: at least the pixels of
        // the smallest tile, the corner one of 150 - 4 * 32 by 110 - 3 * 32 (a bound of half a
        // full tile failed once, when another rank's one tile was an edge tile).
        if (n > 1) {
            EXPECT_GE(s["distributed"]["bytes_sent"].get<std::uint64_t>(), (20 - tilesOf(s, 0)) * 22 * 14 * 12);
        }
    }
}

// Rank 1 runs with the smallest iteration budget, so that each tile takes it hundreds of dispatches
// (about 130 times rank 0's time a tile here; with a budget of 64, 4 times, less than the ranks'
// difference in start-up, and rank 1 once took every tile): it asks for fewer tiles than rank 0,
// and the image is the same.
TEST_F(Mpi, AMuchSlowerRankTakesFewerTilesAndTheImageStaysTheSame) {
    const CommandRun one = vitrum::testing::vitrum(kRender + " -o " + path("one.pfm"));
    ASSERT_EQ(one.exitCode, 0) << one.output;
    const std::string common = kRender + " -o " + path("two.pfm") + " --stats " + path("two.json");
    const CommandRun job = mpirun("-np 1 " + kVitrum + " " + common + " : -np 1 " + kVitrum + " " + common +
                                  " --iteration-budget 4");
    ASSERT_EQ(job.exitCode, 0) << job.output;
    EXPECT_EQ(vitrum::readImage(path("two.pfm")).pixels, vitrum::readImage(path("one.pfm")).pixels);
    const nlohmann::json s = nlohmann::json::parse(std::ifstream(path("two.json")));
    EXPECT_LT(tilesOf(s, 1), tilesOf(s, 0));
}

TEST_F(Mpi, ARankWhoseDeviceCannotBeOpenedEndsTheJobNamingItself) {
    const std::string common = kRender + " -o " + path("out.png");
    const CommandRun job = mpirun("-np 1 " + kVitrum + " " + common + " : -np 1 " + kVitrum + " " + common +
                                  " --device no-such-device");
    EXPECT_EQ(job.exitCode, 1) << job.output;
    EXPECT_NE(job.output.find("vitrum: rank 1 of 2 on "), std::string::npos) << job.output;
    EXPECT_NE(job.output.find("no Vulkan device has that in its name"), std::string::npos) << job.output;
    EXPECT_FALSE(fs::exists(path("out.png")));
}

// A host whose copy of the scene differs (here: rank 1 asks for another sample count) would
// render its tiles of another image.
TEST_F(Mpi, RanksThatLoadedDifferentScenesEndTheJob) {
    const std::string common = kRender + " -o " + path("out.png");
    const CommandRun job =
        mpirun("-np 1 " + kVitrum + " " + common + " : -np 1 " + kVitrum + " " + common + " --spp 2");
    EXPECT_EQ(job.exitCode, 1) << job.output;
    EXPECT_NE(job.output.find("rank 1 of 2 on "), std::string::npos) << job.output;
    EXPECT_NE(job.output.find("is not the scene rank 0 loaded"), std::string::npos) << job.output;
    EXPECT_FALSE(fs::exists(path("out.png")));
}

// The process of `rank` in a job whose command line contains `marker`, or 0.
pid_t rankProcess(const std::string& marker, int rank) {
    for (const auto& entry : fs::directory_iterator("/proc")) {
        const std::string name = entry.path().filename();
        if (name.find_first_not_of("0123456789") != std::string::npos) continue;
        std::ifstream cmdline(entry.path() / "cmdline"), environ(entry.path() / "environ");
        const std::string command((std::istreambuf_iterator<char>(cmdline)), {});
        const std::string environment((std::istreambuf_iterator<char>(environ)), {});
        if (command.rfind(kVitrum, 0) == 0 && command.find(marker) != std::string::npos &&
            environment.find(std::string("OMPI_COMM_WORLD_RANK=") + std::to_string(rank) + '\0') != std::string::npos)
            return pid_t(std::stoi(name));
    }
    return 0;
}

// The documented outcome (docs/distributed.md, "When a rank fails"): the job ends with mpirun's
// non-zero exit and its message naming the rank, its host and the signal, and no image is written.
TEST_F(Mpi, ARankKilledMidRenderEndsTheJobWithoutAnImage) {
    const std::string out = path("killed.png");
    // About ten seconds of work on two cores; rank 0 draws its progress bar once it has rendered
    // for a second, and rank 1 is killed then.
    const std::string command = kMpirun + " -np 2 " + kVitrum + " render " + kDemo +
                                " --width 1200 --height 900 --spp 16 --tile 64 -o " + out + " 2>&1";
    FILE* pipe = popen(("VITRUM_PROGRESS=1 " + command).c_str(), "r");
    ASSERT_NE(pipe, nullptr);
    std::mutex mutex;
    std::string output;
    std::thread reader([&] {
        char buffer[4096];
        // read(), not fread(): fread waits for a full buffer, and the bar's lines are short.
        while (ssize_t n = ::read(fileno(pipe), buffer, sizeof(buffer))) {
            if (n < 0) break;
            std::lock_guard lock(mutex);
            output.append(buffer, std::size_t(n));
        }
    });
    bool killed = false;
    for (auto start = std::chrono::steady_clock::now(); !killed && std::chrono::steady_clock::now() - start < std::chrono::seconds(120);) {
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
        bool rendering;
        {
            std::lock_guard lock(mutex);
            rendering = output.find("rendering [") != std::string::npos;
        }
        if (!rendering) continue;
        if (const pid_t pid = rankProcess(out, 1)) killed = ::kill(pid, SIGKILL) == 0;
    }
    reader.join();
    const int status = pclose(pipe);
    ASSERT_TRUE(killed) << output;
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_NE(WEXITSTATUS(status), 0) << output;
    EXPECT_NE(output.find("process rank 1"), std::string::npos) << output;
    EXPECT_NE(output.find("signal 9"), std::string::npos) << output;
    EXPECT_EQ(output.find("image: "), std::string::npos) << output;  // rank 0 never finished
    EXPECT_FALSE(fs::exists(out));
    for (const auto& entry : fs::directory_iterator(dir_)) ADD_FAILURE() << "left behind: " << entry.path();
}

}  // namespace
