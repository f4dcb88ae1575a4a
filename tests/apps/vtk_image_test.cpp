// The VTK image-data reader (io/vtk/VtkImageFile): .vti files written here in every encoding the reader
// takes (ascii, inline base64, raw appended; zlib; UInt32 and UInt64 headers; both byte orders) and legacy
// .vtk files (ASCII, big-endian BINARY, version 1.0's blank lines and ASPECT_RATIO, FIELD blocks, vectors)
// read back value for value; hostile files refused by name; the shared sample files against what they declare.
#include "io/vtk/VtkImageFile.h"
#include "tests/apps/TestFiles.h"

#include <doctest/doctest.h>
#include <zlib.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

using namespace ripple::apps;
using namespace ripple::test;

namespace {

constexpr uint32_t kX = 4, kY = 3, kZ = 5;

// The test field: distinct at every sample, exact in float and int16.
float fieldAt(uint32_t x, uint32_t y, uint32_t z) { return float(x) + 10.0f * float(y) + 100.0f * float(z) - 50.0f; }

std::vector<float> fieldValues() {
    std::vector<float> v;
    for (uint32_t z = 0; z < kZ; ++z)
        for (uint32_t y = 0; y < kY; ++y)
            for (uint32_t x = 0; x < kX; ++x) v.push_back(fieldAt(x, y, z));
    return v;
}

template <typename T>
std::string bytesOf(const std::vector<T>& values, bool bigEndian) {
    std::string out(values.size() * sizeof(T), '\0');
    std::memcpy(out.data(), values.data(), out.size());
    if (bigEndian != (std::endian::native == std::endian::big))
        for (size_t i = 0; i < out.size(); i += sizeof(T)) std::reverse(out.begin() + long(i), out.begin() + long(i + sizeof(T)));
    return out;
}

std::string word(uint64_t value, uint32_t bytes, bool bigEndian) {
    return bytes == 8 ? bytesOf(std::vector<uint64_t>{value}, bigEndian) : bytesOf(std::vector<uint32_t>{uint32_t(value)}, bigEndian);
}

std::string base64(const std::string& bytes) {
    static const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (size_t i = 0; i < bytes.size(); i += 3) {
        const uint32_t b0 = uint8_t(bytes[i]), b1 = i + 1 < bytes.size() ? uint8_t(bytes[i + 1]) : 0,
                       b2 = i + 2 < bytes.size() ? uint8_t(bytes[i + 2]) : 0;
        const uint32_t w = b0 << 16 | b1 << 8 | b2;
        out += digits[w >> 18];
        out += digits[(w >> 12) & 63];
        out += i + 1 < bytes.size() ? digits[(w >> 6) & 63] : '=';
        out += i + 2 < bytes.size() ? digits[w & 63] : '=';
    }
    return out;
}

// VTK's zlib layout: [blocks, block size, last block size, compressed sizes] then the blocks (of 64 bytes
// here, so that there are several).
std::pair<std::string, std::string> compressed(const std::string& data, uint32_t headerBytes, bool bigEndian) {
    const size_t blockSize = 64;
    const size_t blocks = (data.size() + blockSize - 1) / blockSize;
    std::string header = word(blocks, headerBytes, bigEndian) + word(blockSize, headerBytes, bigEndian) +
                         word(data.size() % blockSize, headerBytes, bigEndian);
    std::string body;
    for (size_t b = 0; b < blocks; ++b) {
        const std::string block = data.substr(b * blockSize, blockSize);
        uLongf size = compressBound(uLong(block.size()));
        std::string out(size, '\0');
        REQUIRE(compress(reinterpret_cast<Bytef*>(out.data()), &size, reinterpret_cast<const Bytef*>(block.data()),
                         uLong(block.size())) == Z_OK);
        out.resize(size);
        header += word(size, headerBytes, bigEndian);
        body += out;
    }
    return {header, body};
}

struct VtiEncoding {
    const char* name;
    std::string format;  // ascii, binary, appended
    bool zlib = false, bigEndian = false;
    uint32_t headerBytes = 4;
};

std::string vtiFile(const VtiEncoding& e) {
    const std::string data = bytesOf(fieldValues(), e.bigEndian);
    std::string inline_, appended;
    if (e.format == "ascii") {
        for (float v : fieldValues()) inline_ += std::to_string(v) + " ";
    } else if (e.zlib) {
        const auto [header, body] = compressed(data, e.headerBytes, e.bigEndian);
        if (e.format == "binary") inline_ = base64(header) + base64(body);
        else appended = header + body;
    } else {
        const std::string sized = word(data.size(), e.headerBytes, e.bigEndian) + data;
        if (e.format == "binary") inline_ = base64(sized);
        else appended = sized;
    }
    std::string xml = "<?xml version=\"1.0\"?>\n<VTKFile type=\"ImageData\" version=\"1.0\" byte_order=\"" +
                      std::string(e.bigEndian ? "BigEndian" : "LittleEndian") + "\" header_type=\"" +
                      (e.headerBytes == 8 ? "UInt64" : "UInt32") + "\"" +
                      (e.zlib ? " compressor=\"vtkZLibDataCompressor\"" : "") + ">\n" +
                      "<ImageData WholeExtent=\"0 3 0 2 0 4\" Origin=\"1 2 3\" Spacing=\"0.5 0.25 2\">\n<Piece Extent=\"0 3 0 2 0 4\">\n" +
                      "<PointData Scalars=\"f\">\n<DataArray type=\"Float32\" Name=\"other\" format=\"ascii\">" +
                      std::string(kX * kY * kZ * 2, ' ') + "</DataArray>\n" +
                      "<DataArray type=\"Float32\" Name=\"f\" format=\"" + e.format + "\"" +
                      (e.format == "appended" ? " offset=\"0\"/>\n" : ">" + inline_ + "</DataArray>\n") +
                      "</PointData>\n</Piece>\n</ImageData>\n";
    if (e.format == "appended") xml += "<AppendedData encoding=\"raw\">\n_" + appended + "\n</AppendedData>\n";
    return xml + "</VTKFile>\n";
}

void checkField(const VolumeData& v) {
    CHECK(v.dims == glm::uvec3(kX, kY, kZ));
    CHECK(v.origin == glm::vec3(1, 2, 3));
    CHECK(v.spacing == glm::vec3(0.5f, 0.25f, 2.0f));
    CHECK(v.values == fieldValues());
    CHECK(v.minValue == fieldAt(0, 0, 0));
    CHECK(v.maxValue == fieldAt(kX - 1, kY - 1, kZ - 1));
}

}  // namespace

