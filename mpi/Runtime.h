// MPI's lifetime for programs that start it (tests, mini-apps, ripple-render): MPI_Init_thread on
// construction unless MPI is already running, MPI_Finalize on destruction if this object started it.
// Only in a process an MPI launcher (mpirun, mpiexec, srun with PMI or PMIx) started, seen by a variable
// the common ones give every process they start (OMPI_COMM_WORLD_SIZE, PMIX_RANK, PMI_RANK, PMI_SIZE,
// MV2_COMM_WORLD_SIZE), or with RIPPLE_MPI_INIT=1 for a launcher that sets none of them. Run on its own,
// the program is one rank without MPI, as when built without MPI: MPI's singleton start-up would buy the
// same world of one rank for about 0.3 s (Open MPI forks a helper daemon), most of a small render's time.
#pragma once

namespace ripple::mpi {

class Runtime {
public:
    Runtime(int* argc, char*** argv);
    ~Runtime();
    Runtime(const Runtime&) = delete;
    Runtime& operator=(const Runtime&) = delete;

private:
    bool started_ = false;
};

}  // namespace ripple::mpi
