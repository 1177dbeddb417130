// `vitrum devices`: the Vulkan devices and how vitrum's kernel runs on each.
#include <cstdio>
#include <iostream>
#include <string>

#include "app/arguments.h"
#include "app/commands.h"
#include "common/byte_size.h"
#include "distributed/mpi_job.h"
#include "gpu/gpu_buffer.h"
#include "gpu/tile_size.h"
#include "gpu/trace_pipeline.h"
#include "gpu/vulkan_device.h"

namespace vitrum {

int devicesCommand(int argc, char** argv, int first) {
    if (wantsHelp(argc, argv, first)) {
        std::cout << "usage: vitrum devices\n\nLists the Vulkan devices, each with what decides how vitrum's kernel runs there: its\n"
                     "subgroups (which count the loop budget and sum the statistics) and its buffer limits.\n"
                     "'vitrum render --device' takes an index or part of a name. Last, whether this build\n"
                     "can render one image with the processes of an MPI job.\n";
        return 0;
    }
    for (const DeviceDescription& d : VulkanDevice::listDevices()) {
        std::printf("%u: %s (%s, Vulkan %u.%u)\n", d.index, d.name.c_str(), d.type.c_str(),
                    VK_API_VERSION_MAJOR(d.apiVersion), VK_API_VERSION_MINOR(d.apiVersion));
        if (d.apiVersion < VK_API_VERSION_1_2) {
            std::printf("   not usable: vitrum needs Vulkan 1.2\n");
            continue;
        }
        std::printf("   driver: %s, %s\n", d.driverName.c_str(), d.driverInfo.c_str());
        // What decides how trace.comp runs there (docs/gpu-design.md): the subgroups, which
        // count the loop budget and sum the statistics, and the buffer limits the scene must fit.
        const SubgroupSupport& s = d.subgroups;
        std::printf("   subgroups of %u lanes, arithmetic and ballots: %s, full subgroups: %s; statistics summed by %s\n",
                    s.size, s.arithmeticAndBallot ? "yes" : "no", s.fullSubgroups ? "yes" : "no",
                    statisticsSumsName(statisticsSumsFor(s, StatisticsSums::shuffles)));
        // The kernel path needs the device opened: the self-check runs there (gpu/subgroup_self_check.h).
        std::printf("   kernel: %s\n", VulkanDevice(std::to_string(d.index)).kernelPath().c_str());
        std::printf("   storage buffers up to %llu MiB, texel buffers up to %u texels\n",
                    static_cast<unsigned long long>(d.maxStorageBufferRange >> 20), d.maxTexelBufferElements);
        // Without it the driver may assume no value is infinite or NaN (gpu/spirv_float_semantics.h).
        std::printf("   infinities and NaNs in kernels: %s\n", d.preservesInfNan ? "kept (IEEE)" : "the driver's choice");
        // Where the kernels' buffers and the scene go (gpu/gpu_buffer.h's MemoryUse), and the tile
        // that sizes the per-pixel ones (gpu/tile_size.h).
        std::printf("   device-local memory %s, of it mappable by the host %s; tiles of %u pixels a side\n",
                    describeBytes(d.deviceLocalBytes).c_str(), describeBytes(d.mappableDeviceLocalBytes).c_str(),
                    defaultTileSize(d));
    }
    // Whether `mpirun -np N vitrum render` shares one image (docs/distributed.md).
    if (builtWithMpi())
        std::printf("MPI: %s: 'mpirun -np N vitrum render ...' renders one image with N processes\n",
                    mpiLibrary().c_str());
    else std::printf("MPI: %s\n", mpiLibrary().c_str());
    return 0;
}

}  // namespace vitrum
