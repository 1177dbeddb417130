// mpi_job.h where the build found no MPI library: this vitrum cannot join a job, and says so
// before any rank renders the whole image on its own.
#include "distributed/distributed_render.h"
#include "distributed/mpi_job.h"

#include <cstdlib>
#include <stdexcept>

#include "common/error.h"

namespace vitrum {

bool builtWithMpi() { return false; }

std::string mpiLibrary() { return "not in this build (libopenmpi-dev was not installed when it was built)"; }

MpiJob::MpiJob(int&, char**&) {
    throw InputError("this vitrum was built without MPI, so the processes mpirun started cannot share one image; "
                     "install libopenmpi-dev and rebuild (docs/distributed.md), or run vitrum without mpirun");
}

MpiJob::~MpiJob() = default;

std::string MpiJob::who() const { return ""; }
void MpiJob::abort(int exitCode) { std::exit(exitCode); }
std::uint32_t MpiJob::smallest(std::uint32_t value) { return value; }
std::vector<std::uint64_t> MpiJob::allGather(std::uint64_t value) { return {value}; }
std::vector<std::vector<char>> MpiJob::gatherToRoot(const std::vector<char>& bytes) { return {bytes}; }
std::vector<std::string> MpiJob::hosts() { return {host_}; }

// Unreachable: no MpiJob is ever made in this build.
Image renderDistributed(MpiJob&, VulkanDevice&, const Scene&, const Bvh&, const VulkanRenderOptions&, RenderStats&,
                        DistributedReport&) {
    throw std::logic_error("a distributed render in a build without MPI");
}

}  // namespace vitrum
