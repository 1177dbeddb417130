#include "distributed/mpi_job.h"

#include <unistd.h>

#include <algorithm>
#include <cstring>
#include <stdexcept>

#include "distributed/mpi_wait.h"

namespace vitrum {

bool builtWithMpi() { return true; }

std::string mpiLibrary() {
    char version[MPI_MAX_LIBRARY_VERSION_STRING];
    int length = 0;
    MPI_Get_library_version(version, &length);
    std::string text(version, std::size_t(length));
    // "Open MPI v4.1.4, package: Debian OpenMPI, ...": its first part.
    return text.substr(0, std::min(text.find(','), text.find('\n')));
}

MpiJob::MpiJob(int& argc, char**& argv) {
    int provided = 0;
    if (MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS)
        throw std::runtime_error("MPI_Init_thread failed");
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
    MPI_Comm local;
    MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, rank_, MPI_INFO_NULL, &local);
    MPI_Comm_rank(local, &localRank_);
    MPI_Comm_size(local, &localSize_);
    MPI_Comm_free(&local);
    char name[MPI_MAX_PROCESSOR_NAME];
    int length = 0;
    MPI_Get_processor_name(name, &length);
    host_.assign(name, std::size_t(length));
}

MpiJob::~MpiJob() { MPI_Finalize(); }

std::string MpiJob::who() const {
    return "rank " + std::to_string(rank_) + " of " + std::to_string(size_) + " on " + host_;
}

void MpiJob::abort(int exitCode) {
    MPI_Abort(MPI_COMM_WORLD, exitCode);
    std::_Exit(exitCode);  // MPI_Abort does not return; should it, this rank still ends
}

std::uint32_t MpiJob::smallest(std::uint32_t value) {
    std::uint32_t result = value;
    MPI_Request request;
    MPI_Iallreduce(&value, &result, 1, MPI_UINT32_T, MPI_MIN, MPI_COMM_WORLD, &request);
    waitWithoutSpinning(request);
    return result;
}

std::vector<std::uint64_t> MpiJob::allGather(std::uint64_t value) {
    std::vector<std::uint64_t> all(static_cast<std::size_t>(size_));
    MPI_Request request;
    MPI_Iallgather(&value, 1, MPI_UINT64_T, all.data(), 1, MPI_UINT64_T, MPI_COMM_WORLD, &request);
    waitWithoutSpinning(request);
    return all;
}

std::vector<std::vector<char>> MpiJob::gatherToRoot(const std::vector<char>& bytes) {
    std::vector<char> all(rank_ == 0 ? bytes.size() * std::size_t(size_) : 0);
    MPI_Request request;
    MPI_Igather(bytes.data(), int(bytes.size()), MPI_BYTE, all.data(), int(bytes.size()), MPI_BYTE, 0,
                MPI_COMM_WORLD, &request);
    waitWithoutSpinning(request);
    std::vector<std::vector<char>> byRank;
    for (std::size_t r = 0; rank_ == 0 && r < std::size_t(size_); ++r)
        byRank.emplace_back(all.begin() + std::ptrdiff_t(r * bytes.size()),
                            all.begin() + std::ptrdiff_t((r + 1) * bytes.size()));
    return byRank;
}

std::vector<std::string> MpiJob::hosts() {
    char mine[MPI_MAX_PROCESSOR_NAME] = {};
    std::memcpy(mine, host_.data(), std::min(host_.size(), sizeof(mine) - 1));
    std::vector<char> all(sizeof(mine) * std::size_t(size_));
    MPI_Request request;
    MPI_Iallgather(mine, sizeof(mine), MPI_CHAR, all.data(), sizeof(mine), MPI_CHAR, MPI_COMM_WORLD, &request);
    waitWithoutSpinning(request);
    std::vector<std::string> names;
    for (std::size_t r = 0; r < std::size_t(size_); ++r) names.emplace_back(all.data() + r * sizeof(mine));
    return names;
}

}  // namespace vitrum
