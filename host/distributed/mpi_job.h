// The processes of one MPI job (MPI_COMM_WORLD) as vitrum uses them: which rank this one is, on
// which host, and the few collectives a distributed render needs. Every wait sleeps between polls:
// Open MPI's blocking calls spin a core, and on lavapipe the cores are the device's.
//
// Built from mpi_job.cpp where Open MPI was found, else from no_mpi_job.cpp, whose constructor
// says that this build cannot join a job (docs/distributed.md).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace vitrum {

// Is this build able to join an MPI job, and with which library: "Open MPI v4.1.4", or why not.
bool builtWithMpi();
std::string mpiLibrary();

class MpiJob {
public:
    // MPI_Init_thread: only the thread that calls it makes MPI calls (MPI_THREAD_FUNNELED).
    MpiJob(int& argc, char**& argv);
    ~MpiJob();  // MPI_Finalize
    MpiJob(const MpiJob&) = delete;
    MpiJob& operator=(const MpiJob&) = delete;

    int rank() const { return rank_; }
    int size() const { return size_; }
    int localRank() const { return localRank_; }  // among the ranks of this host
    int localSize() const { return localSize_; }
    const std::string& host() const { return host_; }
    // "rank 1 of 3 on HOST"
    std::string who() const;

    // Ends every rank of the job with `exitCode` (MPI_Abort): mpirun then exits with it.
    [[noreturn]] void abort(int exitCode);

    // The smallest of every rank's `value`, on every rank.
    std::uint32_t smallest(std::uint32_t value);
    // Every rank's `value`, by rank, on every rank.
    std::vector<std::uint64_t> allGather(std::uint64_t value);
    // Every rank's `bytes` (of one size on all ranks), by rank, on rank 0; empty elsewhere.
    std::vector<std::vector<char>> gatherToRoot(const std::vector<char>& bytes);
    // Each rank's host, by rank, on every rank.
    std::vector<std::string> hosts();

private:
    int rank_ = 0, size_ = 1, localRank_ = 0, localSize_ = 1;
    std::string host_;
};

}  // namespace vitrum
