// libFuzzer target: the VTK readers (io/vtk) on the fuzz input, written to a file in a folder of this
// process's own. The first byte chooses the reader: with bit 2 clear, its low two bits pick image data as .vti,
// as legacy .vtk, an unstructured grid as .vtu, as legacy .vtk; with bit 2 set, an AMR set, as .vthb (bit 0)
// or .vtm, whose blocks may name block.vti beside it (a valid image of 2x2x2 cells, written once). The rest is
// the file.
//
// The readers' contract is "VolumeError on anything malformed": any other exception escapes and is a finding.
// RIPPLE_FUZZ_VERBOSE=1 prints what each input gave while reproducing a case.
#include "io/vtk/VtkAmrFile.h"
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
    std::ofstream(gFolder / "block.vti")
        << "<VTKFile type=\"ImageData\" version=\"0.1\"><ImageData WholeExtent=\"0 2 0 2 0 2\" Origin=\"0 0 0\" "
           "Spacing=\"1 1 1\"><Piece Extent=\"0 2 0 2 0 2\"><CellData><DataArray type=\"Float32\" Name=\"f\" "
           "format=\"ascii\">1 2 3 4 5 6 7 8</DataArray></CellData></Piece></ImageData></VTKFile>\n";
    std::atexit([] {
        std::error_code ec;
        std::filesystem::remove_all(gFolder, ec);
    });
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size == 0) return 0;
    static const std::array<const char*, 6> names = {"input.vti", "image.vtk", "input.vtu", "grid.vtk", "set.vtm", "set.vthb"};
    const unsigned reader = data[0] & 4u ? 4u + (data[0] & 1u) : data[0] & 3u;
    const std::filesystem::path file = gFolder / names[reader];
    {
        std::ofstream out(file, std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(data + 1), std::streamsize(size - 1));
    }
    try {
        if (reader >= 4) {
            const ripple::apps::AmrData amr = ripple::apps::readVtkAmr(file);
            if (gVerbose)
                std::fprintf(stderr, "vtk: AMR set of %zu blocks on %zu levels, %llu cells\n", amr.blocks.size(),
                             amr.cellWidth.size(), (unsigned long long)amr.cells);
        } else if (reader < 2) {
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
