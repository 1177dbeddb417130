#include "distributed/launch.h"

#include <sched.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>

namespace vitrum {

bool launchedByMpi() {
    for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK"})
        if (std::getenv(name)) return true;
    return false;
}

std::string deviceForLocalRank(const std::vector<DeviceDescription>& devices, int localRank) {
    std::vector<std::uint32_t> gpus;
    for (const DeviceDescription& d : devices)
        if (!d.cpu && (d.type == "discrete GPU" || d.type == "integrated GPU")) gpus.push_back(d.index);
    if (gpus.empty()) return "";
    return std::to_string(gpus[std::size_t(localRank) % gpus.size()]);
}

unsigned lavapipeThreadsPerRank(unsigned usableCpus, unsigned hostCpus, int localRanks) {
    if (usableCpus < hostCpus) return std::max(1u, usableCpus);
    return std::max(1u, hostCpus / unsigned(std::max(1, localRanks)));
}

void shareCpuThreads(int localRanks) {
    if (std::getenv("LP_NUM_THREADS")) return;
    cpu_set_t set;
    const unsigned hostCpus = unsigned(std::max(1L, sysconf(_SC_NPROCESSORS_ONLN)));
    const unsigned usable = sched_getaffinity(0, sizeof(set), &set) == 0 ? unsigned(CPU_COUNT(&set)) : hostCpus;
    setenv("LP_NUM_THREADS", std::to_string(lavapipeThreadsPerRank(usable, hostCpus, localRanks)).c_str(), 1);
}

}  // namespace vitrum
