// vitrum: a ray tracer for glass and other dielectrics on Vulkan compute (and its CPU reference).
#include <cstdio>
#include <cstring>
#include <exception>
#include <iostream>
#include <new>
#include <optional>
#include <string>

#include "app/commands.h"
#include "common/error.h"
#include "distributed/launch.h"
#include "distributed/mpi_job.h"
#include "gpu/vulkan_error.h"

namespace {

const char* kUsage = R"(vitrum: ray tracing of glass, water and plastic on Vulkan compute

usage: vitrum <command> [options]

commands:
  render SCENE -o OUT   render a scene (.json, .obj, .gltf or .glb) to PNG, PFM, HDR or OpenEXR
  info SCENE            triangles, materials, lights and BVH statistics of a scene
  diff A B              compare two images (RMSE, PSNR, error shares), optionally write a heat map
  devices               list the Vulkan devices

'vitrum <command> --help' describes each command's options.
Exit codes: 0 success, 1 bad input, 2 Vulkan failure, 3 internal error.
)";

}  // namespace

namespace {

// The message of an error that ends vitrum, and its exit code. In a job of several processes the
// message names the rank and its host, and the whole job ends with the code (mpirun exits with
// it), so that no rank waits for one that failed (docs/distributed.md).
int fail(vitrum::MpiJob* job, int exitCode, const std::string& message) {
    const bool shared = job && job->size() > 1;
    // One write: mpirun forwards each rank's output as it comes, and its own notice of the abort
    // once landed between "vitrum: " and the rest of the line.
    const std::string line = "vitrum: " + (shared ? job->who() + ": " : "") + message + "\n";
    std::fwrite(line.data(), 1, line.size(), stderr);
    std::fflush(stderr);
    if (shared) job->abort(exitCode);
    return exitCode;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2 || !std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h") || !std::strcmp(argv[1], "help")) {
        std::cout << kUsage;
        return argc < 2 ? 1 : 0;
    }
    std::string command = argv[1];
    // Only a render is shared by the processes mpirun starts; the other commands run in each.
    std::optional<vitrum::MpiJob> job;
    try {
        if (command == "render") {
            if (vitrum::launchedByMpi()) job.emplace(argc, argv);
            return vitrum::renderCommand(argc, argv, 2, job ? &*job : nullptr);
        }
        if (command == "info") return vitrum::infoCommand(argc, argv, 2);
        if (command == "diff") return vitrum::diffCommand(argc, argv, 2);
        if (command == "devices") return vitrum::devicesCommand(argc, argv, 2);
        std::cerr << "vitrum: unknown command \"" << command << "\"\n\n" << kUsage;
        return 1;
    } catch (const vitrum::InputError& e) {
        return fail(job ? &*job : nullptr, 1, std::string("error: ") + e.what());
    } catch (const std::bad_alloc&) {
        // The input's size, not a bug: the command line names the input (loadScene says which
        // scene where loading it ran out).
        std::string message = "error: not enough memory for";
        for (int i = 1; i < argc; ++i) message += std::string(" ") + argv[i];
        return fail(job ? &*job : nullptr, 1, message);
    } catch (const vitrum::VulkanError& e) {
        return fail(job ? &*job : nullptr, 2, std::string("Vulkan error: ") + e.what());
    } catch (const std::exception& e) {
        return fail(job ? &*job : nullptr, 3, std::string("internal error: ") + e.what());
    }
}
