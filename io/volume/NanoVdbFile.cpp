// NanoVDB files (see NanoVdbFile.h). The layout, from NanoVDB's IO.h (its file format, version 32): a
// 16-byte header (magic, version, grid count, codec), then per grid 176 bytes of metadata and its name,
// then the grids' buffers in the same order. A zip-compressed buffer is its compressed size (8 bytes) and one
// zlib stream; a blosc-compressed one is chunks of up to 1 GiB, each its compressed size and a blosc block.
#include "io/volume/NanoVdbFile.h"

#include "core/scene/NanoVdbTree.h"
#include "io/FileRead.h"

#include <blosc.h>
#include <nanovdb/NanoVDB.h>
#include <zlib.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>

namespace ripple::apps {

namespace {

constexpr uint64_t kMaxFileBytes = uint64_t(4) << 30;  // the kernels address a grid with 32 bits
constexpr size_t kHeaderBytes = 16, kMetaBytes = 176;

template <typename T>
T readAt(const std::string& bytes, size_t offset) {
    T value;
    std::memcpy(&value, bytes.data() + offset, sizeof(T));
    return value;
}

}  // namespace

bool isNanoVdbFile(const std::filesystem::path& file) {
    std::string extension = file.extension().string();
    for (char& c : extension) c = char(std::tolower(static_cast<unsigned char>(c)));
    return extension == ".nvdb";
}

NanoVdbFile readNanoVdbFile(const std::filesystem::path& file) {
    const std::string bytes = readRegularFile(file, kMaxFileBytes, "NanoVDB file");
    const auto fail = [&](const std::string& problem) { return VolumeError(file.string() + ": " + problem); };
    if (bytes.size() < kHeaderBytes) throw fail("too short for a NanoVDB file header");
    if (readAt<uint64_t>(bytes, 0) != NANOVDB_MAGIC_NUMBER) throw fail("not a NanoVDB file (its magic number is wrong)");
    const uint32_t version = readAt<uint32_t>(bytes, 8);
    if ((version >> 21) != NANOVDB_MAJOR_VERSION_NUMBER)
        throw fail("NanoVDB file version " + std::to_string(version >> 21) + "; Ripple reads major version " +
                   std::to_string(NANOVDB_MAJOR_VERSION_NUMBER));
    const uint16_t gridCount = readAt<uint16_t>(bytes, 12), codec = readAt<uint16_t>(bytes, 14);
    if (gridCount == 0) throw fail("the file holds no grid");
    if (codec > 2) throw fail("unknown compression codec " + std::to_string(codec) + " (0 none, 1 zip and 2 blosc are read)");
    // The metadata and names of the segment's grids, then the first grid's buffer.
    size_t at = kHeaderBytes;
    NanoVdbFile out;
    uint64_t gridSize = 0, fileSize = 0;
    for (uint16_t g = 0; g < gridCount; ++g) {
        if (bytes.size() - at < kMetaBytes) throw fail("its grid metadata runs past the file");
        const uint32_t nameSize = readAt<uint32_t>(bytes, at + 136);
        if (g == 0) {
            gridSize = readAt<uint64_t>(bytes, at);
            fileSize = readAt<uint64_t>(bytes, at + 8);
            const uint32_t gridType = readAt<uint32_t>(bytes, at + 32);
            if (gridType != uint32_t(nanovdb::GridType::Float))
                throw fail("its first grid holds " + core::gridTypeName(gridType) + "; Ripple reads float grids");
            for (int k = 0; k < 3; ++k) {
                out.worldLo[k] = readAt<double>(bytes, at + 40 + 8 * k);
                out.worldHi[k] = readAt<double>(bytes, at + 64 + 8 * k);
            }
        }
        at += kMetaBytes;
        if (bytes.size() - at < nameSize) throw fail("a grid's name runs past the file");
        if (g == 0) out.name.assign(bytes.data() + at, strnlen(bytes.data() + at, nameSize));
        at += nameSize;
    }
    for (int k = 0; k < 3; ++k)
        if (!std::isfinite(out.worldLo[k]) || !std::isfinite(out.worldHi[k]) || out.worldHi[k] < out.worldLo[k])
            throw fail("its first grid's world box is not finite and ordered");
    if (gridSize == 0 || gridSize > kMaxFileBytes)
        throw fail("its first grid says it is " + std::to_string(gridSize) + " bytes (Ripple reads 1 byte to 4 GiB)");
    if (codec == 0) {
        if (gridSize != fileSize) throw fail("its first grid's sizes disagree (" + std::to_string(gridSize) + " in memory, " +
                                             std::to_string(fileSize) + " on disk) for an uncompressed file");
        if (gridSize > bytes.size() - at) throw fail("its first grid (" + std::to_string(gridSize) + " bytes) runs past the file");
        out.grid.assign(bytes.begin() + std::ptrdiff_t(at), bytes.begin() + std::ptrdiff_t(at + gridSize));
    } else {
        // Compressed chunks: zip, one chunk; blosc, one per GiB of the grid.
        constexpr uint64_t kBloscChunk = uint64_t(1) << 30;
        out.grid.resize(gridSize);
        uint64_t done = 0;
        while (done < gridSize) {
            if (bytes.size() - at < 8) throw fail("its first grid's compressed data runs past the file");
            const uint64_t packed = readAt<uint64_t>(bytes, at);
            at += 8;
            if (packed > bytes.size() - at) throw fail("its first grid's compressed data runs past the file");
            const auto* source = reinterpret_cast<const uint8_t*>(bytes.data() + at);
            if (codec == 1) {
                uLongf unpacked = uLongf(gridSize);
                if (uncompress(out.grid.data(), &unpacked, source, uLong(packed)) != Z_OK || unpacked != gridSize)
                    throw fail("its first grid's zip data does not decompress to its " + std::to_string(gridSize) + " bytes");
                done = gridSize;
            } else {
                const uint64_t chunk = std::min(gridSize - done, kBloscChunk);
                size_t expected = 0, compressed = 0, block = 0;
                if (packed >= BLOSC_MIN_HEADER_LENGTH) blosc_cbuffer_sizes(source, &expected, &compressed, &block);
                if (packed < BLOSC_MIN_HEADER_LENGTH || expected != chunk || compressed != packed ||
                    blosc_decompress_ctx(source, out.grid.data() + done, size_t(chunk), 1) != int(chunk))
                    throw fail("its first grid's blosc data does not decompress to its " + std::to_string(gridSize) + " bytes");
                done += chunk;
            }
            at += packed;
        }
    }
    // The root's value range, read through the device's own checks of the grid (core/scene/NanoVdbTree.h).
    try {
        const core::CheckedNanoVdbGrid checked(out.grid);
        out.minValue = checked.grid().tree().root().minimum();
        out.maxValue = checked.grid().tree().root().maximum();
    } catch (const std::invalid_argument& e) {
        throw fail(std::string("its first grid: ") + e.what());
    }
    if (!std::isfinite(out.minValue) || !std::isfinite(out.maxValue)) throw fail("its first grid's value range is not finite");
    return out;
}

}  // namespace ripple::apps