TEST_CASE("VTK XML image data in every encoding reads back exactly") {
    TempFolder dir;
    for (const VtiEncoding& e : {VtiEncoding{"ascii", "ascii"}, VtiEncoding{"inline base64", "binary"},
                                 VtiEncoding{"inline base64, zlib, UInt64", "binary", true, false, 8},
                                 VtiEncoding{"appended raw", "appended"},
                                 VtiEncoding{"appended raw, big-endian", "appended", false, true},
                                 VtiEncoding{"appended raw, zlib, big-endian, UInt64", "appended", true, true, 8},
                                 VtiEncoding{"inline base64, zlib", "binary", true}}) {
        CAPTURE(e.name);
        const std::filesystem::path file = writeText(dir / "field.vti", vtiFile(e));
        checkField(readVtkImageVolume(file, {"f"}));
        checkField(readVtkImageVolume(file));  // the active scalars
        const std::vector<VtkArrayInfo> arrays = listVtkArrays(file);
        REQUIRE(arrays.size() == 2);
        CHECK(arrays[1].name == "f");
        CHECK(arrays[1].tuples == kX * kY * kZ);
    }
}

TEST_CASE("legacy VTK structured points: ASCII, big-endian BINARY, version 1.0, FIELD blocks, vectors") {
    TempFolder dir;
    const std::vector<float> f = fieldValues();
    std::vector<int16_t> ints(f.begin(), f.end());
    std::vector<float> vectors;
    for (float v : f) vectors.insert(vectors.end(), {3.0f * v, 4.0f * v, 0.0f});
    const std::string head = "DATASET STRUCTURED_POINTS\nDIMENSIONS 4 3 5\n";
    std::string ascii = "# vtk DataFile Version 3.0\ntest\nASCII\n" + head + "SPACING 0.5 0.25 2\nORIGIN 1 2 3\n"
                        "POINT_DATA 60\nFIELD extra 1\nnoise%20level 1 60 float\n";
    for (size_t i = 0; i < f.size(); ++i) ascii += "7 ";
    ascii += "\nSCALARS f short 1\nLOOKUP_TABLE default\n";
    for (int16_t v : ints) ascii += std::to_string(v) + "\n";
    ascii += "VECTORS velocity float\n";
    for (float v : vectors) ascii += std::to_string(v) + " ";
    // Version 1.0 as VTK wrote it: blank lines, ASPECT_RATIO for the spacing, big-endian binary.
    const std::string binary = "# vtk DataFile Version 1.0\ntest\n\nBINARY\n\n" + head + "ASPECT_RATIO 0.5 0.25 2\nORIGIN 1 2 3\n\n"
                               "POINT_DATA 60\nSCALARS f short\nLOOKUP_TABLE default\n" + bytesOf(ints, true) +
                               "\nVECTORS velocity float\n" + bytesOf(vectors, true) + "\n";
    for (const auto& [name, text] : {std::pair{"ascii.vtk", ascii}, std::pair{"binary.vtk", binary}}) {
        CAPTURE(name);
        const std::filesystem::path file = writeText(dir / name, text);
        checkField(readVtkImageVolume(file, {"f"}));
        checkField(readVtkImageVolume(file));  // the first SCALARS
        const VolumeData speed = readVtkImageVolume(file, {"velocity"});
        const VolumeData second = readVtkImageVolume(file, {"velocity", 1});
        for (size_t i = 0; i < f.size(); ++i) {
            CHECK(speed.values[i] == doctest::Approx(5.0 * std::abs(f[i])));  // |(3v, 4v, 0)|
            CHECK(second.values[i] == 4.0f * f[i]);
        }
    }
    const std::vector<VtkArrayInfo> arrays = listVtkArrays(dir / "ascii.vtk");
    REQUIRE(arrays.size() == 3);
    CHECK(arrays[0].name == "noise level");  // %20 unescaped
}

