// Writes a NanoVDB fog sphere (NanoVDB's own createFogVolumeSphere and IO: radius 1, voxels of 0.05) to the
// file named on the command line, for the data-parallel NanoVDB renders (tests/mpi/CMakeLists.txt).
#include <nanovdb/util/IO.h>
#include <nanovdb/util/Primitives.h>

#include <cstdio>
#include <exception>

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: ripple_write_fog_sphere FILE.nvdb\n");
        return 2;
    }
    try {
        const auto handle = nanovdb::createFogVolumeSphere<float>(1.0f, nanovdb::Vec3f(0.0f), 0.05, 3.0);
        nanovdb::io::writeGrid(argv[1], handle, nanovdb::io::Codec::NONE);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "ripple_write_fog_sphere: %s\n", e.what());
        return 1;
    }
    return 0;
}
