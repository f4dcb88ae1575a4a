// What VTK's readers share: arrays as stored (binary in the file's byte order, or parsed ASCII), their
// types, the XML layer (pugixml over the file with its raw appended block cut out; inline base64 and raw
// appended arrays, zlib blocks, UInt32/UInt64 headers) and a cursor over legacy files. Every size read from
// a file is checked against the file before anything is allocated; problems are VolumeErrors naming the file.
#pragma once

#include "io/volume/VolumeFile.h"

#include <pugixml.hpp>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace ripple::apps {

// One array of a VTK file, as --list-fields shows it.
struct VtkArrayInfo {
    std::string name;
    std::string association;  // "point" or "cell"
    uint32_t components = 1;
    std::string type;         // as the file names it: Float32, unsigned_char, ...
    uint64_t tuples = 0;
};

}  // namespace ripple::apps

namespace ripple::apps::vtk {

inline constexpr uint64_t kMaxVtkFileBytes = uint64_t(1) << 34;  // 16 GiB: kMaxVoxels of doubles and some

[[noreturn]] void fail(const std::filesystem::path& file, const std::string& what);

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

struct XmlLayout {
    uint32_t headerBytes = 4;  // UInt32 or UInt64 sizes
    bool bigEndian = false;
    bool zlib = false;
};

TypeInfo typeInfo(std::string name);

// The numbers in a text, as many as parse.
std::vector<double> numbersIn(std::string_view text);

// The array's values as doubles, tuples x components in the file's order; throws when it holds fewer.
std::vector<double> arrayValues(const std::filesystem::path& file, const StoredArray& a);

// A VTK XML file of the given type ("ImageData", "UnstructuredGrid"), parsed; its arrays read on demand.
class XmlDocument {
public:
    XmlDocument(const std::filesystem::path& file, const std::string& text, const std::string& type);
    const pugi::xml_node& root() const { return root_; }
    // A <DataArray> of `tuples` tuples.
    StoredArray array(const pugi::xml_node& node, const std::string& association, uint64_t tuples) const;

private:
    const std::filesystem::path& file_;
    pugi::xml_document doc_;
    pugi::xml_node root_;
    XmlLayout layout_;
    std::string_view appended_;  // the raw appended block, in the caller's text
    bool appendedRaw_ = false;
};

// Legacy names escape spaces and other bytes as %XX.
std::string unescape(const std::string& name);

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
        line();  // the rest of the METADATA line
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

// A legacy file's first lines: the version, the title, ASCII or BINARY, and the DATASET keyword.
struct LegacyHeader {
    double version = 0;
    bool binary = false;
    std::string dataset;
};
LegacyHeader readLegacyHeader(LegacyReader& in, const std::filesystem::path& file);

// The POINT_DATA and CELL_DATA sections of a legacy file (SCALARS, VECTORS, NORMALS, TENSORS, FIELD,
// colour tables, 5.1's METADATA), whatever the data set.
class LegacyAttributes {
public:
    LegacyAttributes(LegacyReader& in, const std::filesystem::path& file, bool binary) : in_(in), file_(file), binary_(binary) {}
    // Reads the section `key` opens; false when `key` is not one of these.
    bool take(const std::string& key);

    std::vector<StoredArray> arrays;
    std::string activeScalars;  // the first point SCALARS

private:
    LegacyReader& in_;
    const std::filesystem::path& file_;
    bool binary_;
    std::string association_;
    uint64_t tuples_ = 0;
};

}  // namespace ripple::apps::vtk
