// Whether mpirun (or another MPI launcher) started this process, read from the environment before
// MPI is initialised, and what each rank of a host takes of it: a GPU by its local rank, or a share
// of the CPU's threads for lavapipe (docs/distributed.md).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "gpu/vulkan_device.h"

namespace vitrum {

// True where the environment has a launcher's rank variable (Open MPI's mpirun and PMIx:
// OMPI_COMM_WORLD_SIZE, PMIX_RANK; MPICH-style launchers and Slurm's: PMI_RANK).
bool launchedByMpi();

// The device selector (VulkanDevice's) for local rank `localRank` of a host with `devices`: the
// GPUs (discrete or integrated) in turn by local rank where the host has any; else "" (the default
// device, lavapipe).
std::string deviceForLocalRank(const std::vector<DeviceDescription>& devices, int localRank);

// lavapipe's threads (LP_NUM_THREADS) for one of `localRanks` processes on a host whose process
// may run on `usableCpus` of `hostCpus`: all of those it may use where mpirun bound it to a part
// of the host, else an equal share of the host, at least one.
unsigned lavapipeThreadsPerRank(unsigned usableCpus, unsigned hostCpus, int localRanks);

// Sets LP_NUM_THREADS to lavapipeThreadsPerRank for this process, unless the user set it.
void shareCpuThreads(int localRanks);

}  // namespace vitrum
