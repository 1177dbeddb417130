// vitrum: a ray tracer for glass and other dielectrics on Vulkan compute (and its CPU reference).
#include <cstring>
#include <exception>
#include <iostream>
#include <new>
#include <string>

#include "app/commands.h"
#include "common/error.h"
#include "gpu/vulkan_error.h"

namespace {

const char* kUsage = R"(vitrum: ray tracing of glass, water and plastic on Vulkan compute

usage: vitrum <command> [options]

commands:
  render SCENE -o OUT   render a scene (.json or .obj) to PNG, PFM, HDR or OpenEXR
  info SCENE            triangles, materials, lights and BVH statistics of a scene
  diff A B              compare two images (RMSE, PSNR, error shares), optionally write a heat map
  devices               list the Vulkan devices

'vitrum <command> --help' describes each command's options.
Exit codes: 0 success, 1 bad input, 2 Vulkan failure, 3 internal error.
)";

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2 || !std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h") || !std::strcmp(argv[1], "help")) {
        std::cout << kUsage;
        return argc < 2 ? 1 : 0;
    }
    std::string command = argv[1];
    try {
        if (command == "render") return vitrum::renderCommand(argc, argv, 2);
        if (command == "info") return vitrum::infoCommand(argc, argv, 2);
        if (command == "diff") return vitrum::diffCommand(argc, argv, 2);
        if (command == "devices") return vitrum::devicesCommand(argc, argv, 2);
        std::cerr << "vitrum: unknown command \"" << command << "\"\n\n" << kUsage;
        return 1;
    } catch (const vitrum::InputError& e) {
        std::cerr << "vitrum: error: " << e.what() << "\n";
        return 1;
    } catch (const std::bad_alloc&) {
        // The input's size, not a bug: the command line names the input (loadScene says which
        // scene where loading it ran out).
        std::cerr << "vitrum: error: not enough memory for";
        for (int i = 1; i < argc; ++i) std::cerr << " " << argv[i];
        std::cerr << "\n";
        return 1;
    } catch (const vitrum::VulkanError& e) {
        std::cerr << "vitrum: Vulkan error: " << e.what() << "\n";
        return 2;
    } catch (const std::exception& e) {
        std::cerr << "vitrum: internal error: " << e.what() << "\n";
        return 3;
    }
}
