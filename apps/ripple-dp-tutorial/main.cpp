// ripple-dp-tutorial: the smallest data-parallel ANARI program. Every MPI rank adds one quad and one light
// of its own to the world; anariRenderFrame is collective, and rank 0 receives the whole picture.
//   mpirun -np 3 ripple-dp-tutorial -o tutorial.png
// Plain MPI and the ANARI C API only: this is what any data-parallel application does.
#include "apps/scene/AnariParams.h"
#include "io/image/ImageIO.h"

#include <CLI/CLI.hpp>
#include <mpi.h>

#include <cstdio>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace ripple::apps {
namespace {

struct Options {
    std::string output = "tutorial.png";
    uint32_t width = 480;
    uint32_t height = 240;
    uint32_t spp = 8;
    // Fault demonstrations (and tests): a rank that throws, or a rank that creates one frame too many.
    std::optional<int> failOnRank;
    std::optional<int> extraFrameOnRank;
};

int errorCount = 0;

void onStatus(const void* user, ANARIDevice, ANARIObject, ANARIDataType, ANARIStatusSeverity severity,
              ANARIStatusCode, const char* message) {
    if (severity > ANARI_SEVERITY_WARNING) return;
    if (severity <= ANARI_SEVERITY_ERROR) ++errorCount;
    std::fprintf(stderr, "[ripple-dp-tutorial] rank %d: %s\n", *static_cast<const int*>(user), message);
}

// One colour per rank, so the picture shows who contributed what.
glm::vec3 rankColor(int rank) {
    const glm::vec3 palette[] = {{0.9f, 0.2f, 0.2f}, {0.2f, 0.9f, 0.2f}, {0.2f, 0.3f, 0.9f}, {0.9f, 0.8f, 0.2f}};
    return palette[rank % 4];
}

// Builds this rank's part of the world, renders it with all ranks and writes the image on rank 0. The
// objects are released on return, before the device.
void renderTogether(ANARIDevice d, const Options& options, int rank, int ranks) {
    anari::HandleList handles(d);

    // This rank's quad: a unit square at x = 1.5 * rank, standing in the XY plane and facing the camera.
    const float x = 1.5f * float(rank);
    const std::vector<glm::vec3> corners = {{x, 0, 0}, {x + 1, 0, 0}, {x + 1, 1, 0}, {x, 1, 0}};
    ANARIGeometry quad = handles.keep(anariNewGeometry(d, "quad"), "quad geometry");
    anari::setObject(d, quad, "vertex.position", ANARI_ARRAY1D, handles.keep(anari::newArray1D(d, corners), "array"));
    anariCommitParameters(d, quad);
    ANARIMaterial material = handles.keep(anariNewMaterial(d, "matte"), "material");
    anari::set(d, material, "color", rankColor(rank));
    anariCommitParameters(d, material);
    ANARISurface surface = handles.keep(anariNewSurface(d), "surface");
    anari::setObject(d, surface, "geometry", ANARI_GEOMETRY, quad);
    anari::setObject(d, surface, "material", ANARI_MATERIAL, material);
    anariCommitParameters(d, surface);

    // This rank's light, in front of its quad: the device gathers every rank's lights, so each lights all.
    ANARILight light = handles.keep(anariNewLight(d, "point"), "light");
    anari::set(d, light, "position", glm::vec3(x + 0.5f, 0.5f, 1.5f));
    anari::set(d, light, "intensity", 3.0f);
    anariCommitParameters(d, light);

    ANARIWorld world = handles.keep(anariNewWorld(d), "world");
    anari::setObject(d, world, "surface", ANARI_ARRAY1D,
                     handles.keep(anari::newArray1D(d, std::vector<ANARISurface>{surface}, ANARI_SURFACE), "array"));
    anari::setObject(d, world, "light", ANARI_ARRAY1D,
                     handles.keep(anari::newArray1D(d, std::vector<ANARILight>{light}, ANARI_LIGHT), "array"));
    anariCommitParameters(d, world);

    // World bounds with ANARI_WAIT are collective: the union of every rank's part.
    float bounds[6] = {};
    if (!anariGetProperty(d, world, "bounds", ANARI_FLOAT32_BOX3, bounds, sizeof bounds, ANARI_WAIT))
        throw std::runtime_error("the device gave no world bounds");
    if (rank == 0)
        std::printf("world bounds (union of %d ranks): (%.2f, %.2f, %.2f) - (%.2f, %.2f, %.2f)\n", ranks, bounds[0],
                    bounds[1], bounds[2], bounds[3], bounds[4], bounds[5]);

    // Camera, renderer and frame: the same on every rank. The camera looks at the whole row of quads.
    const glm::vec3 center(0.5f * (bounds[0] + bounds[3]), 0.5f * (bounds[1] + bounds[4]), 0.0f);
    const float aspect = float(options.width) / float(options.height);
    ANARICamera camera = handles.keep(anariNewCamera(d, "perspective"), "camera");
    anari::set(d, camera, "position", center + glm::vec3(0.0f, 0.0f, 0.4f * (bounds[3] - bounds[0]) + 1.2f));
    anari::set(d, camera, "direction", glm::vec3(0.0f, 0.0f, -1.0f));
    anari::set(d, camera, "up", glm::vec3(0.0f, 1.0f, 0.0f));
    anari::set(d, camera, "aspect", aspect);
    anariCommitParameters(d, camera);
    ANARIRenderer renderer = handles.keep(anariNewRenderer(d, "default"), "renderer");
    anari::set(d, renderer, "pixelSamples", int32_t(options.spp));
    anari::set(d, renderer, "background", glm::vec4(0.05f, 0.05f, 0.08f, 1.0f));
    anariCommitParameters(d, renderer);

    // Frames are global by creation order: a rank that makes an extra one renders "a different frame".
    if (options.extraFrameOnRank == rank) handles.keep(anariNewFrame(d), "frame");
    ANARIFrame frame = handles.keep(anariNewFrame(d), "frame");
    const ANARIDataType colorType = ANARI_UFIXED8_RGBA_SRGB;
    anari::set(d, frame, "size", glm::uvec2(options.width, options.height));
    anariSetParameter(d, frame, "channel.color", ANARI_DATA_TYPE, &colorType);
    anari::setObject(d, frame, "world", ANARI_WORLD, world);
    anari::setObject(d, frame, "camera", ANARI_CAMERA, camera);
    anari::setObject(d, frame, "renderer", ANARI_RENDERER, renderer);
    anariCommitParameters(d, frame);

    if (options.failOnRank == rank) throw std::runtime_error("a fault injected on rank " + std::to_string(rank));
    anariRenderFrame(d, frame);  // collective: every rank calls it
    anariFrameReady(d, frame, ANARI_WAIT);
    if (errorCount > 0) throw std::runtime_error("the device reported errors (above)");

    if (rank == 0) {  // only rank 0 holds the image; mapping elsewhere is legal but undefined
        uint32_t width = 0, height = 0;
        ANARIDataType type = ANARI_UNKNOWN;
        const void* pixels = anariMapFrame(d, frame, "channel.color", &width, &height, &type);
        if (!pixels || type != colorType) throw std::runtime_error("the device returned no color channel");
        writePngBottomUp(options.output, width, height, static_cast<const uint8_t*>(pixels));
        anariUnmapFrame(d, frame, "channel.color");
        std::printf("rank 0 of %d wrote %s\n", ranks, options.output.c_str());
    }
}

void run(const Options& options, MPI_Comm comm, int rank, int ranks) {
    ANARILibrary library = anariLoadLibrary("ripple", onStatus, &rank);
    if (!library) throw std::runtime_error("cannot load the ANARI library 'ripple'");
    ANARIDevice d = anariNewDevice(library, "default");
    if (!d) throw std::runtime_error("the ANARI library created no device");
    // Which ranks render together: the device copies the communicator (without it, MPI_COMM_WORLD).
    // An ANARI_VOID_POINTER parameter's value is the pointer itself: here the address of the MPI_Comm.
    anariSetParameter(d, d, "mpiCommunicator", ANARI_VOID_POINTER, &comm);
    anariCommitParameters(d, d);
    renderTogether(d, options, rank, ranks);
    anariRelease(d, d);  // the device's last release is collective
    anariUnloadLibrary(library);
}

}  // namespace
}  // namespace ripple::apps

