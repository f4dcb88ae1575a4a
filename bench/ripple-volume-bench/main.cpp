// ripple-volume-bench: what volumes and iso-surfaces cost. A Marschner-Lobb field (Marschner & Lobb 1994,
// alpha 0.25, f_M 6) quantised to 8 bits on an N^3 grid (default 256^3, as a uint8 file would give it) is
// rendered four ways under a sun and a sky: as a thin scattering shell around the value 0.5 (the demo's
// transfer function), as a smooth medium (opacity rising with the value), as a stiff medium (extinction
// from 1e-6 to 1e6 per unit over the values), and as the iso-surface at 0.5.
// Per case it prints the scene build (the majorant grid for volumes, the BLAS over crossed cells for the
// iso-surface), bytes per voxel on the GPU, the time of a 512^2 16-spp render (one sample per frame, as
// ripple-render renders), free-flight samples (tentative collisions of delta tracking) per CPU-second, the
// null/real collision ratio, the GPU time per frame of the main stages and whether the volume has
// macrocells deep enough to be crossed cell by cell (core/scene/VolumeMajorants.h); --json writes the
// same. --case runs only the cases whose name holds the given text. Core only: no ANARI, no files.
// The case "tetrahedra, smooth" is the same field on an unstructured mesh of about as many tetrahedra as
// the grid has voxels (the grid's nodes at 1 / cbrt(6) of its resolution, each cell cut into six), drawn like
// "volume, smooth": its bytes are per tetrahedron, and it also prints what one of 2 ranks holds of the mesh
// (apps/scene/MeshPartition.h) against 1 rank. Up to --dims 128 (2.1M tetrahedra).
// The cases "sparse 10%, dense grid" and "sparse 10%, nanovdb" draw the field kept only inside a sphere holding
// a tenth of the box (0 outside), as a structuredRegular grid of every voxel and as a NanoVDB grid of the
// voxels inside (NanoVDB's own GridBuilder); the NanoVDB case also prints its render time and device bytes
// over the dense grid's.
#include "bench/ripple-bench/Timing.h"
#include "core/render/PathTracer.h"
#include "core/scene/Scene.h"
#include "core/scene/NanoVdbGrid.h"
#include "core/scene/UnstructuredGrid.h"
#include "apps/scene/MeshPartition.h"
#include "core/vk/Context.h"
#include "io/FileWrite.h"

#include <nanovdb/util/GridBuilder.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

using namespace ripple;

