// OpenVDB files, converted to NanoVDB on load (see OpenVdbFile.h).
#include "io/volume/OpenVdbFile.h"

#include "io/FileRead.h"

#include <nanovdb/util/OpenToNanoVDB.h>
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>

#include <cctype>
#include <cmath>
#include <mutex>

namespace ripple::apps {

bool isOpenVdbFile(const std::filesystem::path& file) {
    std::string extension = file.extension().string();
    for (char& c : extension) c = char(std::tolower(static_cast<unsigned char>(c)));
    return extension == ".vdb";
}

NanoVdbFile readOpenVdbFile(const std::filesystem::path& file, const std::string& gridName) {
    const auto fail = [&](const std::string& problem) { return VolumeError(file.string() + ": " + problem); };
    // Refuse what is not a regular file (a FIFO, a device) before OpenVDB opens it.
    uint64_t size = 0;
    std::string error;
    if (openRegularFile(file, false, size, error).get() < 0) throw fail(error);
    static std::once_flag initialized;
    std::call_once(initialized, [] { openvdb::initialize(); });
    openvdb::FloatGrid::Ptr grid;
    try {
        openvdb::io::File vdb(file.string());
        vdb.open(false);  // no delayed loading: the whole grid is read now
        std::string names;
        for (auto it = vdb.beginName(); it != vdb.endName(); ++it) {
            const openvdb::GridBase::Ptr base = vdb.readGrid(it.gridName());
            names += (names.empty() ? "" : ", ") + it.gridName() + " (" + base->valueType() + ")";
            if (!gridName.empty() && it.gridName() != gridName) continue;
            grid = openvdb::GridBase::grid<openvdb::FloatGrid>(base);
            if (grid || !gridName.empty()) break;
        }
        vdb.close();
        if (!grid)
            throw fail((gridName.empty() ? std::string("no float grid") : "no float grid '" + gridName + "'") + " (grids: " +
                       (names.empty() ? "none" : names) + ")");
    } catch (const openvdb::Exception& e) {
        throw fail(std::string("OpenVDB cannot read it: ") + e.what());
    }
    if (grid->activeVoxelCount() == 0) throw fail("its grid '" + grid->getName() + "' has no active voxel");
    const auto handle = nanovdb::openToNanoVDB(*grid);
    const nanovdb::NanoGrid<float>* nano = handle.grid<float>();
    if (!nano) throw fail("its grid could not be converted to NanoVDB");
    NanoVdbFile out;
    out.grid.assign(handle.data(), handle.data() + handle.size());
    out.name = grid->getName();
    const nanovdb::BBox<nanovdb::Vec3R>& box = nano->worldBBox();
    for (int k = 0; k < 3; ++k) {
        out.worldLo[k] = box.min()[k];
        out.worldHi[k] = box.max()[k];
    }
    out.minValue = nano->tree().root().minimum();
    out.maxValue = nano->tree().root().maximum();
    if (!std::isfinite(out.minValue) || !std::isfinite(out.maxValue)) throw fail("its grid's value range is not finite");
    return out;
}

}  // namespace ripple::apps
