// MPI's lifetime for programs that start it (tests, mini-apps, ripple-render): MPI_Init_thread on
// construction unless MPI is already running, MPI_Finalize on destruction if this object started it.
// Built without MPI, it does nothing and the program runs as one rank.
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