int main(int argc, char** argv) {
    MPI_Init(&argc, &argv);
    int rank = 0, ranks = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &ranks);

    ripple::apps::Options options;
    CLI::App app{"ripple-dp-tutorial: every MPI rank adds one quad and one light; rank 0 writes the image "
                 "(mpirun -np 3 ripple-dp-tutorial)"};
    app.add_option("-o,--output", options.output, "PNG written by rank 0")->capture_default_str();
    app.add_option("--width", options.width, "image width")->check(CLI::Range(1u, 8192u))->capture_default_str();
    app.add_option("--height", options.height, "image height")->check(CLI::Range(1u, 8192u))->capture_default_str();
    app.add_option("--spp", options.spp, "samples per pixel")->check(CLI::Range(1u, 4096u))->capture_default_str();
    app.add_option("--fail-on-rank", options.failOnRank, "fault demonstration: this rank throws before rendering");
    app.add_option("--extra-frame-on-rank", options.extraFrameOnRank,
                   "fault demonstration: this rank creates one frame more than the others");
    int status = 0;
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        status = rank == 0 ? app.exit(e) : (e.get_exit_code() == 0 ? 0 : 1);  // one rank speaks
        MPI_Finalize();
        return status;
    }
    try {
        ripple::apps::run(options, MPI_COMM_WORLD, rank, ranks);
    } catch (const std::exception& e) {
        // The other ranks may wait for this one in a collective call: report, then end them all.
        std::fprintf(stderr, "[ripple-dp-tutorial] rank %d of %d failed: %s\n", rank, ranks, e.what());
        std::fflush(stderr);
        MPI_Abort(MPI_COMM_WORLD, 1);
    }
    MPI_Finalize();
    return status;
}
