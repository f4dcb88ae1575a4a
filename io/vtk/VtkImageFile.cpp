// VTK image data, XML and legacy (see VtkImageFile.h). The XML is parsed by pugixml once the raw appended
// block (binary bytes that are not XML) is cut out; every size read from a file is checked against the file
// and against kMaxVoxels before anything is allocated, so a hostile file ends in a VolumeError.
#include "io/vtk/VtkImageFile.h"

#include "io/FileRead.h"

#include <pugixml.hpp>
#include <zlib.h>

#include <algorithm>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>
#include <sstream>

namespace ripple::apps {

namespace {

constexpr uint64_t kMaxVtkFileBytes = uint64_t(1) << 34;  // 16 GiB: kMaxVoxels of doubles and some

[[noreturn]] void fail(const std::filesystem::path& file, const std::string& what) {
    throw VolumeError(file.string() + ": " + what);
}

// An array as stored: its bytes in the file's byte order, or its ASCII numbers already parsed.
struct StoredArray {
    VtkArrayInfo info;
    std::string bytes;            // binary, `type` elements
    std::vector<double> numbers;  // ascii
    bool bigEndian = false;
};

// Element size of a VTK type name (XML and legacy spellings); 0 for an unknown one.
struct TypeInfo {
    uint32_t size = 0;
    bool isFloat = false, isSigned = false;
};
TypeInfo typeInfo(std::string name) {
    std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    if (name == "int8" || name == "char" || name == "signed_char") return {1, false, true};
    if (name == "uint8" || name == "unsigned_char") return {1, false, false};
    if (name == "int16" || name == "short") return {2, false, true};
    if (name == "uint16" || name == "unsigned_short") return {2, false, false};
    if (name == "int32" || name == "int") return {4, false, true};
    if (name == "uint32" || name == "unsigned_int") return {4, false, false};
    if (name == "int64" || name == "long" || name == "vtktypeint64" || name == "long_long") return {8, false, true};
    if (name == "uint64" || name == "unsigned_long" || name == "vtktypeuint64" || name == "unsigned_long_long")
        return {8, false, false};
    if (name == "float32" || name == "float") return {4, true, true};
    if (name == "float64" || name == "double") return {8, true, true};
    return {};
}

double element(const char* p, const TypeInfo& t, bool swap) {
    unsigned char b[8];
    std::memcpy(b, p, t.size);
    if (swap) std::reverse(b, b + t.size);
    switch (t.size) {
    case 1: return t.isSigned ? double(int8_t(b[0])) : double(b[0]);
    case 2: {
        uint16_t v;
        std::memcpy(&v, b, 2);
        return t.isSigned ? double(int16_t(v)) : double(v);
    }
    case 4: {
        uint32_t v;
        std::memcpy(&v, b, 4);
        if (t.isFloat) return double(std::bit_cast<float>(v));
        return t.isSigned ? double(int32_t(v)) : double(v);
    }
    default: {
        uint64_t v;
        std::memcpy(&v, b, 8);
        if (t.isFloat) return std::bit_cast<double>(v);
        return t.isSigned ? double(int64_t(v)) : double(v);
    }
    }
}

// The array's values as doubles, tuples x components, in the file's order.
std::vector<double> values(const std::filesystem::path& file, const StoredArray& a) {
    const uint64_t count = a.info.tuples * a.info.components;
    if (!a.numbers.empty() || a.bytes.empty()) {
        if (a.numbers.size() != count)
            fail(file, "array '" + a.info.name + "' holds " + std::to_string(a.numbers.size()) + " numbers, not the " +
                           std::to_string(count) + " its size needs");
        return a.numbers;
    }
    const TypeInfo t = typeInfo(a.info.type);
    if (a.bytes.size() / t.size < count)
        fail(file, "array '" + a.info.name + "' holds " + std::to_string(a.bytes.size()) + " bytes, not the " +
                       std::to_string(count * t.size) + " its size needs");
    const bool swap = a.bigEndian != (std::endian::native == std::endian::big);
    std::vector<double> out(count);
    for (uint64_t i = 0; i < count; ++i) out[i] = element(a.bytes.data() + i * t.size, t, swap);
    return out;
}

// ---- XML -------------------------------------------------------------------------------------------------

int base64Value(char c) {
    if (c >= 'A' && c <= 'Z') return c - 'A';
    if (c >= 'a' && c <= 'z') return c - 'a' + 26;
    if (c >= '0' && c <= '9') return c - '0' + 52;
    if (c == '+') return 62;
    if (c == '/') return 63;
    return -1;
}

// Decodes base64 `text` (whitespace already removed); '=' padding ends a group.
std::string decodeBase64(const std::filesystem::path& file, std::string_view text, const std::string& what) {
    if (text.size() % 4 != 0) fail(file, what + ": base64 data of " + std::to_string(text.size()) + " characters (not a multiple of 4)");
    std::string out;
    out.reserve(text.size() / 4 * 3);
    for (size_t i = 0; i < text.size(); i += 4) {
        int v[4];
        int pad = 0;
        for (int k = 0; k < 4; ++k) {
            if (text[i + size_t(k)] == '=') {
                v[k] = 0;
                ++pad;
            } else if ((v[k] = base64Value(text[i + size_t(k)])) < 0 || pad > 0) {
                fail(file, what + ": not base64 data");
            }
        }
        const uint32_t word = uint32_t(v[0]) << 18 | uint32_t(v[1]) << 12 | uint32_t(v[2]) << 6 | uint32_t(v[3]);
        out += char(word >> 16);
        if (pad < 2) out += char((word >> 8) & 0xff);
        if (pad < 1) out += char(word & 0xff);
    }
    return out;
}

struct XmlLayout {
    uint32_t headerBytes = 4;  // UInt32 or UInt64 sizes
    bool bigEndian = false;
    bool zlib = false;
};

uint64_t headerWord(const std::string& bytes, size_t index, const XmlLayout& layout) {
    const TypeInfo t{layout.headerBytes, false, false};
    return uint64_t(element(bytes.data() + index * layout.headerBytes, t, layout.bigEndian != (std::endian::native == std::endian::big)));
}

// A compressed array: [blocks, block size, last block size, compressed sizes...] then the zlib blocks.
std::string inflateBlocks(const std::filesystem::path& file, const std::string& header, std::string_view data,
                          const XmlLayout& layout, const std::string& what) {
    const uint64_t blocks = headerWord(header, 0, layout), blockSize = headerWord(header, 1, layout),
                   lastSize = headerWord(header, 2, layout);
    const uint64_t total = blocks == 0 ? 0 : (blocks - 1) * blockSize + (lastSize == 0 ? blockSize : lastSize);
    if (blocks > (uint64_t(1) << 32) || total > kMaxVoxels * 8)
        fail(file, what + ": a compression header of " + std::to_string(blocks) + " blocks of " +
                       std::to_string(blockSize) + " bytes is beyond any field Ripple reads");
    std::string out(total, '\0');
    uint64_t at = 0, written = 0;
    for (uint64_t b = 0; b < blocks; ++b) {
        const uint64_t compressed = headerWord(header, 3 + b, layout);
        const uint64_t expected = b + 1 == blocks && lastSize != 0 ? lastSize : blockSize;
        if (at + compressed > data.size()) fail(file, what + ": compressed block " + std::to_string(b) + " runs past the data");
        uLongf size = uLongf(expected);
        if (uncompress(reinterpret_cast<Bytef*>(out.data() + written), &size,
                       reinterpret_cast<const Bytef*>(data.data() + at), uLong(compressed)) != Z_OK ||
            size != expected)
            fail(file, what + ": compressed block " + std::to_string(b) + " does not inflate to " + std::to_string(expected) + " bytes");
        at += compressed;
        written += expected;
    }
    return out;
}

// The bytes of an inline base64 array ("binary"), or of an appended raw one at `raw`.
std::string xmlArrayBytes(const std::filesystem::path& file, const XmlLayout& layout, std::string_view base64,
                          std::optional<std::string_view> raw, const std::string& what) {
    const size_t hb = layout.headerBytes;
    if (raw) {  // appended raw: the header then the data, as bytes
        std::string_view in = *raw;
        if (!layout.zlib) {
            if (in.size() < hb) fail(file, what + ": its appended data ends before its size");
            const uint64_t size = headerWord(std::string(in.substr(0, hb)), 0, layout);
            if (size > in.size() - hb) fail(file, what + ": " + std::to_string(size) + " bytes run past the appended data");
            return std::string(in.substr(hb, size));
        }
        if (in.size() < 3 * hb) fail(file, what + ": its appended data ends before its compression header");
        const uint64_t blocks = headerWord(std::string(in.substr(0, 3 * hb)), 0, layout);
        if (blocks > (in.size() - 3 * hb) / hb) fail(file, what + ": a compression header of " + std::to_string(blocks) + " blocks runs past the data");
        const size_t headerSize = size_t(3 + blocks) * hb;
        return inflateBlocks(file, std::string(in.substr(0, headerSize)), in.substr(headerSize), layout, what);
    }
    // Inline base64: uncompressed, header and data are one stream; compressed, the header is a stream of its own.
    if (!layout.zlib) {
        const std::string bytes = decodeBase64(file, base64, what);
        if (bytes.size() < hb) fail(file, what + ": its data ends before its size");
        const uint64_t size = headerWord(bytes, 0, layout);
        if (size > bytes.size() - hb) fail(file, what + ": " + std::to_string(size) + " bytes run past its data");
        return bytes.substr(hb, size);
    }
    const size_t firstChars = (3 * hb + 2) / 3 * 4;
    if (base64.size() < firstChars) fail(file, what + ": its data ends before its compression header");
    const uint64_t blocks = headerWord(decodeBase64(file, base64.substr(0, firstChars), what), 0, layout);
    if (blocks > base64.size()) fail(file, what + ": a compression header of " + std::to_string(blocks) + " blocks runs past the data");
    const size_t headerChars = (size_t(3 + blocks) * hb + 2) / 3 * 4;
    if (base64.size() < headerChars) fail(file, what + ": its data ends inside its compression header");
    const std::string header = decodeBase64(file, base64.substr(0, headerChars), what);
    return inflateBlocks(file, header, decodeBase64(file, base64.substr(headerChars), what), layout, what);
}

std::vector<double> numbersIn(std::string_view text) {
    std::vector<double> out;
    std::istringstream in{std::string(text)};
    for (double v; in >> v;) out.push_back(v);
    return out;
}

struct ImageGrid {
    glm::uvec3 dims{0};
    glm::vec3 origin{0.0f}, spacing{1.0f};
    std::vector<StoredArray> arrays;
    std::string activeScalars;
};

ImageGrid readXmlImage(const std::filesystem::path& file, const std::string& text) {
    // The raw appended block is bytes, not XML: cut out before parsing, kept for the arrays.
    std::string xml = text;
    std::string_view appended;
    bool appendedRaw = false;
    if (const size_t open = text.find("<AppendedData"); open != std::string::npos) {
        const size_t tagEnd = text.find('>', open);
        const size_t close = text.rfind("</AppendedData>");
        const size_t underscore = tagEnd == std::string::npos ? std::string::npos : text.find('_', tagEnd);
        if (tagEnd == std::string::npos || close == std::string::npos || underscore == std::string::npos || underscore > close)
            fail(file, "malformed <AppendedData> (no '_' before </AppendedData>)");
        appendedRaw = text.substr(open, tagEnd - open).find("\"raw\"") != std::string::npos;
        appended = std::string_view(text).substr(underscore + 1, close - underscore - 1);
        xml = text.substr(0, tagEnd + 1) + text.substr(close);
    }
    pugi::xml_document doc;
    const pugi::xml_parse_result parsed = doc.load_buffer(xml.data(), xml.size());
    if (!parsed) fail(file, std::string("not VTK XML: ") + parsed.description() + " at byte " + std::to_string(parsed.offset));
    const pugi::xml_node root = doc.child("VTKFile");
    if (!root) fail(file, "not VTK XML: no <VTKFile> element");
    const std::string type = root.attribute("type").value();
    if (type != "ImageData") fail(file, "a VTK " + (type.empty() ? std::string("file of no type") : type) + " file; Ripple reads ImageData (.vti) here");
    XmlLayout layout;
    const std::string order = root.attribute("byte_order").as_string("LittleEndian");
    if (order != "LittleEndian" && order != "BigEndian") fail(file, "unknown byte_order '" + order + "'");
    layout.bigEndian = order == "BigEndian";
    const std::string headerType = root.attribute("header_type").as_string("UInt32");
    if (headerType != "UInt32" && headerType != "UInt64") fail(file, "unknown header_type '" + headerType + "' (UInt32 or UInt64)");
    layout.headerBytes = headerType == "UInt64" ? 8 : 4;
    const std::string compressor = root.attribute("compressor").value();
    if (!compressor.empty() && compressor != "vtkZLibDataCompressor")
        fail(file, "compressor " + compressor + " is not supported (vtkZLibDataCompressor is)");
    layout.zlib = !compressor.empty();

    const pugi::xml_node image = root.child("ImageData");
    if (!image) fail(file, "no <ImageData> element");
    const std::vector<double> extent = numbersIn(image.attribute("WholeExtent").value());
    if (extent.size() != 6) fail(file, "WholeExtent is not six integers");
    ImageGrid grid;
    for (int a = 0; a < 3; ++a) {
        const double n = extent[size_t(2 * a + 1)] - extent[size_t(2 * a)] + 1;
        if (!(n >= 1 && n <= double(kMaxVoxels))) fail(file, "WholeExtent spans no samples along an axis");
        grid.dims[a] = uint32_t(n);
    }
    const std::vector<double> origin = numbersIn(image.attribute("Origin").as_string("0 0 0"));
    const std::vector<double> spacing = numbersIn(image.attribute("Spacing").as_string("1 1 1"));
    if (origin.size() != 3 || spacing.size() != 3) fail(file, "Origin and Spacing need three numbers each");
    const std::vector<double> direction = numbersIn(image.attribute("Direction").as_string("1 0 0 0 1 0 0 0 1"));
    if (direction != std::vector<double>{1, 0, 0, 0, 1, 0, 0, 0, 1})
        fail(file, "a Direction other than the identity (a rotated grid) is not supported");
    for (int a = 0; a < 3; ++a) {
        grid.origin[a] = float(origin[size_t(a)]);
        grid.spacing[a] = float(spacing[size_t(a)]);
    }
    const auto pieces = image.children("Piece");
    if (std::distance(pieces.begin(), pieces.end()) != 1) fail(file, "an ImageData of several pieces is not supported (one piece is)");
    const pugi::xml_node piece = image.child("Piece");
    const uint64_t points = uint64_t(grid.dims.x) * grid.dims.y * grid.dims.z;
    const uint64_t cells = uint64_t(std::max(grid.dims.x - 1, 1u)) * std::max(grid.dims.y - 1, 1u) * std::max(grid.dims.z - 1, 1u);
    for (const char* association : {"PointData", "CellData"}) {
        const pugi::xml_node data = piece.child(association);
        if (std::string(association) == "PointData") grid.activeScalars = data.attribute("Scalars").value();
        for (const pugi::xml_node array : data.children("DataArray")) {
            StoredArray a;
            a.info.name = array.attribute("Name").value();
            a.info.association = std::string(association) == "PointData" ? "point" : "cell";
            a.info.type = array.attribute("type").value();
            a.info.components = array.attribute("NumberOfComponents").as_uint(1);
            a.info.tuples = a.info.association == "point" ? points : cells;
            a.bigEndian = layout.bigEndian;
            const std::string what = "array '" + a.info.name + "'";
            if (typeInfo(a.info.type).size == 0) fail(file, what + " has unknown type '" + a.info.type + "'");
            if (a.info.components < 1 || a.info.components > 9) fail(file, what + " has " + std::to_string(a.info.components) + " components (1 to 9)");
            const std::string format = array.attribute("format").value();
            if (format == "ascii") {
                a.numbers = numbersIn(array.child_value());
            } else if (format == "binary" || format == "appended") {
                std::optional<std::string_view> raw;
                std::string base64;
                if (format == "appended") {
                    if (!appendedRaw) fail(file, what + ": appended data in base64 is not supported (raw or inline binary is)");
                    const uint64_t offset = array.attribute("offset").as_ullong(std::numeric_limits<uint64_t>::max());
                    if (offset > appended.size()) fail(file, what + ": offset " + std::to_string(offset) + " is past the appended data");
                    raw = appended.substr(offset);
                } else {
                    for (const char c : std::string_view(array.child_value()))
                        if (!std::isspace(static_cast<unsigned char>(c))) base64 += c;
                }
                a.bytes = xmlArrayBytes(file, layout, base64, raw, what);
            } else {
                fail(file, what + " has unknown format '" + format + "'");
            }
            grid.arrays.push_back(std::move(a));
        }
    }
    return grid;
}

// ---- legacy ----------------------------------------------------------------------------------------------

// A cursor over a legacy file: lines, whitespace-separated words, and raw bytes for BINARY arrays.
class LegacyReader {
public:
    LegacyReader(const std::filesystem::path& file, const std::string& bytes) : file_(file), bytes_(bytes) {}

