// doctest entry point for the MPI suites, run under mpirun: every rank runs every test case (they are
// collective), and mpirun fails if any rank fails.
#define DOCTEST_CONFIG_IMPLEMENT
#include "mpi/Runtime.h"

#include <doctest/doctest.h>

int main(int argc, char** argv) {
    ripple::mpi::Runtime runtime(&argc, &argv);
    doctest::Context context(argc, argv);
    return context.run();
}
