// Volume-file options (see VolumeOptions.h).
#include "apps/scene/VolumeOptions.h"

#include "apps/scene/AmrPartition.h"
#include "apps/scene/MeshPartition.h"
#include "apps/scene/NanoVdbPartition.h"
#include "io/volume/OpenVdbFile.h"
#include "io/vtk/VtkImageFile.h"
#include "io/vtk/VtkUnstructuredFile.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <tuple>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <span>
#include <stdexcept>

namespace ripple::apps {

void addVolumeOptions(CLI::App& app, VolumeOptions& options) {
    app.add_option("--volume", options.volume,
                   "scalar field file: NRRD (.nrrd, or .nhdr with a raw data file; encoding raw), VTK image data (.vti, "
                   "or legacy .vtk STRUCTURED_POINTS), a VTK unstructured grid of tetrahedra, hexahedra, wedges and "
                   "pyramids (.vtu, or legacy .vtk UNSTRUCTURED_GRID), a VTK AMR set (.vthb, or .vtm of image data at "
                   "several spacings), a NanoVDB float grid (.nvdb, uncompressed, zip or blosc), an OpenVDB float grid "
                   "(.vdb) or raw (needs --dims and --type); drawn as a volume, or as isosurfaces with --isovalue, on a "
                   "floor");
    app.add_option("--field", options.field,
                   "VTK --volume: the array to draw (a point array, an unstructured grid's or AMR set's cell array; "
                   "default: the file's active scalars); OpenVDB --volume: the grid (default: the first float grid)");
    app.add_option("--field-component", options.fieldComponent,
                   "VTK --volume: of a vector array, this component (from 0) instead of the magnitude")
        ->check(CLI::Range(0, 8));
    app.add_flag("--list-fields", options.listFields, "VTK --volume: list the file's arrays and exit");
    app.add_option("--dims", options.dims, "raw --volume: samples along x, y, z as X,Y,Z or XxYxZ (x fastest)");
    app.add_option("--type", options.type, "raw --volume: uint8, int8, uint16, int16, float32 or float64 (little-endian)");
    app.add_option("--spacing", options.spacing, "raw --volume: distance between samples along x, y, z as SX,SY,SZ "
                                                 "(default 1,1,1)");
    std::string names;
    for (const std::string& n : transferFunctionNames()) names += (names.empty() ? "" : ", ") + n;
    app.add_option("--tf", options.transferFunction,
                   "--volume's colour map, over the voxels' min..max with opacity rising from 0 to --opacity: " +
                       names + " (default viridis; with --isovalue the volume is drawn only when --tf is given)");
    app.add_option("--opacity", options.opacity, "--volume: opacity at the largest value, per --unit-distance, 0 to 1 "
                                                 "(default 0.5)");
    app.add_option("--unit-distance", options.unitDistance,
                   "--volume: the distance the opacity holds for, in scene units where the field's longest side is 2, "
                   "positive (default 0.2)");
    app.add_option("--isovalue", options.isovalues,
                   "--volume: draw the field's surface at this value, coloured by the colour map; one value per "
                   "flag, repeat the flag for more (--isovalue 0.3 --isovalue 0.5)")
        ->allow_extra_args(false);
}

void printVolumeFields(const VolumeOptions& options) {
    const bool amr = isVtkAmrFile(options.volume);
    if (!isVtkImageFile(options.volume) && !isVtkUnstructuredFile(options.volume) && !amr)
        throw VolumeError("--list-fields reads VTK files (--volume FILE.vti, .vtu, .vtk, .vthb or .vtm); " + options.volume +
                          " is not one");
    const bool unstructured = isVtkUnstructuredFile(options.volume);
    if (unstructured) {
        const UnstructuredMesh mesh = readVtkUnstructured(options.volume);
        uint64_t counts[256] = {};
        for (uint8_t t : mesh.cellType) ++counts[t];
        std::printf("%zu points, %zu cells: %llu tetrahedra, %llu hexahedra, %llu wedges, %llu pyramids\n",
                    mesh.positions.size(), mesh.cellType.size(), (unsigned long long)counts[10], (unsigned long long)counts[12],
                    (unsigned long long)counts[13], (unsigned long long)counts[14]);
        for (const std::string& warning : mesh.warnings) std::printf("note: %s\n", warning.c_str());
    }
    if (amr) std::printf("the arrays of its first block:\n");
    const std::vector<VtkArrayInfo> arrays = unstructured ? listVtkUnstructuredArrays(options.volume)
                                             : amr        ? listVtkAmrArrays(options.volume)
                                                          : listVtkArrays(options.volume);
    for (const VtkArrayInfo& a : arrays)
        std::printf("%s array '%s': %u component%s of %s, %llu tuples\n", a.association.c_str(), a.name.c_str(),
                    a.components, a.components == 1 ? "" : "s", a.type.c_str(), (unsigned long long)a.tuples);
}

std::string describeVolumeOptions(const VolumeOptions& options) {
    std::string text = options.field + ";" + std::to_string(options.fieldComponent.value_or(-1)) + ";" + options.dims + ";" + options.type + ";" + options.spacing + ";" + options.transferFunction + ";" +
                       std::to_string(options.opacity.value_or(-1.0f)) + ";" +
                       std::to_string(options.unitDistance.value_or(-1.0f));
    for (float v : options.isovalues) {  // exact: the bits, not a rounded decimal
        uint32_t bits = 0;
        std::memcpy(&bits, &v, sizeof bits);
        text += ";" + std::to_string(bits);
    }
    return text;
}

void checkVolumeOptions(const VolumeOptions& options) {
    const bool rawOptions = !options.dims.empty() || !options.type.empty() || !options.spacing.empty();
    if (options.volume.empty() && (rawOptions || !options.transferFunction.empty() || options.opacity ||
                                   options.unitDistance || !options.isovalues.empty()))
        throw std::runtime_error("--dims, --type, --spacing, --tf, --opacity, --unit-distance and --isovalue "
                                 "need --volume FILE");
    if (!options.transferFunction.empty()) checkTransferFunctionName(options.transferFunction);
    if (options.opacity && !(*options.opacity >= 0.0f && *options.opacity <= 1.0f))
        throw std::runtime_error("--opacity " + std::to_string(*options.opacity) + " is not a number from 0 to 1");
    if (options.unitDistance && !(*options.unitDistance > 0.0f && std::isfinite(*options.unitDistance)))
        throw std::runtime_error("--unit-distance " + std::to_string(*options.unitDistance) +
                                 " is not a finite positive number");
    for (float v : options.isovalues)
        if (!std::isfinite(v)) throw std::runtime_error("--isovalue " + std::to_string(v) + " is not a finite number");
}

std::optional<FieldPlan> planField(const VolumeOptions& options, const mpi::Communicator& ranks, bool root,
                                   const char* program, bool quiet) {
    checkVolumeOptions(options);
    if (options.volume.empty()) return std::nullopt;
    const bool rawOptions = !options.dims.empty() || !options.type.empty() || !options.spacing.empty();
    FieldPlan plan;
    FieldSceneOptions& field = plan.scene;
    field.isovalues = options.isovalues;
    // With isovalues the volume is drawn only when --tf asks for it; without, the default map draws it.
    field.transferFunction = !options.transferFunction.empty() ? options.transferFunction
                             : options.isovalues.empty()       ? "viridis"
                                                               : "";
    field.opacity = options.opacity.value_or(field.opacity);
    field.unitDistance = options.unitDistance;
    // Under mpirun each rank reads only its z-slab (data-parallel ANARI: every rank's world holds its own
    // brick, sharing a sample plane with its neighbour); rank 0's world holds the floor and the sun.
    const VolumeSlab slab{uint32_t(ranks.rank()), uint32_t(ranks.size())};
    field.stage = root;
    std::string extension = std::filesystem::path(options.volume).extension().string();
    for (char& c : extension) c = char(std::tolower(static_cast<unsigned char>(c)));
    const bool vtkOptions = !options.field.empty() || options.fieldComponent;
    const bool unstructured = isVtkUnstructuredFile(options.volume);
    const bool amr = isVtkAmrFile(options.volume);
    if (vtkOptions && !isVtkImageFile(options.volume) && !unstructured && !amr && !isNanoVdbFile(options.volume) &&
        !isOpenVdbFile(options.volume))
        throw std::runtime_error("--volume " + options.volume + ": --field and --field-component are for VTK files");
    if ((isVtkImageFile(options.volume) || unstructured || amr) && rawOptions)
        throw std::runtime_error("--volume " + options.volume + ": --dims, --type and --spacing are for raw files; "
                                 "the VTK file gives them");
    // A rank's share of a field (a data-parallel split), its problems named with the option and the file.
    const auto rankShare = [&](const auto& split) {
        try {
            return split();
        } catch (const std::runtime_error& e) {
            throw std::runtime_error("--volume " + options.volume + ": " + e.what());
        }
    };
    const bool openvdb = isOpenVdbFile(options.volume);
    if (isNanoVdbFile(options.volume) || openvdb) {
        if (rawOptions || options.fieldComponent || (!openvdb && !options.field.empty()))
            throw std::runtime_error("--volume " + options.volume + ": --dims, --type, --spacing and --field-component are "
                                     "not for NanoVDB and OpenVDB files (--field names an OpenVDB file's grid)");
        // Every rank reads the whole grid (its box frames the view, its values span the colour map) and keeps
        // only its region's voxels. An OpenVDB grid is converted to NanoVDB as it is read.
        const NanoVdbFile whole = openvdb ? readOpenVdbFile(options.volume, options.field) : readNanoVdbFile(options.volume);
        plan.nanovdb = rankShare([&] { return nanoVdbPart(whole, slab.index, slab.count); });
        plan.data.minValue = whole.minValue;
        plan.data.maxValue = whole.maxValue;
    } else if (amr) {
        // Every rank reads the whole set (its box frames the view, its values span the colour map) and keeps
        // only its region's part of the blocks.
        const AmrData whole = readVtkAmr(options.volume, {options.field, options.fieldComponent.value_or(-1)});
        AmrPart part;
        std::tie(part.wholeLo, part.wholeHi) = amrBounds(whole);
        part.blocks = rankShare([&] { return amrPart(whole, slab.index, slab.count); });
        plan.data.minValue = whole.minValue;
        plan.data.maxValue = whole.maxValue;
        plan.amr = std::move(part);
    } else if (unstructured) {
        // Every rank reads the whole file (its box frames the view, its values span the colour map) and keeps
        // only its part of the cells.
        MeshPart mesh;
        mesh.cells = readVtkUnstructured(options.volume, {options.field, options.fieldComponent.value_or(-1)});
        if (mesh.cells.values.empty())
            throw std::runtime_error("--volume " + options.volume + ": the file has no point or cell array to draw");
        const size_t cellCount = mesh.cells.cellType.size();
        if (cellCount == 0) throw std::runtime_error("--volume " + options.volume + ": the file has no cells");
        if (cellCount < size_t(ranks.size()))
            throw std::runtime_error("--volume " + options.volume + ": " + std::to_string(cellCount) + " cells cannot be "
                                     "split over " + std::to_string(ranks.size()) + " ranks (each needs at least one)");
        mesh.wholeLo = glm::vec3(INFINITY);
        mesh.wholeHi = glm::vec3(-INFINITY);
        for (const glm::vec3& p : mesh.cells.positions) {
            mesh.wholeLo = glm::min(mesh.wholeLo, p);
            mesh.wholeHi = glm::max(mesh.wholeHi, p);
        }
        const glm::vec3 extent = mesh.wholeHi - mesh.wholeLo;
        const float longest = std::max({extent.x, extent.y, extent.z});
        if (!(longest > 0.0f) || !std::isfinite(longest) || !std::isfinite(2.0f / longest))
            throw std::runtime_error("--volume " + options.volume + ": the mesh's points span no finite, non-zero box "
                                     "(longest side " + std::to_string(longest) + ")");
        if (!quiet && root)
            for (const std::string& warning : mesh.cells.warnings)
                std::fprintf(stderr, "[%s] WARNING: %s: %s\n", program, options.volume.c_str(), warning.c_str());
        plan.data.minValue = mesh.cells.minValue;
        plan.data.maxValue = mesh.cells.maxValue;
        mesh.cells = meshPart(mesh.cells, slab.index, slab.count);
        plan.mesh = std::move(mesh);
    } else if (isVtkImageFile(options.volume)) {
        plan.data = readVtkImageVolume(options.volume, {options.field, options.fieldComponent.value_or(-1)}, slab);
    } else if (isNrrdFile(options.volume)) {
        if (rawOptions)
            throw std::runtime_error("--volume " + options.volume + ": --dims, --type and --spacing are for raw files; "
                                     "the NRRD header gives them");
        plan.data = readNrrdVolume(options.volume, slab);
    } else {
        if (options.dims.empty() || options.type.empty())
            throw std::runtime_error("--volume " + options.volume + ": a raw file needs --dims X,Y,Z and --type "
                                     "(or give an NRRD file, .nrrd or .nhdr)");
        plan.data = readRawVolume(options.volume, {options.dims, options.type, options.spacing}, slab);
    }
    if (ranks.distributed() && !plan.mesh && !plan.nanovdb && !plan.amr) {  // the colour map spans every rank's values
        float lowest = plan.data.minValue, highest = plan.data.maxValue;
        ranks.min(std::span<float>(&lowest, 1));
        ranks.max(std::span<float>(&highest, 1));
        plan.data.minValue = lowest;
        plan.data.maxValue = highest;
        field.valueRange = glm::vec2(lowest, highest);
    }
    if (!quiet && root) {
        for (float v : options.isovalues)
            if (v < plan.data.minValue || v > plan.data.maxValue)
                std::fprintf(stderr, "[%s] WARNING: --isovalue %g is outside the field's values [%g, %g]: it draws nothing\n",
                             program, double(v), double(plan.data.minValue), double(plan.data.maxValue));
        if (!field.transferFunction.empty() && plan.data.minValue == plan.data.maxValue)
            std::fprintf(stderr, "[%s] WARNING: every voxel is %g: the transfer function shows nothing\n", program,
                         double(plan.data.minValue));
    }
    return plan;
}

AnariWorld buildPlannedField(ANARIDevice device, const FieldPlan& plan, const std::vector<ANARILight>& extraLights,
                             SceneEdits* edits) {
    if (plan.mesh) return buildMeshScene(device, *plan.mesh, plan.scene, extraLights, edits);
    if (plan.nanovdb) return buildNanoVdbScene(device, *plan.nanovdb, plan.scene, extraLights, edits);
    if (plan.amr) return buildAmrScene(device, *plan.amr, plan.scene, extraLights, edits);
    return buildFieldScene(device, plan.data, plan.scene, extraLights, edits);
}

}  // namespace ripple::apps