TEST_CASE("z-slabs of a VTK field share their boundary plane") {
    TempFolder dir;
    const std::filesystem::path file = writeText(dir / "field.vti", vtiFile({"zlib", "binary", true}));
    const VolumeData first = readVtkImageVolume(file, {}, {0, 2}), second = readVtkImageVolume(file, {}, {1, 2});
    CHECK(first.zFirst == 0);
    CHECK(second.zFirst == first.zFirst + first.dims.z - 1);
    CHECK(first.dims.z + second.dims.z - 1 == kZ);
    CHECK(second.values.front() == fieldAt(0, 0, second.zFirst));
}

TEST_CASE("hostile VTK files are refused by name") {
    TempFolder dir;
    const std::string good = vtiFile({"zlib", "binary", true});
    struct Case {
        std::string name, text, expected;
    };
    std::string truncatedAppended = vtiFile({"appended", "appended"});
    truncatedAppended.erase(truncatedAppended.find("\n_") + 22, 100);
    std::string badBlocks = vtiFile({"appended zlib", "appended", true});
    badBlocks[badBlocks.find("\n_") + 2] = '\x7f';  // the block count: 127 blocks of data that is not there
    for (const Case& c : {Case{"not xml.vti", "this is not XML", "not VTK XML"},
                          Case{"grid.vti", "<VTKFile type=\"UnstructuredGrid\"/>", "a VTK UnstructuredGrid file"},
                          Case{"extent.vti", std::string(good).replace(good.find("0 3 0 2 0 4"), 11, "0 3 0 2"), "WholeExtent"},
                          Case{"type.vti", std::string(good).replace(good.find("type=\"Float32\" Name=\"f\""), 14, "type=\"Float99\""), "unknown type"},
                          Case{"base64.vti", std::string(good).replace(good.find("format=\"binary\">") + 16, 4, "!!!!"), "not base64"},
                          Case{"short.vti", truncatedAppended, "run past"},
                          Case{"blocks.vti", badBlocks, "blocks"},
                          Case{"short.vtk", "# vtk DataFile Version 3.0\nt\nBINARY\nDATASET STRUCTURED_POINTS\nDIMENSIONS 4 3 5\n"
                                            "POINT_DATA 60\nSCALARS f float\nLOOKUP_TABLE default\n" + std::string(17, '\0'),
                               "needs 240 bytes"},
                          Case{"dataset.vtk", "# vtk DataFile Version 5.1\nt\nASCII\nDATASET POLYDATA\n", "a legacy POLYDATA data set"},
                          Case{"nan.vtk", "# vtk DataFile Version 3.0\nt\nASCII\nDATASET STRUCTURED_POINTS\nDIMENSIONS 1 1 2\n"
                                          "POINT_DATA 2\nSCALARS f float\nLOOKUP_TABLE default\n1 nan\n", "NaN"}}) {
        CAPTURE(c.name);
        const std::filesystem::path file = writeText(dir / c.name, c.text);
        CHECK_THROWS_WITH_AS(readVtkImageVolume(file), doctest::Contains(c.expected.c_str()), VolumeError);
    }
}

TEST_CASE("the shared VTK image files read as they declare") {
    const std::filesystem::path data = RIPPLE_DATA_DIR;
    if (!std::filesystem::exists(data / "vtk" / "hydrogen.vti")) {
        MESSAGE("skipped: " << (data / "vtk").string() << " is absent");
        return;
    }
    // hydrogen.vti declares WholeExtent 0 63 (three times) and, on its array, RangeMin 0 and RangeMax 1.
    const VolumeData hydrogen = readVtkImageVolume(data / "vtk" / "hydrogen.vti");
    CHECK(hydrogen.dims == glm::uvec3(64));
    CHECK(hydrogen.minValue == doctest::Approx(0.0).epsilon(1e-6));
    CHECK(hydrogen.maxValue == doctest::Approx(1.0).epsilon(1e-6));
    // ironProt.vtk declares DIMENSIONS 68 68 68, POINT_DATA 314432 and unsigned_char scalars.
    const std::vector<VtkArrayInfo> arrays = listVtkArrays(data / "vtk" / "ironProt.vtk");
    REQUIRE(arrays.size() == 1);
    CHECK(arrays[0].tuples == 314432);
    CHECK(arrays[0].type == "unsigned_char");
    const VolumeData iron = readVtkImageVolume(data / "vtk" / "ironProt.vtk");
    CHECK(iron.dims == glm::uvec3(68));
    CHECK(iron.minValue >= 0.0f);
    CHECK(iron.maxValue <= 255.0f);
    CHECK(iron.maxValue > iron.minValue);
}