    std::string line() {
        if (pos_ >= bytes_.size()) fail(file_, "the file ends early, in its header");
        const size_t end = std::min(bytes_.find('\n', pos_), bytes_.size());
        std::string text = bytes_.substr(pos_, end - pos_);
        pos_ = end + 1;
        if (!text.empty() && text.back() == '\r') text.pop_back();
        return text;
    }
    // The next word, or empty at the end of the file.
    std::string word() {
        while (pos_ < bytes_.size() && std::isspace(static_cast<unsigned char>(bytes_[pos_]))) ++pos_;
        const size_t start = pos_;
        while (pos_ < bytes_.size() && !std::isspace(static_cast<unsigned char>(bytes_[pos_]))) ++pos_;
        return bytes_.substr(start, pos_ - start);
    }
    uint64_t count(const std::string& what) {
        const std::string w = word();
        char* end = nullptr;
        const unsigned long long v = std::strtoull(w.c_str(), &end, 10);
        if (w.empty() || *end != '\0' || w[0] == '-') fail(file_, what + " '" + w + "' is not a count");
        return v;
    }
    double number(const std::string& what) {
        const std::string w = word();
        char* end = nullptr;
        const double v = std::strtod(w.c_str(), &end);
        if (w.empty() || *end != '\0') fail(file_, what + " '" + w + "' is not a number");
        return v;
    }
    // `count` elements: ASCII numbers, or big-endian binary right after the current line's end.
    void data(StoredArray& a, bool binary, uint64_t count) {
        if (!binary) {
            if (count > bytes_.size()) fail(file_, "array '" + a.info.name + "': " + std::to_string(count) + " numbers cannot fit in the file");
            a.numbers.reserve(count);
            for (uint64_t i = 0; i < count; ++i) a.numbers.push_back(number("array '" + a.info.name + "' value"));
            return;
        }
        const size_t lineEnd = bytes_.find('\n', pos_);
        if (lineEnd == std::string::npos) fail(file_, "array '" + a.info.name + "': the file ends before its data");
        pos_ = lineEnd + 1;
        const uint64_t size = count * typeInfo(a.info.type).size;
        if (count > kMaxVoxels * 9 || size > bytes_.size() - pos_)
            fail(file_, "array '" + a.info.name + "' needs " + std::to_string(size) + " bytes; the file holds " +
                            std::to_string(bytes_.size() - pos_) + " after its header");
        a.bytes = bytes_.substr(pos_, size);
        a.bigEndian = true;
        pos_ += size;
    }
    bool done() {
        while (pos_ < bytes_.size() && std::isspace(static_cast<unsigned char>(bytes_[pos_]))) ++pos_;
        return pos_ >= bytes_.size();
    }
    // 5.1's METADATA block after an array: lines up to a blank one.
    void skipMetadata() {
        while (pos_ < bytes_.size()) {
            const std::string l = line();
            if (l.find_first_not_of(" \t") == std::string::npos) return;
        }
    }

private:
    const std::filesystem::path& file_;
    const std::string& bytes_;
    size_t pos_ = 0;
};

// Legacy names escape spaces and other bytes as %XX.
std::string unescape(const std::string& name) {
    std::string out;
    for (size_t i = 0; i < name.size(); ++i) {
        if (name[i] == '%' && i + 2 < name.size() && std::isxdigit(static_cast<unsigned char>(name[i + 1])) &&
            std::isxdigit(static_cast<unsigned char>(name[i + 2]))) {
            out += char(std::stoi(name.substr(i + 1, 2), nullptr, 16));
            i += 2;
        } else {
            out += name[i];
        }
    }
    return out;
}

ImageGrid readLegacyImage(const std::filesystem::path& file, const std::string& bytes) {
    LegacyReader in(file, bytes);
    const std::string version = in.line();
    if (version.rfind("# vtk DataFile Version", 0) != 0) fail(file, "not a VTK file (no '# vtk DataFile Version' line)");
    in.line();  // the title
    std::string format;
    while (format.find_first_not_of(" \t") == std::string::npos) format = in.line();  // version 1.0 leaves blank lines
    format.erase(std::remove_if(format.begin(), format.end(), [](unsigned char c) { return std::isspace(c); }), format.end());
    if (format != "ASCII" && format != "BINARY") fail(file, "the third line is '" + format + "', not ASCII or BINARY");
    const bool binary = format == "BINARY";
    if (in.word() != "DATASET") fail(file, "no DATASET line");
    const std::string dataset = in.word();
    if (dataset != "STRUCTURED_POINTS")
        fail(file, "a legacy " + dataset + " data set; Ripple reads STRUCTURED_POINTS here");
    ImageGrid grid;
    bool haveDims = false;
    uint64_t tuples = 0;
    std::string association;
    for (std::string key = in.word(); !key.empty(); key = in.done() ? "" : in.word()) {
        if (key == "DIMENSIONS") {
            for (int a = 0; a < 3; ++a) {
                const uint64_t n = in.count("DIMENSIONS");
                if (n < 1 || n > kMaxVoxels) fail(file, "DIMENSIONS " + std::to_string(n) + " along an axis");
                grid.dims[a] = uint32_t(n);
            }
            haveDims = true;
        } else if (key == "SPACING" || key == "ASPECT_RATIO") {
            for (int a = 0; a < 3; ++a) grid.spacing[a] = float(in.number(key));
        } else if (key == "ORIGIN") {
            for (int a = 0; a < 3; ++a) grid.origin[a] = float(in.number(key));
        } else if (key == "POINT_DATA" || key == "CELL_DATA") {
            association = key == "POINT_DATA" ? "point" : "cell";
            tuples = in.count(key);
        } else if (key == "SCALARS" || key == "VECTORS" || key == "NORMALS" || key == "TENSORS") {
            if (association.empty()) fail(file, key + " before POINT_DATA or CELL_DATA");
            StoredArray a;
            a.info.name = unescape(in.word());
            a.info.type = in.word();
            a.info.association = association;
            a.info.tuples = tuples;
            a.info.components = key == "VECTORS" || key == "NORMALS" ? 3 : key == "TENSORS" ? 9 : 1;
            if (typeInfo(a.info.type).size == 0) fail(file, "array '" + a.info.name + "' has unknown type '" + a.info.type + "'");
            if (key == "SCALARS") {
                const std::string rest = in.line();  // an optional component count
                if (const std::vector<double> n = numbersIn(rest); !n.empty()) {
                    if (!(n[0] >= 1 && n[0] <= 4)) fail(file, "SCALARS '" + a.info.name + "' of " + rest + " components (1 to 4)");
                    a.info.components = uint32_t(n[0]);
                }
                if (in.word() != "LOOKUP_TABLE") fail(file, "SCALARS '" + a.info.name + "' without its LOOKUP_TABLE line");
                in.word();
            }
            if (grid.activeScalars.empty() && key == "SCALARS" && association == "point") grid.activeScalars = a.info.name;
            in.data(a, binary, a.info.tuples * a.info.components);
            grid.arrays.push_back(std::move(a));
        } else if (key == "FIELD") {
            in.word();  // the field's name
            const uint64_t arrays = in.count("FIELD array count");
            if (association.empty()) association = "point";  // a FIELD at the data set's level: kept as point data
            for (uint64_t i = 0; i < arrays; ++i) {
                StoredArray a;
                a.info.name = unescape(in.word());
                a.info.components = uint32_t(std::min<uint64_t>(in.count("FIELD components"), 1u << 20));
                a.info.tuples = in.count("FIELD tuples");
                a.info.type = in.word();
                a.info.association = association;
                if (typeInfo(a.info.type).size == 0) fail(file, "FIELD array '" + a.info.name + "' has unknown type '" + a.info.type + "'");
                if (a.info.components * a.info.tuples > kMaxVoxels * 9) fail(file, "FIELD array '" + a.info.name + "' is too large");
                in.data(a, binary, a.info.components * a.info.tuples);
                grid.arrays.push_back(std::move(a));
            }
        } else if (key == "LOOKUP_TABLE") {  // a colour table: read past it
            StoredArray table;
            table.info.name = in.word();
            table.info.type = binary ? "unsigned_char" : "float";
            in.data(table, binary, in.count("LOOKUP_TABLE size") * 4);
        } else if (key == "METADATA") {
            in.skipMetadata();
        } else {
            fail(file, "unknown keyword '" + key + "'");
        }
    }
    if (!haveDims) fail(file, "no DIMENSIONS");
    return grid;
}

ImageGrid readImage(const std::filesystem::path& file) {
    const std::string bytes = readRegularFile(file, kMaxVtkFileBytes, "");
    std::string extension = file.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    try {
        return extension == ".vti" ? readXmlImage(file, bytes) : readLegacyImage(file, bytes);
    } catch (const std::bad_alloc&) {
        fail(file, "too large to read");
    }
}

}  // namespace

bool isVtkImageFile(const std::filesystem::path& file) {
    std::string extension = file.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return extension == ".vti" || extension == ".vtk";
}

std::vector<VtkArrayInfo> listVtkArrays(const std::filesystem::path& file) {
    std::vector<VtkArrayInfo> list;
    for (const StoredArray& a : readImage(file).arrays) list.push_back(a.info);
    return list;
}

VolumeData readVtkImageVolume(const std::filesystem::path& file, const VtkFieldChoice& choice, VolumeSlab slab) {
    ImageGrid grid = readImage(file);
    const uint64_t points = uint64_t(grid.dims.x) * grid.dims.y * grid.dims.z;
    if (points > kMaxVoxels) fail(file, std::to_string(points) + " samples is more than the 2^31 Ripple reads");
    const std::string wanted = !choice.name.empty() ? choice.name : grid.activeScalars;
    const StoredArray* chosen = nullptr;
    for (const StoredArray& a : grid.arrays)
        if (a.info.association == "point" && (wanted.empty() || a.info.name == wanted)) {
            chosen = &a;
            break;
        }
    if (!chosen) {
        std::string names;
        for (const StoredArray& a : grid.arrays) names += (names.empty() ? "" : ", ") + a.info.association + " '" + a.info.name + "'";
        fail(file, (wanted.empty() ? std::string("no point array") : "no point array '" + wanted + "'") +
                       " (arrays: " + (names.empty() ? "none" : names) + ")");
    }
    if (chosen->info.tuples != points)
        fail(file, "array '" + chosen->info.name + "' has " + std::to_string(chosen->info.tuples) + " tuples for " +
                       std::to_string(points) + " points");
    if (choice.component >= int(chosen->info.components))
        fail(file, "array '" + chosen->info.name + "' has " + std::to_string(chosen->info.components) + " components; component " +
                       std::to_string(choice.component) + " asked for");
    const std::vector<double> all = values(file, *chosen);
    const uint32_t c = chosen->info.components;
    // The slab's sample planes (the same split as the raw and NRRD readers: each slab keeps its cells' planes).
    const uint64_t cellsZ = grid.dims.z - 1;
    if (slab.count == 0 || slab.index >= slab.count || cellsZ < slab.count)
        fail(file, std::to_string(grid.dims.z) + " sample planes along z cannot be split into " +
                       std::to_string(slab.count) + " slabs (each needs one cell)");
    const uint32_t zFirst = uint32_t(cellsZ * slab.index / slab.count);
    const uint32_t zLast = uint32_t(cellsZ * (slab.index + 1) / slab.count);
    VolumeData out;
    out.wholeDims = grid.dims;
    out.dims = glm::uvec3(grid.dims.x, grid.dims.y, zLast - zFirst + 1);
    out.zFirst = zFirst;
    out.origin = grid.origin;
    out.spacing = grid.spacing;
    for (int a = 0; a < 3; ++a)
        if (!(out.spacing[a] > 0.0f && std::isfinite(out.spacing[a]))) fail(file, "its spacing must be positive and finite");
    const uint64_t plane = uint64_t(grid.dims.x) * grid.dims.y;
    out.values.resize(plane * out.dims.z);
    uint64_t nonFinite = 0;
    for (uint64_t i = 0; i < out.values.size(); ++i) {
        const double* tuple = all.data() + (uint64_t(zFirst) * plane + i) * c;
        double v = 0.0;
        if (choice.component >= 0) {
            v = tuple[choice.component];
        } else if (c == 1) {
            v = tuple[0];
        } else {
            for (uint32_t k = 0; k < c; ++k) v += tuple[k] * tuple[k];
            v = std::sqrt(v);
        }
        if (!std::isfinite(v) || std::abs(v) > double(std::numeric_limits<float>::max())) ++nonFinite;
        out.values[i] = float(v);
    }
    if (nonFinite > 0) fail(file, "array '" + chosen->info.name + "' has " + std::to_string(nonFinite) + " values that are NaN, infinite or beyond float");
    const auto [lo, hi] = std::minmax_element(out.values.begin(), out.values.end());
    out.minValue = *lo;
    out.maxValue = *hi;
    return out;
}

}  // namespace ripple::apps
