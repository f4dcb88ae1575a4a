// Volume records, transfer-function tables and macrocell majorants (see VolumeTable.h).
#include "core/scene/VolumeTable.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <optional>

namespace ripple::core {

namespace {

// The array's value at x in [0, 1], linear between entries spread evenly over [0, 1].
template <class T>
T resampled(const std::vector<T>& values, float x) {
    if (values.size() == 1) return values[0];
    const float at = std::clamp(x, 0.0f, 1.0f) * float(values.size() - 1);
    const size_t i = std::min(size_t(at), values.size() - 2);
    const float w = at - float(i);
    return values[i] * (1.0f - w) + values[i + 1] * w;
}

// The field's problems (an unstructured mesh or a NanoVDB grid was checked when it was prepared).
std::optional<std::string> fieldProblemOf(const Volume& v) {
    if (v.unstructured || v.nanovdb || v.amr) return std::nullopt;
    const uint64_t voxels = uint64_t(v.dims.x) * v.dims.y * v.dims.z;
    if (v.dims.x == 0 || v.dims.y == 0 || v.dims.z == 0) return "a dimension is 0";
    const size_t count = v.values ? v.values->size() : 0;
    if (voxels != count)
        return "holds " + std::to_string(count) + " values for " + std::to_string(v.dims.x) + "x" +
               std::to_string(v.dims.y) + "x" + std::to_string(v.dims.z) + " voxels";
    if (voxels > (uint64_t(1) << 31)) return "has more than 2^31 voxels";
    for (size_t i = 0; i < count; ++i)
        if (!std::isfinite((*v.values)[i])) return "voxel " + std::to_string(i) + " is not finite";
    if (!glm::all(glm::greaterThan(v.spacing, glm::vec3(0.0f))) || !std::isfinite(v.spacing.x + v.spacing.y + v.spacing.z))
        return "spacing is not finite and positive";
    if (!std::isfinite(v.origin.x + v.origin.y + v.origin.z)) return "origin is not finite";
    return std::nullopt;
}

std::optional<std::string> problemOf(const Volume& v) {
    if (std::optional<std::string> problem = fieldProblemOf(v)) return problem;
    if (!std::isfinite(v.valueRange.x) || !std::isfinite(v.valueRange.y)) return "valueRange is not finite";
    // The kernels map a value to the table by multiplying with 1 / (highest - lowest): past 1e37 that
    // reciprocal is no longer a normal float (a device may flush it to 0, and every value would read entry 0).
    const double width = std::abs(double(v.valueRange.y) - double(v.valueRange.x));
    if (width > 1e37) return "valueRange is wider than 1e37 (values cannot be mapped to the transfer function in float)";
    if (width > 0.0 && width < 1e-37)
        return "valueRange is narrower than 1e-37 but not empty (values cannot be mapped to the transfer function in float)";
    if (!(v.unitDistance > 0.0f) || !std::isfinite(v.unitDistance)) return "unitDistance is not finite and positive";
    for (const glm::vec3& c : v.colors)
        if (!std::isfinite(c.x + c.y + c.z)) return "a colour is not finite";
    for (float o : v.opacities)
        if (!std::isfinite(o)) return "an opacity is not finite";
    if (!affineAndInvertible(v.transform)) return "transform is not finite, affine and invertible";
    return std::nullopt;
}

// The largest extinction the table gives over values [range.x, range.y] (0 for an empty range), as the
// kernels bound it (extinctionMax in shaders/volume.glsl): from the range-maximum table at `levelsAt`, the
// entries from below the range's first position to above its last, raised by 1e-5.
float extinctionMax(const gpu::VolumeRecord& r, size_t levelsAt, const std::vector<float>& data, glm::vec2 range) {
    if (range.y < range.x) return 0.0f;
    const float top = float(r.tableSize - 1);
    const auto position = [&](float value) {
        const float x = (value - r.valueRange.x) * r.valueRange.y;
        return (x >= 0.0f ? std::min(x, 1.0f) : 0.0f) * top;
    };
    const float p0 = position(range.x), p1 = std::max(position(range.y), p0);
    const uint32_t first = std::min(uint32_t(p0), r.tableSize - 1), last = std::min(uint32_t(std::ceil(p1)), r.tableSize - 1);
    uint32_t level = 0;
    while ((uint32_t(2) << level) <= last - first + 1) ++level;
    const size_t at = levelsAt + size_t(level) * r.tableSize;
    return std::max(data[at + first], data[at + last + 1 - (uint32_t(1) << level)]) * (1.0f + 1e-5f);
}

void storeRows(const glm::dmat4& m, gpu::vec4* rows) {
    for (int r = 0; r < 3; ++r) rows[r] = gpu::vec4(float(m[0][r]), float(m[1][r]), float(m[2][r]), float(m[3][r]));
}

}  // namespace

size_t transferTableSize(const Volume& volume) {
    return std::max<size_t>({kMinTransferEntries, volume.colors.size(), volume.opacities.size()});
}

uint32_t extinctionMaxLevels(size_t entries) {
    uint32_t levels = 1;
    while ((size_t(1) << levels) <= entries) ++levels;
    return levels;
}

glm::uvec3 macrocellsPerAxis(glm::uvec3 dims) {
    return glm::max((dims - 1u + gpu::VOLUME_MACROCELL - 1u) / gpu::VOLUME_MACROCELL, glm::uvec3(1u));
}

VolumeTable buildVolumeTable(const std::vector<Volume>& volumes) {
    VolumeTable table;
    for (size_t index = 0; index < volumes.size(); ++index) {
        const Volume& v = volumes[index];
        if (const std::optional<std::string> problem = problemOf(v)) {
            table.messages.push_back("volume " + std::to_string(index) + ": " + *problem + "; skipped");
            ++table.skipped;
            continue;
        }
        // The kernels index the one float array with 32-bit offsets: a volume that would reach past them is
        // skipped (the majorants would otherwise be written over another volume's data).
        const size_t entries = transferTableSize(v);
        const glm::uvec3 macroCells = v.unstructured ? v.unstructured->macrocells
                                      : v.nanovdb    ? v.nanovdb->macrocells
                                      : v.amr        ? v.amr->macrocells
                                                     : macrocellsPerAxis(v.dims);
        // The value ranges the host knows per macrocell (the device computes a structured grid's).
        const std::vector<glm::vec2>* hostRanges = v.unstructured ? &v.unstructured->macrocellRanges
                                                   : v.nanovdb    ? &v.nanovdb->macrocellRanges
                                                   : v.amr        ? &v.amr->macrocellRanges
                                                                  : nullptr;
        const uint64_t floatsNeeded = 4 * uint64_t(entries) + uint64_t(entries) * extinctionMaxLevels(entries) +
                                      uint64_t(macroCells.x) * macroCells.y * macroCells.z;
        if (table.data.size() + floatsNeeded > uint64_t(UINT32_MAX)) {
            table.messages.push_back("volume " + std::to_string(index) + ": the scene's volumes hold more than 2^32 floats "
                                     "with this one; skipped");
            ++table.skipped;
            continue;
        }
        gpu::VolumeRecord record{};
        // An unstructured mesh's or an AMR hierarchy's grid is a virtual one over its box, of whole macrocells; a
        // NanoVDB grid's spans its active box.
        const glm::uvec3 dims = v.nanovdb ? v.nanovdb->extent + 1u : hostRanges ? macroCells * gpu::VOLUME_MACROCELL + 1u : v.dims;
        // Object -> grid index space (voxel i at i); in double, as a mesh's box may be narrow or wide enough
        // that its spacing rounds in float.
        glm::dmat4 objectToGrid(1.0);
        if (v.unstructured) {
            const glm::dvec3 lo(v.unstructured->lo), spacing = (glm::dvec3(v.unstructured->hi) - lo) / glm::dvec3(dims - 1u);
            objectToGrid = glm::scale(glm::dmat4(1.0), 1.0 / spacing) * glm::translate(glm::dmat4(1.0), -lo);
        } else if (v.nanovdb) {
            objectToGrid = glm::translate(glm::dmat4(1.0), -glm::dvec3(v.nanovdb->base)) * glm::inverse(v.nanovdb->indexToObject);
        } else if (v.amr) {
            objectToGrid = v.amr->objectToGrid;
        } else {
            objectToGrid = glm::scale(glm::dmat4(1.0), 1.0 / glm::dvec3(v.spacing)) * glm::translate(glm::dmat4(1.0), -glm::dvec3(v.origin));
        }
        storeRows(objectToGrid * glm::inverse(glm::dmat4(v.transform)), record.worldToGrid);
        bool finiteMap = true;
        for (const gpu::vec4& row : record.worldToGrid) finiteMap = finiteMap && std::isfinite(row.x + row.y + row.z + row.w);
        if (!finiteMap) {
            table.messages.push_back("volume " + std::to_string(index) + ": its transform and spacing map the world to "
                                     "its grid beyond what a float holds; skipped");
            ++table.skipped;
            continue;
        }
        const glm::uvec3 extent = dims - 1u;
        record.gridExtent = gpu::vec4(glm::vec3(extent), 0.0f);
        record.kind = v.unstructured ? gpu::VOLUME_KIND_UNSTRUCTURED
                      : v.nanovdb    ? gpu::VOLUME_KIND_NANOVDB
                      : v.amr        ? gpu::VOLUME_KIND_AMR
                                     : gpu::VOLUME_KIND_STRUCTURED;
        const float lo = std::min(v.valueRange.x, v.valueRange.y), hi = std::max(v.valueRange.x, v.valueRange.y);
        record.valueRange = gpu::vec4(lo, hi > lo ? 1.0f / (hi - lo) : 0.0f, 0.0f, 0.0f);
        record.dimX = dims.x;
        record.dimY = dims.y;
        record.dimZ = dims.z;
        record.filterMode = v.linearFilter && !v.unstructured && !v.amr ? gpu::VOLUME_FILTER_LINEAR : gpu::VOLUME_FILTER_NEAREST;
        record.objectId = v.objectId;
        record.instanceId = v.instanceId;
        record.macroX = macroCells.x;
        record.macroY = macroCells.y;
        record.macroZ = macroCells.z;

        // Transfer-function table: albedo and extinction per entry. The kernels track extinction in float
        // (times the ray's speed, over sums of steps): past 1e36 per unit a volume is skipped rather than
        // tracked with an infinite majorant, which would never collide.
        std::vector<float> entryData;
        entryData.reserve(4 * entries);
        double largestExtinction = 0.0;
        for (size_t e = 0; e < entries; ++e) {
            const float x = float(e) / float(entries - 1);
            const glm::vec3 albedo = v.colors.empty() ? glm::vec3(1.0f) : glm::clamp(resampled(v.colors, x), 0.0f, 1.0f);
            // No opacities: opaque, capped like any other (an uncapped 1 would be an infinite extinction).
            const float opacity = std::clamp(v.opacities.empty() ? 1.0f : resampled(v.opacities, x), 0.0f, gpu::VOLUME_OPACITY_CAP);
            const float extinction = -std::log1p(-std::min(opacity, gpu::VOLUME_OPACITY_CAP)) / v.unitDistance;
            largestExtinction = std::max(largestExtinction, -std::log1p(-double(opacity)) / double(v.unitDistance));
            entryData.insert(entryData.end(), {albedo.r, albedo.g, albedo.b, extinction});
        }
        if (largestExtinction > 1e36) {
            char unitDistance[32];
            std::snprintf(unitDistance, sizeof unitDistance, "%g", double(v.unitDistance));
            table.messages.push_back("volume " + std::to_string(index) + ": its opacity over unitDistance " + unitDistance +
                                     " gives an extinction above 1e36 per unit, more than the kernels can track in "
                                     "float; skipped");
            ++table.skipped;
            continue;
        }
        record.tableSize = static_cast<uint32_t>(entries);
        record.tableOffset = static_cast<uint32_t>(table.data.size());
        table.data.insert(table.data.end(), entryData.begin(), entryData.end());
        // Its range-maximum table, right after it (level k, entry i: the largest extinction of entries
        // i .. i + 2^k - 1, clamped to the last): the tracking kernels bound the extinction over any range
        // of values with two reads.
        const size_t levelsAt = table.data.size();
        table.data.resize(levelsAt + entries * extinctionMaxLevels(entries));
        for (size_t e = 0; e < entries; ++e) table.data[levelsAt + e] = table.data[record.tableOffset + 4 * e + 3];
        for (uint32_t level = 1; level < extinctionMaxLevels(entries); ++level) {
            const size_t below = levelsAt + (level - 1) * entries, half = size_t(1) << (level - 1);
            for (size_t e = 0; e < entries; ++e)
                table.data[below + entries + e] = std::max(table.data[below + e], table.data[below + std::min(e + half, entries - 1)]);
        }

        // Majorants: one float per macrocell, filled on the device once the data is uploaded
        // (VolumeMajorants.h), which also sets cellByCell; an unstructured mesh's here, from the value ranges
        // of its macrocells.
        record.majorantOffset = static_cast<uint32_t>(table.data.size());
        table.data.resize(table.data.size() + size_t(macroCells.x) * macroCells.y * macroCells.z, 0.0f);
        if (hostRanges)
            for (size_t m = 0; m < hostRanges->size(); ++m)
                table.data[record.majorantOffset + m] = extinctionMax(record, levelsAt, table.data, (*hostRanges)[m]);

        // World bounds: the grid box's corners.
        const glm::dmat4 gridToWorld = glm::dmat4(v.transform) * glm::inverse(objectToGrid);
        bvh::Aabb box;
        for (int c = 0; c < 8; ++c) {
            const glm::dvec4 corner((c & 1) ? extent.x : 0.0, (c & 2) ? extent.y : 0.0, (c & 4) ? extent.z : 0.0, 1.0);
            box.extend(glm::vec3(gridToWorld * corner));
        }
        table.bounds.extend(box);
        table.boxes.push_back(box);
        table.records.push_back(record);
        table.sources.push_back(index);
    }
    return table;
}

}  // namespace ripple::core