namespace {

float marschnerLobb(const glm::vec3& p) {
    const float alpha = 0.25f, frequency = 6.0f, pi = 3.14159265f;
    const float r = std::sqrt(p.x * p.x + p.y * p.y);
    const float rho = std::cos(2.0f * pi * frequency * std::cos(pi * r / 2.0f));
    return (1.0f - std::sin(pi * p.z / 2.0f) + alpha * (1.0f + rho)) / (2.0f * (1.0f + alpha));
}

// The field on n^3 samples over [-1, 1]^3, each value rounded to k / 255.
std::vector<float> quantisedField(uint32_t n) {
    std::vector<float> values;
    values.reserve(size_t(n) * n * n);
    for (uint32_t z = 0; z < n; ++z)
        for (uint32_t y = 0; y < n; ++y)
            for (uint32_t x = 0; x < n; ++x) {
                const glm::vec3 p = glm::vec3(x, y, z) / float(n - 1) * 2.0f - 1.0f;
                values.push_back(std::round(marschnerLobb(p) * 255.0f) / 255.0f);
            }
    return values;
}

struct Case {
    std::string name;
    core::SceneDescription scene;
};

core::SceneDescription litScene() {
    core::SceneDescription scene;
    core::Light sun;
    sun.kind = core::Light::Kind::Directional;
    sun.direction = glm::normalize(glm::vec3(-0.6f, -0.4f, -1.0f));
    sun.intensity = 3.0f;
    scene.lights.push_back(sun);
    return scene;
}

core::Volume volumeOf(uint32_t n, std::shared_ptr<const std::vector<float>> values, std::vector<float> opacities,
                      float unitDistance) {
    core::Volume v;
    v.dims = glm::uvec3(n);
    v.values = std::move(values);
    v.voxelIdentity = {1, 1};  // one field, never changed: a transfer-function edit reuses its voxels
    v.origin = glm::vec3(-1.0f);
    v.spacing = glm::vec3(2.0f / float(n - 1));
    v.colors = {{0.15f, 0.2f, 0.6f}, {0.2f, 0.7f, 0.8f}, {0.95f, 0.85f, 0.4f}, {0.95f, 0.35f, 0.15f}};
    v.opacities = std::move(opacities);
    v.unitDistance = unitDistance;
    return v;
}

// The field on m^3 nodes over [-1, 1]^3 (quantised as above), each of the (m - 1)^3 cells cut into six
// tetrahedra around its diagonal, in the layout of a VTK file's mesh.
apps::UnstructuredMesh tetrahedralField(uint32_t m) {
    apps::UnstructuredMesh mesh;
    const auto at = [m](uint32_t i, uint32_t j, uint32_t k) { return (k * m + j) * m + i; };
    for (uint32_t k = 0; k < m; ++k)
        for (uint32_t j = 0; j < m; ++j)
            for (uint32_t i = 0; i < m; ++i) {
                const glm::vec3 p = glm::vec3(i, j, k) / float(m - 1) * 2.0f - 1.0f;
                mesh.positions.push_back(p);
                mesh.values.push_back(std::round(marschnerLobb(p) * 255.0f) / 255.0f);
            }
    for (uint32_t k = 0; k + 1 < m; ++k)
        for (uint32_t j = 0; j + 1 < m; ++j)
            for (uint32_t i = 0; i + 1 < m; ++i) {
                const uint32_t h[8] = {at(i, j, k),     at(i + 1, j, k),     at(i + 1, j + 1, k),     at(i, j + 1, k),
                                       at(i, j, k + 1), at(i + 1, j, k + 1), at(i + 1, j + 1, k + 1), at(i, j + 1, k + 1)};
                for (const auto& t : {std::array{0, 1, 2, 6}, std::array{0, 2, 3, 6}, std::array{0, 3, 7, 6},
                                      std::array{0, 7, 4, 6}, std::array{0, 4, 5, 6}, std::array{0, 5, 1, 6}}) {
                    mesh.cellIndex.push_back(uint32_t(mesh.index.size()));
                    mesh.cellType.push_back(10);
                    for (int c : t) mesh.index.push_back(h[c]);
                }
            }
    return mesh;
}

std::shared_ptr<const core::UnstructuredGrid> prepared(const apps::UnstructuredMesh& mesh) {
    core::UnstructuredCells cells;
    cells.positions = mesh.positions;
    cells.values = mesh.values;
    cells.cellCentered = mesh.cellCentered;
    cells.index = mesh.index;
    cells.cellIndex = mesh.cellIndex;
    cells.cellType = mesh.cellType;
    return core::prepareUnstructuredGrid(cells);
}

std::vector<Case> cases(uint32_t n) {
    const auto values = std::make_shared<const std::vector<float>>(quantisedField(n));
    std::vector<Case> out;
    {
        core::SceneDescription scene = litScene();
        std::vector<float> shell(21, 0.0f);
        shell[10] = 0.8f;
        scene.volumes.push_back(volumeOf(n, values, shell, 0.01f));
        out.push_back({"volume, thin shell", std::move(scene)});
    }
    {
        core::SceneDescription scene = litScene();
        scene.volumes.push_back(volumeOf(n, values, {0.0f, 0.05f, 0.2f, 0.5f}, 0.05f));
        out.push_back({"volume, smooth", std::move(scene)});
    }
    if (n <= 128) {
        core::SceneDescription scene = litScene();
        const apps::UnstructuredMesh mesh = tetrahedralField(uint32_t(std::lround(double(n) / std::cbrt(6.0))) + 1);
        core::Volume v = volumeOf(n, values, {0.0f, 0.05f, 0.2f, 0.5f}, 0.05f);
        v.values.reset();
        v.unstructured = prepared(mesh);
        scene.volumes.push_back(std::move(v));
        out.push_back({"tetrahedra, smooth", std::move(scene)});
    }
    {
        // Sparse: the field inside the sphere of radius 0.576 (a tenth of [-1, 1]^3), 0 outside; as a dense grid
        // and as a NanoVDB grid of the voxels inside, with the same placement (voxel i at -1 + i * spacing).
        const float radius = 0.576f, spacing = 2.0f / float(n - 1);
        auto masked = std::make_shared<std::vector<float>>(*values);
        nanovdb::GridBuilder<float> builder(0.0f);
        auto voxels = builder.getAccessor();
        for (uint32_t z = 0; z < n; ++z)
            for (uint32_t y = 0; y < n; ++y)
                for (uint32_t x = 0; x < n; ++x) {
                    const glm::vec3 p = glm::vec3(x, y, z) * spacing - 1.0f;
                    float& v = (*masked)[(size_t(z) * n + y) * n + x];
                    if (glm::length(p) <= radius) voxels.setValue(nanovdb::Coord(int(x), int(y), int(z)), v);
                    else v = 0.0f;
                }
        core::SceneDescription dense = litScene();
        dense.volumes.push_back(volumeOf(n, masked, {0.0f, 0.05f, 0.2f, 0.5f}, 0.05f));
        const auto handle = builder.getHandle(double(spacing), nanovdb::Vec3d(-1.0));
        core::SceneDescription sparse = litScene();
        core::Volume v = volumeOf(n, masked, {0.0f, 0.05f, 0.2f, 0.5f}, 0.05f);
        v.values.reset();
        v.nanovdb = core::prepareNanoVdbGrid(std::span<const uint8_t>(handle.data(), handle.size()));
        sparse.volumes.push_back(std::move(v));
        out.push_back({"sparse 10%, dense grid", std::move(dense)});
        out.push_back({"sparse 10%, nanovdb", std::move(sparse)});
    }
    {
        // Stiff: extinction from 1e-6 to 1e6 per unit, log-spaced over the value range (the opacity cap
        // 0.999999 over unitDistance 13.8e-6 is 1e6 per unit).
        core::SceneDescription scene = litScene();
        const float unitDistance = float(-std::log(1e-6) / 1e6);
        std::vector<float> stiff(256);
        for (size_t e = 0; e < stiff.size(); ++e) {
            const double extinction = std::pow(10.0, -6.0 + 12.0 * double(e) / double(stiff.size() - 1));
            stiff[e] = float(-std::expm1(-extinction * unitDistance));
        }
        scene.volumes.push_back(volumeOf(n, values, stiff, unitDistance));
        out.push_back({"volume, stiff", std::move(scene)});
    }
    {
        core::SceneDescription scene = litScene();
        core::IsosurfaceSet iso;
        iso.dims = glm::uvec3(n);
        iso.values = *values;
        iso.origin = glm::vec3(-1.0f);
        iso.spacing = glm::vec3(2.0f / float(n - 1));
        iso.isovalues = {0.5f};
        scene.isosurfaceSets.push_back(std::move(iso));
        core::Material gold;
        gold.kind = core::Material::Kind::PhysicallyBased;
        gold.baseColor = {1.0f, 0.78f, 0.34f};
        gold.roughness = 0.3f;
        scene.materials.push_back(gold);
        core::InstanceDescription instance;
        instance.geometry = {core::GeometryKind::Isosurfaces, 0};
        scene.instances.push_back(instance);
        out.push_back({"isosurface 0.5", std::move(scene)});
    }
    return out;
}

}  // namespace

