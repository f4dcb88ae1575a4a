// Raw and NRRD volume files (NRRD: teem.sourceforge.net/nrrd/format.html; only the fields a 3D scalar
// field of one of six types needs, raw or gzip-encoded). Sizes are checked before anything is allocated, so
// a hostile header cannot ask for more than kMaxVoxels, and a short raw file is refused before it is read
// (a gzip stream only ever yields as many bytes as the field needs, so no stream can make it read more).
#include "io/volume/VolumeFile.h"

#include "io/FileRead.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstring>
#include <fstream>

#include <fcntl.h>
#include <unistd.h>
#include <zlib.h>

namespace ripple::apps {

namespace {

constexpr uint64_t kMaxHeaderBytes = 1 << 20;

std::string quoted(const std::filesystem::path& file) { return file.string(); }

[[noreturn]] void fail(const std::filesystem::path& file, const std::string& what) {
    throw VolumeError(quoted(file) + ": " + what);
}

size_t typeSize(VoxelType t) {
    switch (t) {
    case VoxelType::UInt8:
    case VoxelType::Int8: return 1;
    case VoxelType::UInt16:
    case VoxelType::Int16: return 2;
    case VoxelType::Float32: return 4;
    case VoxelType::Float64: return 8;
    }
    return 1;
}

const char* typeName(VoxelType t) {
    switch (t) {
    case VoxelType::UInt8: return "uint8";
    case VoxelType::Int8: return "int8";
    case VoxelType::UInt16: return "uint16";
    case VoxelType::Int16: return "int16";
    case VoxelType::Float32: return "float32";
    case VoxelType::Float64: return "float64";
    }
    return "?";
}

std::string lower(std::string s) {
    for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

std::string trim(const std::string& s) {
    const size_t a = s.find_first_not_of(" \t\r");
    if (a == std::string::npos) return "";
    return s.substr(a, s.find_last_not_of(" \t\r") - a + 1);
}

// A decimal count: digits only, no sign, at most 2^64 - 1.
std::optional<uint64_t> parseCount(const std::string& text) {
    if (text.empty() || text.size() > 20) return std::nullopt;
    uint64_t value = 0;
    for (char c : text) {
        if (c < '0' || c > '9') return std::nullopt;
        if (__builtin_mul_overflow(value, uint64_t(10), &value) || __builtin_add_overflow(value, uint64_t(c - '0'), &value))
            return std::nullopt;
    }
    return value;
}

std::optional<double> parseNumber(const std::string& text) {
    const std::string t = trim(text);
    if (t.empty()) return std::nullopt;
    char* end = nullptr;
    const double v = std::strtod(t.c_str(), &end);
    if (end != t.c_str() + t.size()) return std::nullopt;
    return v;
}

// Splits at any of `separators`, dropping empty pieces.
std::vector<std::string> split(const std::string& text, const char* separators) {
    std::vector<std::string> out;
    std::string piece;
    for (char c : text) {
        if (std::strchr(separators, c)) {
            if (!piece.empty()) out.push_back(piece);
            piece.clear();
        } else {
            piece += c;
        }
    }
    if (!piece.empty()) out.push_back(piece);
    return out;
}

// Three sizes, checked: none zero, their product within 64 bits and kMaxVoxels, at least 2 along each axis.
glm::uvec3 checkedDims(const std::filesystem::path& file, const std::array<uint64_t, 3>& d) {
    const std::string text = std::to_string(d[0]) + "x" + std::to_string(d[1]) + "x" + std::to_string(d[2]);
    if (d[0] == 0 || d[1] == 0 || d[2] == 0) fail(file, "dimensions " + text + " include a zero");
    uint64_t voxels = 0;
    if (__builtin_mul_overflow(d[0], d[1], &voxels) || __builtin_mul_overflow(voxels, d[2], &voxels))
        fail(file, "dimensions " + text + ": the voxel count overflows 64 bits");
    if (voxels > kMaxVoxels)
        fail(file, "dimensions " + text + " are " + std::to_string(voxels) + " voxels, more than the limit of " +
                       std::to_string(kMaxVoxels) + " (2^31)");
    if (d[0] < 2 || d[1] < 2 || d[2] < 2)
        fail(file, "dimensions " + text + ": a field needs at least 2 samples along each axis");
    return glm::uvec3(uint32_t(d[0]), uint32_t(d[1]), uint32_t(d[2]));
}

glm::vec3 checkedSpacing(const std::filesystem::path& file, const std::array<double, 3>& s, const std::string& what) {
    for (double v : s)
        if (!(std::isfinite(v) && v >= 1e-30 && v < 1e30))
            fail(file, what + " must be three positive finite numbers between 1e-30 and 1e30");
    return glm::vec3(float(s[0]), float(s[1]), float(s[2]));
}

std::optional<VoxelType> voxelTypeNamed(const std::string& name) {
    static const std::vector<std::pair<std::vector<const char*>, VoxelType>> names{
        {{"uint8", "uchar", "unsigned char", "uint8_t"}, VoxelType::UInt8},
        {{"int8", "signed char", "int8_t"}, VoxelType::Int8},
        {{"uint16", "ushort", "unsigned short", "unsigned short int", "uint16_t"}, VoxelType::UInt16},
        {{"int16", "short", "short int", "signed short", "signed short int", "int16_t"}, VoxelType::Int16},
        {{"float32", "float"}, VoxelType::Float32},
        {{"float64", "double"}, VoxelType::Float64}};
    const std::string key = lower(trim(name));
    for (const auto& [aliases, type] : names)
        for (const char* alias : aliases)
            if (key == alias) return type;
    return std::nullopt;
}

// The bytes of a field's samples, from `offset` in a file on: raw, or a gzip stream decompressed on the way
// (whose first `skip` decompressed bytes are passed over: NRRD's byte skip of compressed data).
class SampleBytes {
public:
    SampleBytes(const std::filesystem::path& label, const std::filesystem::path& dataFile, uint64_t offset, bool gzip)
        : label_(label), dataFile_(dataFile) {
        if (!gzip) {
            raw_.open(dataFile, std::ios::binary);
            if (!raw_) fail(label, "cannot open " + quoted(dataFile));
            raw_.seekg(std::streamoff(offset));
            return;
        }
        const int fd = ::open(dataFile.c_str(), O_RDONLY | O_CLOEXEC);
        if (fd < 0) fail(label, "cannot open " + quoted(dataFile));
        if (::lseek(fd, off_t(offset), SEEK_SET) != off_t(offset) || !(gzip_ = gzdopen(fd, "rb"))) {
            ::close(fd);
            fail(label, "cannot start reading the gzip data of " + quoted(dataFile));
        }
        gzbuffer(gzip_, 1u << 17);
    }
    ~SampleBytes() {
        if (gzip_) gzclose(gzip_);
    }
    SampleBytes(const SampleBytes&) = delete;
    SampleBytes& operator=(const SampleBytes&) = delete;

    // Fills `bytes`, or fails naming how many bytes the data held (`before` of them already read).
    void read(unsigned char* bytes, uint64_t count, uint64_t before, uint64_t needed) {
        if (!gzip_) {
            if (!raw_.read(reinterpret_cast<char*>(bytes), std::streamsize(count)))
                fail(label_, "reading " + quoted(dataFile_) + " stopped early");
            return;
        }
        for (uint64_t done = 0; done < count;) {
            const unsigned ask = unsigned(std::min<uint64_t>(count - done, uint64_t(1) << 30));
            const int got = gzread(gzip_, bytes + done, ask);
            if (got < 0) failCorrupt();
            if (gzdirect(gzip_)) fail(label_, "its encoding is gzip but its data is not gzip-compressed");
            if (got == 0)
                fail(label_, "its gzip data holds " + std::to_string(before + done) + " bytes after decompression, but the " +
                                 "field needs " + std::to_string(needed));
            done += uint64_t(got);
        }
    }

    // After the field's last sample: a gzip stream's end, where zlib checks its CRC-32 and length (data
    // after the field, as in a raw file, is allowed).
    void checkEnd() {
        if (!gzip_) return;
        unsigned char next = 0;
        if (gzread(gzip_, &next, 1) < 0) failCorrupt();
    }

    // Passes over `count` bytes.
    void skip(uint64_t count, uint64_t needed) {
        if (!gzip_) {
            raw_.seekg(std::streamoff(count), std::ios::cur);
            return;
        }
        std::vector<unsigned char> discard(std::min<uint64_t>(count, uint64_t(1) << 20));
        for (uint64_t done = 0; done < count;) {
            const uint64_t n = std::min<uint64_t>(count - done, discard.size());
            read(discard.data(), n, done, needed);
            done += n;
        }
    }

private:
    // zlib's message, without the "<fd:N>: " it names the stream by.
    [[noreturn]] void failCorrupt() const {
        int code = 0;
        const char* text = gzerror(gzip_, &code);
        std::string why = text ? text : "zlib error";
        if (why.rfind("<fd:", 0) == 0 && why.find(": ") != std::string::npos) why = why.substr(why.find(": ") + 2);
        fail(label_, "its gzip data is corrupt (" + why + ")");
    }

    std::filesystem::path label_, dataFile_;
    std::ifstream raw_;
    gzFile gzip_ = nullptr;
};

// Converts the samples of `slab` to floats: raw from `offset` in `dataFile` on (whose size is checked for the
// whole field), or (`gzip`) decompressed from a gzip stream starting at `offset`, past its first `gzipSkip`
// decompressed bytes.
VolumeData readSamples(const std::filesystem::path& label, const std::filesystem::path& dataFile, uint64_t offset,
                       glm::uvec3 dims, VoxelType type, bool bigEndian, VolumeSlab slab, bool gzip = false,
                       uint64_t gzipSkip = 0) {
    uint64_t fileSize = 0;
    std::string error;
    if (openRegularFile(dataFile, false, fileSize, error).get() < 0) {
        if (dataFile == label) fail(label, error);
        fail(label, "its data file " + quoted(dataFile) + (error == "no such file" ? " does not exist" : " " + error));
    }
    const uint64_t voxels = uint64_t(dims.x) * dims.y * dims.z;  // checked: at most 2^31
    const size_t size = typeSize(type);
    const uint64_t needed = voxels * size;
    const uint64_t available = fileSize > offset ? fileSize - offset : 0;
    const std::string dimsText = std::to_string(dims.x) + "x" + std::to_string(dims.y) + "x" + std::to_string(dims.z);
    if (!gzip && available < needed)
        fail(label, (dataFile == label ? std::string("holds ") : "its data file " + quoted(dataFile) + " holds ") +
                        std::to_string(available) + " bytes of data but " + dimsText + " " + typeName(type) +
                        " voxels need " + std::to_string(needed) + " bytes");
    // A raw file (no header: the data from its first byte) may end in a few bytes more than the field, but
    // one that holds a whole plane more was given the wrong dimensions or type: read as given it would come
    // out sheared, silently.
    if (!gzip && dataFile == label && offset == 0 && available - needed >= uint64_t(dims.x) * dims.y * size)
        fail(label, "holds " + std::to_string(available) + " bytes but " + dimsText + " " + typeName(type) +
                        " voxels need " + std::to_string(needed) + ": the dimensions or the type do not match the file");
    const uint64_t cells = dims.z - 1;
    if (slab.count == 0 || slab.index >= slab.count || cells < slab.count)
        fail(label, "its " + std::to_string(dims.z) + " sample planes along z cannot be split into " +
                        std::to_string(slab.count) + " slabs (each needs one cell)");
    const uint32_t zFirst = uint32_t(cells * slab.index / slab.count);
    const uint32_t zLast = uint32_t(cells * (slab.index + 1) / slab.count);  // shared with the next slab
    const uint64_t plane = uint64_t(dims.x) * dims.y;
    // A gzip stream is read from its start (each rank decompresses up to its slab, keeping only the slab).
    SampleBytes in(label, dataFile, offset, gzip);
    in.skip(gzipSkip + plane * zFirst * size, gzipSkip + needed);

    VolumeData out;
    out.wholeDims = dims;
    out.zFirst = zFirst;
    out.dims = glm::uvec3(dims.x, dims.y, zLast - zFirst + 1);
    const uint64_t slabVoxels = plane * out.dims.z;
    out.values.resize(slabVoxels);
    const bool swap = bigEndian != (std::endian::native == std::endian::big);
    std::vector<unsigned char> chunk;
    uint64_t nonFinite = 0;
    for (uint64_t done = 0; done < slabVoxels;) {
        const uint64_t count = std::min<uint64_t>(slabVoxels - done, uint64_t(1) << 20);
        chunk.resize(count * size);
        in.read(chunk.data(), chunk.size(), gzipSkip + (plane * zFirst + done) * size, gzipSkip + needed);
        for (uint64_t i = 0; i < count; ++i) {
            unsigned char bytes[8];
            std::memcpy(bytes, chunk.data() + i * size, size);
            if (swap) std::reverse(bytes, bytes + size);
            float v = 0.0f;
            switch (type) {
            case VoxelType::UInt8: v = float(bytes[0]); break;
            case VoxelType::Int8: v = float(int8_t(bytes[0])); break;
            case VoxelType::UInt16: { uint16_t x; std::memcpy(&x, bytes, 2); v = float(x); break; }
            case VoxelType::Int16: { int16_t x; std::memcpy(&x, bytes, 2); v = float(x); break; }
            case VoxelType::Float32: std::memcpy(&v, bytes, 4); break;
            case VoxelType::Float64: { double x; std::memcpy(&x, bytes, 8); v = float(x); break; }
            }
            if (!std::isfinite(v)) ++nonFinite;
            out.values[done + i] = v;
        }
        done += count;
    }
    if (zLast == cells) in.checkEnd();
    if (nonFinite > 0)
        fail(label, std::to_string(nonFinite) + " of " + std::to_string(slabVoxels) +
                        " voxels are NaN or infinite (or beyond float range); refusing the field");
    const auto [lo, hi] = std::minmax_element(out.values.begin(), out.values.end());
    out.minValue = *lo;
    out.maxValue = *hi;
    return out;
}

// By path components, so "/a/bc" is not inside "/a/b".
// "(a,b,c)" -> three numbers.
std::optional<std::array<double, 3>> parseVector(const std::string& text) {
    const std::string t = trim(text);
    if (t.size() < 2 || t.front() != '(' || t.back() != ')') return std::nullopt;
    const std::vector<std::string> parts = split(t.substr(1, t.size() - 2), ",");
    if (parts.size() != 3) return std::nullopt;
    std::array<double, 3> v{};
    for (int i = 0; i < 3; ++i) {
        const auto n = parseNumber(parts[size_t(i)]);
        if (!n) return std::nullopt;
        v[size_t(i)] = *n;
    }
    return v;
}

}  // namespace

bool isNrrdFile(const std::filesystem::path& file) {
    const std::string ext = lower(file.extension().string());
    return ext == ".nrrd" || ext == ".nhdr";
}

VoxelType parseVoxelType(const std::string& name) {
    if (const auto t = voxelTypeNamed(name)) return *t;
    throw VolumeError("unknown voxel type '" + name + "' (known: uint8, int8, uint16, int16, float32, float64)");
}

VolumeData readRawVolume(const std::filesystem::path& file, const RawLayout& layout, VolumeSlab slab) {
    const std::vector<std::string> parts = split(layout.dims, ",xX");
    std::array<uint64_t, 3> d{};
    bool good = parts.size() == 3;
    for (size_t i = 0; good && i < 3; ++i) {
        const auto n = parseCount(parts[i]);
        good = n.has_value();
        if (good) d[i] = *n;
    }
    if (!good) fail(file, "--dims '" + layout.dims + "' is not three counts X,Y,Z (or XxYxZ) of at most 2^64 - 1");
    const glm::uvec3 dims = checkedDims(file, d);
    VoxelType type = VoxelType::UInt8;
    try {
        type = parseVoxelType(layout.type);
    } catch (const VolumeError& e) {
        fail(file, std::string("--type: ") + e.what());
    }
    glm::vec3 spacing(1.0f);
    if (!layout.spacing.empty()) {
        const std::vector<std::string> s = split(layout.spacing, ",");
        std::array<double, 3> v{};
        bool ok = s.size() == 3;
        for (size_t i = 0; ok && i < 3; ++i) {
            const auto n = parseNumber(s[i]);
            ok = n.has_value();
            if (ok) v[i] = *n;
        }
        if (!ok) fail(file, "--spacing '" + layout.spacing + "' is not three numbers SX,SY,SZ");
        spacing = checkedSpacing(file, v, "--spacing");
    }
    VolumeData out = readSamples(file, file, 0, dims, type, false, slab);
    out.spacing = spacing;
    return out;
}

VolumeData readNrrdVolume(const std::filesystem::path& file, VolumeSlab slab) {
    uint64_t headerFileSize = 0;
    std::string error;
    if (openRegularFile(file, false, headerFileSize, error).get() < 0) fail(file, error);
    std::ifstream in(file, std::ios::binary);
    if (!in) fail(file, "cannot open it");

    // The header: lines up to a blank line or the end of the file.
    uint64_t consumed = 0;
    bool blankLine = false;
    std::vector<std::pair<std::string, std::string>> fields;  // lower-case name, value
    int lineNumber = 0;
    // Lines read a byte at a time, so that a file with no line break is not read whole.
    const auto nextLine = [&](std::string& line) {
        line.clear();
        for (int c; (c = in.get()) != std::char_traits<char>::eof();) {
            if (++consumed > kMaxHeaderBytes)
                fail(file, "the header is longer than 1 MiB (or the data has no blank line before it)");
            if (c == '\n') return true;
            line += char(c);
        }
        return !line.empty();
    };
    for (std::string line; nextLine(line);) {
        ++lineNumber;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (lineNumber == 1) {
            if (line.size() != 8 || line.compare(0, 7, "NRRD000") != 0 || line[7] < '1' || line[7] > '5')
                fail(file, "not an NRRD file (it does not start with NRRD0001 to NRRD0005)");
            continue;
        }
        if (line.empty()) {
            blankLine = true;
            break;
        }
        if (line[0] == '#' || line.find(":=") != std::string::npos) continue;  // comments and key/value pairs
        const size_t colon = line.find(": ");
        if (colon == std::string::npos)
            fail(file, "header line " + std::to_string(lineNumber) + " is not 'field: value': " + line.substr(0, 80));
        fields.emplace_back(lower(trim(line.substr(0, colon))), trim(line.substr(colon + 2)));
    }
    if (lineNumber == 0) fail(file, "is empty, not an NRRD file");

    const auto field = [&](const std::string& name) -> std::optional<std::string> {
        for (const auto& [n, v] : fields)
            if (n == name) return v;
        return std::nullopt;
    };
    const auto required = [&](const std::string& name) {
        const auto v = field(name);
        if (!v) fail(file, "the header has no '" + name + "' field");
        return *v;
    };

    const std::string typeText = required("type");
    const auto type = voxelTypeNamed(typeText);
    if (!type) fail(file, "type '" + typeText + "' is not supported (known: uint8, int8, uint16, int16, float32, float64 "
                                                "and their NRRD names)");
    const std::string dimension = required("dimension");
    if (dimension != "3") fail(file, "dimension: " + dimension + ": only 3D scalar fields (dimension: 3) are supported");
    const std::string sizesText = required("sizes");
    const std::vector<std::string> sizes = split(sizesText, " \t");
    std::array<uint64_t, 3> d{};
    bool sizesGood = sizes.size() == 3;
    for (size_t i = 0; sizesGood && i < 3; ++i) {
        const auto n = parseCount(sizes[i]);
        sizesGood = n.has_value();
        if (sizesGood) d[i] = *n;
    }
    if (!sizesGood) fail(file, "sizes '" + sizesText + "' are not three counts of at most 2^64 - 1");
    const glm::uvec3 dims = checkedDims(file, d);
    const std::string encoding = lower(required("encoding"));
    const bool gzip = encoding == "gzip" || encoding == "gz";
    if (encoding != "raw" && !gzip)
        fail(file, "encoding '" + encoding + "' is not supported: raw and gzip are (convert the data, e.g. with unu "
                                             "save -e gzip)");
    bool bigEndian = false;
    if (const auto endian = field("endian")) {
        const std::string e = lower(*endian);
        if (e != "little" && e != "big") fail(file, "endian '" + *endian + "' is neither little nor big");
        bigEndian = e == "big";
    } else if (typeSize(*type) > 1) {
        fail(file, "the header has no 'endian' field, which a type of more than one byte needs");
    }
    if (const auto lineSkip = field("line skip"); lineSkip && *lineSkip != "0")
        fail(file, "line skip " + *lineSkip + " is not supported");
    uint64_t byteSkip = 0;
    if (const auto skip = field("byte skip")) {
        const auto n = parseCount(*skip);
        if (!n || *n > (uint64_t(1) << 62)) fail(file, "byte skip '" + *skip + "' is not supported (give a count >= 0)");
        byteSkip = *n;
    }

    std::array<double, 3> spacing{1.0, 1.0, 1.0};
    if (const auto spacings = field("spacings")) {
        const std::vector<std::string> parts = split(*spacings, " \t");
        bool ok = parts.size() == 3;
        for (size_t i = 0; ok && i < 3; ++i) {
            const auto n = parseNumber(parts[i]);
            ok = n.has_value();
            if (ok) spacing[i] = *n;
        }
        if (!ok) fail(file, "spacings '" + *spacings + "' are not three numbers");
        checkedSpacing(file, spacing, "spacings");
    }
    if (const auto directions = field("space directions")) {
        const std::vector<std::string> parts = split(*directions, " \t");
        if (parts.size() != 3) fail(file, "space directions '" + *directions + "' are not three vectors (a,b,c)");
        for (size_t axis = 0; axis < 3; ++axis) {
            const auto v = parseVector(parts[axis]);
            if (!v) fail(file, "space directions: '" + parts[axis] + "' is not a vector (a,b,c)");
            for (size_t j = 0; j < 3; ++j)
                if (j != axis && (*v)[j] != 0.0)
                    fail(file, "space directions '" + *directions + "' are not axis-aligned: only diagonal directions "
                                                                   "are supported");
            spacing[axis] = (*v)[axis];
        }
        checkedSpacing(file, spacing, "space directions (their diagonal)");
    }
    glm::vec3 origin(0.0f);
    if (const auto spaceOrigin = field("space origin")) {
        const auto v = parseVector(*spaceOrigin);
        if (!v || !std::isfinite((*v)[0]) || !std::isfinite((*v)[1]) || !std::isfinite((*v)[2]))
            fail(file, "space origin '" + *spaceOrigin + "' is not a finite vector (x,y,z)");
        origin = glm::vec3(float((*v)[0]), float((*v)[1]), float((*v)[2]));
    }

    std::filesystem::path dataFile = file;
    uint64_t offset = consumed;
    std::optional<std::string> detached = field("data file");
    if (!detached) detached = field("datafile");
    if (detached) {
        if (detached->rfind("LIST", 0) == 0 || detached->find('%') != std::string::npos)
            fail(file, "data file '" + *detached + "': lists and patterns of data files are not supported, only one file");
        dataFile = resolveBeside(file, *detached, error);
        if (dataFile.empty()) fail(file, "data file '" + *detached + "' " + error);
        offset = 0;
    } else if (!blankLine) {
        fail(file, "the header names no 'data file' and no blank line ends it before attached data");
    }
    // Raw data skips file bytes; gzip data skips decompressed bytes (the NRRD format's reading).
    if (!gzip && __builtin_add_overflow(offset, byteSkip, &offset)) fail(file, "byte skip is too large");

    VolumeData out = readSamples(file, dataFile, offset, dims, *type, bigEndian, slab, gzip, gzip ? byteSkip : 0);
    out.origin = origin;
    out.spacing = glm::vec3(float(spacing[0]), float(spacing[1]), float(spacing[2]));
    return out;
}

}  // namespace ripple::apps
