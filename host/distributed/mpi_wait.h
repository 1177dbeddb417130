// Waiting on MPI without holding a core (mpi_job.h says why). Only for the files built with MPI.
#pragma once

#include <chrono>
#include <thread>

#include <mpi.h>

namespace vitrum {

// A poll every 100 us: a tile takes milliseconds at least, so the wait adds little to it.
inline constexpr std::chrono::microseconds kMpiPollInterval{100};

inline void waitWithoutSpinning(MPI_Request& request) {
    for (int done = 0;;) {
        MPI_Test(&request, &done, MPI_STATUS_IGNORE);
        if (done) return;
        std::this_thread::sleep_for(kMpiPollInterval);
    }
}

}  // namespace vitrum