int main(int argc, char** argv) {
    uint32_t n = 256, size = 512, spp = 16;
    std::string jsonFile, only;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--dims" && i + 1 < argc) n = uint32_t(std::atoi(argv[++i]));
        else if (arg == "--size" && i + 1 < argc) size = uint32_t(std::atoi(argv[++i]));
        else if (arg == "--spp" && i + 1 < argc) spp = uint32_t(std::atoi(argv[++i]));
        else if (arg == "--json" && i + 1 < argc) jsonFile = argv[++i];
        else if (arg == "--case" && i + 1 < argc) only = argv[++i];
        else {
            std::fprintf(stderr, "usage: ripple-volume-bench [--dims N (256)] [--size N (512)] [--spp N (16)] [--json FILE]\n"
                                 "                           [--case TEXT (only the cases whose name holds it)]\n");
            return arg == "--help" ? 0 : 2;
        }
    }
    if (n < 2 || n > 1024 || size < 1 || size > 8192 || spp < 1) {
        std::fprintf(stderr, "ripple-volume-bench: --dims must be 2..1024, --size 1..8192, --spp at least 1\n");
        return 2;
    }
    try {
        vk::Context context;
        std::printf("ripple-volume-bench: Marschner-Lobb %u^3 (8-bit values), %ux%u, %u spp (frames of 1), %s\n", n,
                    size, size, spp, context.deviceName().c_str());
        std::printf("%-20s %9s %9s %9s %9s %12s %9s\n", "case", "build s", "B/voxel", "render s", "first s",
                    "Mfree/CPU-s", "null/real");
        nlohmann::json results = nlohmann::json::array();
        core::Camera camera;
        camera.position = {0.0f, -3.2f, 2.2f};
        camera.direction = glm::normalize(-camera.position);
        camera.up = {0.0f, 0.0f, 1.0f};
        camera.fovy = 0.75f;
        core::RenderSettings settings;
        settings.ambientRadiance = 0.3f;
        settings.background = {0.55f, 0.65f, 0.8f, 1.0f};
        settings.maxPathLength = 5;
        settings.pixelSamples = 1;
        for (const Case& c : cases(n)) {
            if (c.name.find(only) == std::string::npos) continue;
            double buildSeconds = bench::wallSeconds();
            const core::Scene scene(context, c.scene);
            buildSeconds = bench::wallSeconds() - buildSeconds;
            const double majorantSeconds = scene.report().volumeMajorantSeconds;  // on the device, within the build
            // Per voxel, or per tetrahedron of a mesh (its words, BVH included, and the tables and majorants).
            const core::Volume* mesh = !c.scene.volumes.empty() && c.scene.volumes[0].unstructured ? &c.scene.volumes[0] : nullptr;
            const double voxels = mesh ? double(mesh->unstructured->cellsKept) : double(n) * n * n;
            const double bytesPerVoxel = double(scene.report().gpuBytes) / voxels;
            double halfShare = 0.0;     // one of 2 ranks' mesh bytes over 1 rank's
            double prepareSeconds = 0.0;  // checking and packing the mesh on the host (prepareUnstructuredGrid)
            if (mesh) {
                const apps::UnstructuredMesh whole = tetrahedralField(uint32_t(std::lround(double(n) / std::cbrt(6.0))) + 1);
                prepareSeconds = bench::wallSeconds();
                prepared(whole);
                prepareSeconds = bench::wallSeconds() - prepareSeconds;
                halfShare = double(prepared(apps::meshPart(whole, 0, 2))->words.size()) / double(mesh->unstructured->words.size());
                std::printf("  %.0f tetrahedra (macrocells %ux%ux%u, BVH depth %u), packed in %.2f s; one of 2 ranks holds %.3f of the "
                            "mesh's bytes\n",
                            voxels, mesh->unstructured->macrocells.x, mesh->unstructured->macrocells.y,
                            mesh->unstructured->macrocells.z, mesh->unstructured->bvhDepth, prepareSeconds, halfShare);
            }
            core::PathTracer tracer(context);
            tracer.resize({size, size}, false);
            double first = bench::wallSeconds();
            (void)tracer.render(scene, camera, settings);  // builds the pipelines too
            first = bench::wallSeconds() - first;
            core::FrameStats total;  // of the frames timed on the CPU clock below
            const double cpu0 = bench::processCpuSeconds(), wall0 = bench::wallSeconds();
            for (uint32_t s = 1; s < std::max(spp, 2u); ++s) {  // at least one frame after the first
                const core::FrameStats f = tracer.render(scene, camera, settings);
                total.realCollisions += f.realCollisions;
                total.nullCollisions += f.nullCollisions;
                total.flaggedRays += f.flaggedRays;
                total.parkedMarches += f.parkedMarches;
                for (size_t i = 0; i < core::kStageCount; ++i) total.stageSeconds[i] += f.stageSeconds[i];
            }
            const double cpu = bench::processCpuSeconds() - cpu0, wall = bench::wallSeconds() - wall0;
            const double freeFlight = double(total.realCollisions + total.nullCollisions);
            const double perCpu = cpu > 0.0 ? freeFlight / cpu / 1e6 : 0.0;
            const double ratio = total.realCollisions > 0 ? double(total.nullCollisions) / double(total.realCollisions) : 0.0;
            std::printf("%-20s %9.2f %9.2f %9.2f %9.2f %12.2f %9.2f\n", c.name.c_str(), buildSeconds, bytesPerVoxel,
                        first + wall, first, perCpu, ratio);
            // GPU time per frame of the stages that take at least 5% of it, longest first.
            const size_t frames = std::max(spp, 2u) - 1;
            double frameSeconds = 0.0;
            for (double seconds : total.stageSeconds) frameSeconds += seconds / double(frames);
            std::vector<size_t> order(core::kStageCount);
            for (size_t i = 0; i < order.size(); ++i) order[i] = i;
            std::sort(order.begin(), order.end(),
                      [&](size_t a, size_t b) { return total.stageSeconds[a] > total.stageSeconds[b]; });
            std::printf("  GPU ms per frame %.1f:", frameSeconds * 1e3);
            nlohmann::json stageMilliseconds;
            for (size_t i : order) {
                const double ms = total.stageSeconds[i] / double(frames) * 1e3;
                stageMilliseconds[core::stageName(core::Stage(i))] = ms;
                if (ms >= 0.05 * frameSeconds * 1e3) std::printf(" %s %.1f", core::stageName(core::Stage(i)), ms);
            }
            std::printf("\n");
            const bool cellByCell = scene.report().volumesCellByCell > 0;
            if (!c.scene.volumes.empty())
                std::printf("  macrocells crossed cell by cell where deep enough: %s\n", cellByCell ? "yes" : "no (none is)");
            if (total.parkedMarches > 0)
                std::printf("  %llu marches spent a dispatch's step budget and were resumed\n",
                            (unsigned long long)total.parkedMarches);
            if (total.flaggedRays > 0)
                std::printf("  warning: %llu rays ran out of their step budget\n", (unsigned long long)total.flaggedRays);
            // A transfer-function edit (every opacity halved), as a viewer's panel makes it: the scene rebuilt
            // from the edited description with the current one as `previous`.
            double editSeconds = 0.0;
            if (!c.scene.volumes.empty()) {
                core::SceneDescription edited = c.scene;
                for (float& opacity : edited.volumes[0].opacities) opacity *= 0.5f;
                editSeconds = bench::wallSeconds();
                const core::Scene rebuilt(context, edited, {}, &scene);
                editSeconds = bench::wallSeconds() - editSeconds;
                std::printf("  transfer-function edit: scene rebuilt in %.3f s\n", editSeconds);
            }
            results.push_back({{"case", c.name}, {"dims", n}, {"size", size}, {"spp", spp},
                               {"sceneBuildSeconds", buildSeconds}, {"majorantBuildSeconds", majorantSeconds},
                               {mesh ? "gpuBytesPerTetrahedron" : "gpuBytesPerVoxel", bytesPerVoxel},
                               {"tetrahedra", mesh ? voxels : 0.0}, {"oneOfTwoRanksMeshShare", halfShare},
                               {"meshPrepareSeconds", prepareSeconds},
                               {"gpuBytes", double(scene.report().gpuBytes)},
                               {"renderSeconds", first + wall},
                               {"firstFrameSeconds", first}, {"cpuSecondsAfterFirst", cpu},
                               {"realCollisions", total.realCollisions}, {"nullCollisions", total.nullCollisions},
                               {"freeFlightPerCpuSecond", perCpu * 1e6}, {"nullPerReal", ratio},
                               {"flaggedRays", total.flaggedRays}, {"parkedMarches", total.parkedMarches},
                               {"stageMillisecondsPerFrame", stageMilliseconds},
                               {"cellByCell", cellByCell},
                               {"transferFunctionEditSeconds", editSeconds}});
        }
        // The NanoVDB grid against the dense grid of the same sparse field (the targets: at most 2x the time, at
        // most a quarter of the bytes).
        const auto find = [&](const char* name) -> const nlohmann::json* {
            for (const nlohmann::json& r : results)
                if (r["case"] == name) return &r;
            return nullptr;
        };
        nlohmann::json comparison;
        if (const nlohmann::json *dense = find("sparse 10%, dense grid"), *sparse = find("sparse 10%, nanovdb"); dense && sparse) {
            const double timeRatio = (*sparse)["renderSeconds"].get<double>() / (*dense)["renderSeconds"].get<double>();
            const double byteRatio = (*sparse)["gpuBytes"].get<double>() / (*dense)["gpuBytes"].get<double>();
            std::printf("sparse 10%%: the NanoVDB grid renders in %.2fx the dense grid's time (target <= 2) and takes %.3f of "
                        "its device bytes (target <= 0.25)\n", timeRatio, byteRatio);
            comparison = {{"nanovdbOverDenseRenderSeconds", timeRatio}, {"nanovdbOverDenseGpuBytes", byteRatio}};
        }
        if (!jsonFile.empty()) {
            const nlohmann::json report{{"benchmark", "ripple-volume-bench"}, {"device", context.deviceName()}, {"results", results},
                                        {"sparse", comparison}};
            apps::writeFileAtomically(jsonFile, report.dump(2) + "\n", "the benchmark results");
        }
    } catch (const std::exception& error) {
        std::fprintf(stderr, "ripple-volume-bench: %s\n", error.what());
        return 1;
    }
    return 0;
}
