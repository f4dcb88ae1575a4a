// doctest entry point for the checks on the images the data-parallel apps wrote (no MPI in this program).
#define DOCTEST_CONFIG_IMPLEMENT_WITH_MAIN
#include <doctest/doctest.h>
