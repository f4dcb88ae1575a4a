// The array machinery VTK's readers share (see VtkArrays.h).
#include "io/vtk/VtkArrays.h"

#include <zlib.h>

#include <algorithm>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>
#include <sstream>

namespace ripple::apps::vtk {

void fail(const std::filesystem::path& file, const std::string& what) { throw VolumeError(file.string() + ": " + what); }

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

std::vector<double> numbersIn(std::string_view text) {
    std::vector<double> out;
    std::istringstream in{std::string(text)};
    for (double v; in >> v;) out.push_back(v);
    return out;
}

namespace {

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

// Header words are read as integers, not through element()'s double: a hostile 2^64 - 1 does not fit back.
uint64_t headerWord(const std::string& bytes, size_t index, const XmlLayout& layout) {
    unsigned char b[8] = {};
    std::memcpy(b, bytes.data() + index * layout.headerBytes, layout.headerBytes);
    if (layout.bigEndian != (std::endian::native == std::endian::big)) std::reverse(b, b + layout.headerBytes);
    if (layout.headerBytes == 4) {
        uint32_t v;
        std::memcpy(&v, b, 4);
        return v;
    }
    uint64_t v;
    std::memcpy(&v, b, 8);
    return v;
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
    // zlib inflates at most 1032:1: a header that claims more than the blocks can hold is refused before the
    // allocation, not after it (a few bytes claiming gigabytes).
    uint64_t compressedTotal = 0;
    for (uint64_t b = 0; b < blocks; ++b) {
        const uint64_t compressed = headerWord(header, 3 + b, layout);
        if (compressed > data.size()) fail(file, what + ": compressed block " + std::to_string(b) + " runs past the data");
        compressedTotal += compressed;  // at most 2^32 blocks of at most the data's size: no overflow
    }
    if (compressedTotal > data.size() || total > compressedTotal * 1032 + 64 * blocks)
        fail(file, what + ": its compression header claims " + std::to_string(total) + " bytes from " +
                       std::to_string(compressedTotal) + " compressed bytes (" + std::to_string(data.size()) + " present)");
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

}  // namespace

// The array's values as doubles, tuples x components, in the file's order.
std::vector<double> arrayValues(const std::filesystem::path& file, const StoredArray& a) {
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

XmlDocument::XmlDocument(const std::filesystem::path& file, const std::string& text, const std::string& type)
    : file_(file) {
    // The raw appended block is bytes, not XML: cut out before parsing, kept for the arrays.
    std::string xml = text;
    if (const size_t open = text.find("<AppendedData"); open != std::string::npos) {
        const size_t tagEnd = text.find('>', open);
        const size_t close = text.rfind("</AppendedData>");
        const size_t underscore = tagEnd == std::string::npos ? std::string::npos : text.find('_', tagEnd);
        if (tagEnd == std::string::npos || close == std::string::npos || underscore == std::string::npos || underscore > close)
            fail(file, "malformed <AppendedData> (no '_' before </AppendedData>)");
        appendedRaw_ = text.substr(open, tagEnd - open).find("\"raw\"") != std::string::npos;
        appended_ = std::string_view(text).substr(underscore + 1, close - underscore - 1);
        xml = text.substr(0, tagEnd + 1) + text.substr(close);
    }
    const pugi::xml_parse_result parsed = doc_.load_buffer(xml.data(), xml.size());
    if (!parsed) fail(file, std::string("not VTK XML: ") + parsed.description() + " at byte " + std::to_string(parsed.offset));
    root_ = doc_.child("VTKFile");
    if (!root_) fail(file, "not VTK XML: no <VTKFile> element");
    const std::string fileType = root_.attribute("type").value();
    if (fileType != type)
        fail(file, "a VTK " + (fileType.empty() ? std::string("file of no type") : fileType) + " file; Ripple reads " + type + " here");
    const std::string order = root_.attribute("byte_order").as_string("LittleEndian");
    if (order != "LittleEndian" && order != "BigEndian") fail(file, "unknown byte_order '" + order + "'");
    layout_.bigEndian = order == "BigEndian";
    const std::string headerType = root_.attribute("header_type").as_string("UInt32");
    if (headerType != "UInt32" && headerType != "UInt64") fail(file, "unknown header_type '" + headerType + "' (UInt32 or UInt64)");
    layout_.headerBytes = headerType == "UInt64" ? 8 : 4;
    const std::string compressor = root_.attribute("compressor").value();
    if (!compressor.empty() && compressor != "vtkZLibDataCompressor")
        fail(file, "compressor " + compressor + " is not supported (vtkZLibDataCompressor is)");
    layout_.zlib = !compressor.empty();
}

StoredArray XmlDocument::array(const pugi::xml_node& node, const std::string& association, uint64_t tuples) const {
    StoredArray a;
    a.info.name = node.attribute("Name").value();
    a.info.association = association;
    a.info.type = node.attribute("type").value();
    a.info.components = node.attribute("NumberOfComponents").as_uint(1);
    a.info.tuples = tuples;
    a.bigEndian = layout_.bigEndian;
    const std::string what = "array '" + a.info.name + "'";
    if (typeInfo(a.info.type).size == 0) fail(file_, what + " has unknown type '" + a.info.type + "'");
    if (a.info.components < 1 || a.info.components > 9)
        fail(file_, what + " has " + std::to_string(a.info.components) + " components (1 to 9)");
    const std::string format = node.attribute("format").value();
    if (format == "ascii") {
        a.numbers = numbersIn(node.child_value());
    } else if (format == "binary" || format == "appended") {
        std::optional<std::string_view> raw;
        std::string base64;
        if (format == "appended") {
            if (!appendedRaw_) fail(file_, what + ": appended data in base64 is not supported (raw or inline binary is)");
            const uint64_t offset = node.attribute("offset").as_ullong(std::numeric_limits<uint64_t>::max());
            if (offset > appended_.size()) fail(file_, what + ": offset " + std::to_string(offset) + " is past the appended data");
            raw = appended_.substr(offset);
        } else {
            for (const char c : std::string_view(node.child_value()))
                if (!std::isspace(static_cast<unsigned char>(c))) base64 += c;
        }
        a.bytes = xmlArrayBytes(file_, layout_, base64, raw, what);
    } else {
        fail(file_, what + " has unknown format '" + format + "'");
    }
    return a;
}

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

LegacyHeader readLegacyHeader(LegacyReader& in, const std::filesystem::path& file) {
    const std::string versionLine = in.line();
    const std::string prefix = "# vtk DataFile Version";
    if (versionLine.rfind(prefix, 0) != 0) fail(file, "not a VTK file (no '# vtk DataFile Version' line)");
    LegacyHeader header;
    header.version = std::atof(versionLine.c_str() + prefix.size());
    in.line();  // the title
    std::string format;
    while (format.find_first_not_of(" \t") == std::string::npos) format = in.line();  // version 1.0 leaves blank lines
    format.erase(std::remove_if(format.begin(), format.end(), [](unsigned char c) { return std::isspace(c); }), format.end());
    if (format != "ASCII" && format != "BINARY") fail(file, "the third line is '" + format + "', not ASCII or BINARY");
    header.binary = format == "BINARY";
    if (in.word() != "DATASET") fail(file, "no DATASET line");
    header.dataset = in.word();
    return header;
}

bool LegacyAttributes::take(const std::string& key) {
    if (key == "POINT_DATA" || key == "CELL_DATA") {
        association_ = key == "POINT_DATA" ? "point" : "cell";
        tuples_ = in_.count(key);
    } else if (key == "SCALARS" || key == "VECTORS" || key == "NORMALS" || key == "TENSORS") {
        if (association_.empty()) fail(file_, key + " before POINT_DATA or CELL_DATA");
        StoredArray a;
        a.info.name = unescape(in_.word());
        a.info.type = in_.word();
        a.info.association = association_;
        a.info.tuples = tuples_;
        a.info.components = key == "VECTORS" || key == "NORMALS" ? 3 : key == "TENSORS" ? 9 : 1;
        if (typeInfo(a.info.type).size == 0) fail(file_, "array '" + a.info.name + "' has unknown type '" + a.info.type + "'");
        if (key == "SCALARS") {
            const std::string rest = in_.line();  // an optional component count
            if (const std::vector<double> n = numbersIn(rest); !n.empty()) {
                if (!(n[0] >= 1 && n[0] <= 4)) fail(file_, "SCALARS '" + a.info.name + "' of " + rest + " components (1 to 4)");
                a.info.components = uint32_t(n[0]);
            }
            if (in_.word() != "LOOKUP_TABLE") fail(file_, "SCALARS '" + a.info.name + "' without its LOOKUP_TABLE line");
            in_.word();
        }
        if (activeScalars.empty() && key == "SCALARS" && association_ == "point") activeScalars = a.info.name;
        in_.data(a, binary_, a.info.tuples * a.info.components);
        arrays.push_back(std::move(a));
    } else if (key == "FIELD") {
        in_.word();  // the field's name
        const uint64_t count = in_.count("FIELD array count");
        if (association_.empty()) association_ = "point";  // a FIELD at the data set's level: kept as point data
        for (uint64_t i = 0; i < count; ++i) {
            StoredArray a;
            a.info.name = unescape(in_.word());
            a.info.components = uint32_t(std::min<uint64_t>(in_.count("FIELD components"), 1u << 20));
            a.info.tuples = in_.count("FIELD tuples");
            a.info.type = in_.word();
            a.info.association = association_;
            if (typeInfo(a.info.type).size == 0) fail(file_, "FIELD array '" + a.info.name + "' has unknown type '" + a.info.type + "'");
            if (a.info.components * a.info.tuples > kMaxVoxels * 9) fail(file_, "FIELD array '" + a.info.name + "' is too large");
            in_.data(a, binary_, a.info.components * a.info.tuples);
            arrays.push_back(std::move(a));
        }
    } else if (key == "LOOKUP_TABLE") {  // a colour table: read past it
        StoredArray table;
        table.info.name = in_.word();
        table.info.type = binary_ ? "unsigned_char" : "float";
        in_.data(table, binary_, in_.count("LOOKUP_TABLE size") * 4);
    } else if (key == "METADATA") {
        in_.skipMetadata();
    } else {
        return false;
    }
    return true;
}

}  // namespace ripple::apps::vtk
