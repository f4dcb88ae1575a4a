// Reads a structured-regular scalar field from a raw file or an NRRD file (.nrrd, or a .nhdr header with a
// detached raw data file), for ripple-render --volume. No ANARI here: the field comes back as float values.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace ripple::apps {

// Every problem with a volume file: the message names the file and what is wrong with it.
struct VolumeError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

enum class VoxelType { UInt8, Int8, UInt16, Int16, Float32, Float64 };

// The largest field read: 2^31 voxels (8 GiB of float values).
constexpr uint64_t kMaxVoxels = uint64_t(1) << 31;

// A field of dims.x * dims.y * dims.z samples, x fastest: the whole file's, or one z-slab of it (then
// wholeDims is the file's and zFirst the slab's first sample plane). The values are the file's numbers converted to
// float as they are (a uint8 255 is 255.0, not 1.0): the transfer function's range comes from min..max.
struct VolumeData {
    glm::uvec3 dims{0};
    glm::uvec3 wholeDims{0};
    uint32_t zFirst = 0;
    std::vector<float> values;
    glm::vec3 origin{0.0f};             // NRRD "space origin"; 0 for raw files
    glm::vec3 spacing{1.0f};            // between neighbouring samples, each positive
    float minValue = 0.0f, maxValue = 0.0f;  // of the samples read
};

// Which part of the z axis to read: slab `index` of `count` (data-parallel ranks). The cells between
// sample planes are dealt evenly; each slab holds its cells' planes, so neighbours share one plane.
// Every slab checks the whole file (its size, its header) so that all ranks agree on errors.
struct VolumeSlab {
    uint32_t index = 0, count = 1;
};

// How to read a raw file (for NRRD the header says all of it).
struct RawLayout {
    std::string dims;                   // "X,Y,Z" or "XxYxZ"
    std::string type;                   // uint8, int8, uint16, int16, float32 or float64
    std::string spacing;                // "SX,SY,SZ"; empty: 1,1,1
};

// Whether `file` is read as NRRD (its extension is .nrrd or .nhdr, any case).
bool isNrrdFile(const std::filesystem::path& file);

// The type named as --type names it; throws VolumeError listing the known names.
VoxelType parseVoxelType(const std::string& name);

// Reads a little-endian raw file (x fastest) of the given layout. The file may be longer than the field by
// less than one x-y plane (trailing bytes are ignored) but not shorter, and not a plane or more longer (the
// layout would not be the file's). Throws VolumeError.
VolumeData readRawVolume(const std::filesystem::path& file, const RawLayout& layout, VolumeSlab slab = {});

// Reads an NRRD file: attached data (.nrrd) or `data file:` (relative to the header's folder, confined to
// it). Encoding raw or gzip (a slab of gzip data is decompressed from the stream's start: every rank reads
// up to its slab, and keeps only the slab). Throws VolumeError.
VolumeData readNrrdVolume(const std::filesystem::path& file, VolumeSlab slab = {});

}  // namespace ripple::apps
