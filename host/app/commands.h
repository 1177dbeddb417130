// The `vitrum` subcommands. Each takes the arguments after its name and returns the exit code;
// errors are thrown (InputError for the user's, anything else for vitrum's or the device's).
#pragma once

namespace vitrum {

class MpiJob;

// `job`: the MPI job mpirun started this process in, or null (distributed/mpi_job.h).
int renderCommand(int argc, char** argv, int first, MpiJob* job = nullptr);
int infoCommand(int argc, char** argv, int first);
int diffCommand(int argc, char** argv, int first);
int devicesCommand(int argc, char** argv, int first);

}  // namespace vitrum
