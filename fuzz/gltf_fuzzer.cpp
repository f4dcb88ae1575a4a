// libFuzzer target: the glTF/GLB importer (loadGltf) on the fuzz input, written to a file in a folder of
// this process's own (the importer reads paths; GLB or JSON is told by the magic, not the name).
//
// The importer's contract is "GltfError on anything malformed": any other exception escapes and is a finding.
// RIPPLE_FUZZ_VERBOSE=1 prints what each input gave (counts, warnings, the error) while reproducing a case.
#include "io/gltf/GltfScene.h"

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace {

std::filesystem::path gFile;
bool gVerbose = false;

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    gVerbose = std::getenv("RIPPLE_FUZZ_VERBOSE") != nullptr;
    // A folder per process: parallel fuzzing jobs must not overwrite each other's input.
    std::string pattern = (std::filesystem::temp_directory_path() / "ripple-fuzz-gltf-XXXXXX").string();
    if (!mkdtemp(pattern.data())) {
        std::perror("gltf fuzzer: mkdtemp");
        std::abort();
    }
    gFile = std::filesystem::path(pattern) / "input.gltf";
    std::atexit([] {
        std::error_code ec;
        std::filesystem::remove_all(gFile.parent_path(), ec);
    });
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    {
        std::ofstream out(gFile, std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
    }
    ripple::apps::GltfLoadOptions options;
    // Small caps keep one execution cheap; the limits' own checks are what is exercised, not their values.
    options.maxImagePixels = uint64_t(1) << 20;
    options.maxNodeDepth = 64;
    try {
        const ripple::apps::GltfScene scene = ripple::apps::loadGltf(gFile, options);
        // Touch what a renderer reads first, so results that are inconsistent show up under the sanitizers.
        const uint64_t drawn = scene.trianglesDrawn(), stored = scene.trianglesStored();
        if (gVerbose) {
            std::fprintf(stderr, "gltf: %llu triangles stored, %llu drawn, %zu materials, %zu textures, %zu cameras, "
                         "%zu lights\n", (unsigned long long)stored, (unsigned long long)drawn, scene.materials.size(),
                         scene.textures.size(), scene.cameras.size(), scene.lights.size());
            for (const std::string& w : scene.warnings) std::fprintf(stderr, "  warning: %s\n", w.c_str());
        }
    } catch (const ripple::apps::GltfError& e) {
        if (gVerbose) std::fprintf(stderr, "gltf: %s\n", e.what());
    }
    return 0;
}
