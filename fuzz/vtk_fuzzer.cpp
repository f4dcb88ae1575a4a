// libFuzzer target: the VTK readers (io/vtk) on the fuzz input, written to a file in a folder of this
// process's own. The first byte chooses the reader (its low two bits: image data as .vti, as legacy .vtk,
// an unstructured grid as .vtu, as legacy .vtk); the rest is the file.
//
// The readers' contract is "VolumeError on anything malformed": any other exception escapes and is a finding.
// RIPPLE_FUZZ_VERBOSE=1 prints what each input gave while reproducing a case.
#include "io/vtk/VtkImageFile.h"
#include "io/vtk/VtkUnstructuredFile.h"

#include <unistd.h>

#include <array>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace {

std::filesystem::path gFolder;
bool gVerbose = false;

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    gVerbose = std::getenv("RIPPLE_FUZZ_VERBOSE") != nullptr;
    // A folder per process: parallel fuzzing jobs must not overwrite each other's input.
    std::string pattern = (std::filesystem::temp_directory_path() / "ripple-fuzz-vtk-XXXXXX").string();
    if (!mkdtemp(pattern.data())) {
        std::perror("vtk fuzzer: mkdtemp");
        std::abort();
    }
    gFolder = pattern;
    std::atexit([] {
        std::error_code ec;
        std::filesystem::remove_all(gFolder, ec);
    });
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size == 0) return 0;
    static const std::array<const char*, 4> names = {"input.vti", "image.vtk", "input.vtu", "grid.vtk"};
    const unsigned reader = data[0] & 3u;
    const std::filesystem::path file = gFolder / names[reader];
    {
        std::ofstream out(file, std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(data + 1), std::streamsize(size - 1));
    }
    try {
        if (reader < 2) {
            const ripple::apps::VolumeData field = ripple::apps::readVtkImageVolume(file);
            if (gVerbose)
                std::fprintf(stderr, "vtk: image %ux%ux%u, values %g..%g\n", field.dims.x, field.dims.y, field.dims.z,
                             double(field.minValue), double(field.maxValue));
        } else {
            const ripple::apps::UnstructuredMesh mesh = ripple::apps::readVtkUnstructured(file);
            if (gVerbose)
                std::fprintf(stderr, "vtk: %zu points, %zu cells, field '%s'\n", mesh.positions.size(),
                             mesh.cellType.size(), mesh.fieldName.c_str());
        }
    } catch (const ripple::apps::VolumeError& e) {
        if (gVerbose) std::fprintf(stderr, "vtk: %s\n", e.what());
    }
    return 0;
}
