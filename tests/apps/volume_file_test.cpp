// The volume file reader (io/volume/VolumeFile): raw and NRRD files written here, read back value for value,
// and every malformed case refused with a message naming the file and the problem.
#include "io/volume/VolumeFile.h"
#include "tests/apps/TestFiles.h"

#include <doctest/doctest.h>
#include <zlib.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <string>

using namespace ripple::test;
using ripple::apps::RawLayout;
using ripple::apps::VolumeData;
using ripple::apps::VolumeError;

namespace {

template <typename T>
std::vector<uint8_t> bytesOf(const std::vector<T>& values) {
    std::vector<uint8_t> out(values.size() * sizeof(T));
    std::memcpy(out.data(), values.data(), out.size());
    return out;
}

// An NRRD header (lines joined by newlines, a blank line after) followed by `data`.
std::vector<uint8_t> nrrd(const std::string& header, const std::vector<uint8_t>& data) {
    std::vector<uint8_t> out(header.begin(), header.end());
    out.push_back('\n');
    out.push_back('\n');
    out.insert(out.end(), data.begin(), data.end());
    return out;
}

// The message of the VolumeError `read` throws; fails the test when it throws nothing.
template <typename Read>
std::string errorOf(Read read) {
    try {
        read();
    } catch (const VolumeError& e) {
        return e.what();
    }
    FAIL("no error thrown");
    return "";
}

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// `data` as a gzip stream (what NRRD's "encoding: gzip" holds).
std::vector<uint8_t> gzipped(const std::vector<uint8_t>& data) {
    z_stream z{};
    REQUIRE(deflateInit2(&z, Z_BEST_SPEED, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY) == Z_OK);  // 16: gzip header
    std::vector<uint8_t> out(deflateBound(&z, uLong(data.size())));
    z.next_in = const_cast<Bytef*>(data.data());
    z.avail_in = uInt(data.size());
    z.next_out = out.data();
    z.avail_out = uInt(out.size());
    REQUIRE(deflate(&z, Z_FINISH) == Z_STREAM_END);
    out.resize(z.total_out);
    deflateEnd(&z);
    return out;
}

}  // namespace

TEST_CASE("raw volumes read back exactly, x fastest, converted but not normalised") {
    TempFolder dir;
    SUBCASE("uint8, 3x2x2, dims as X,Y,Z") {
        std::vector<uint8_t> v(12);
        for (size_t i = 0; i < v.size(); ++i) v[i] = uint8_t(i * 20);
        v[11] = 255;
        const VolumeData d = ripple::apps::readRawVolume(writeBytes(dir / "a.raw", v), {"3,2,2", "uint8", ""});
        CHECK(d.dims == glm::uvec3(3, 2, 2));
        REQUIRE(d.values.size() == 12);
        for (size_t i = 0; i < 12; ++i) CHECK(d.values[i] == float(v[i]));
        CHECK(d.minValue == 0.0f);
        CHECK(d.maxValue == 255.0f);
        CHECK(d.spacing == glm::vec3(1.0f));
    }
    SUBCASE("uint16 and int16, dims as XxYxZ, spacing given") {
        const std::vector<uint16_t> u{0, 1, 65535, 300, 7, 8, 9, 10};
        const VolumeData d = ripple::apps::readRawVolume(writeBytes(dir / "u.raw", bytesOf(u)), {"2x2x2", "uint16", "0.5,1,2"});
        CHECK(d.dims == glm::uvec3(2));
        for (size_t i = 0; i < u.size(); ++i) CHECK(d.values[i] == float(u[i]));
        CHECK(d.spacing == glm::vec3(0.5f, 1.0f, 2.0f));
        const std::vector<int16_t> s{-32768, -1, 0, 1, 2, 3, 4, 32767};
        const VolumeData e = ripple::apps::readRawVolume(writeBytes(dir / "s.raw", bytesOf(s)), {"2x2x2", "int16", ""});
        for (size_t i = 0; i < s.size(); ++i) CHECK(e.values[i] == float(s[i]));
        CHECK(e.minValue == -32768.0f);
    }
    SUBCASE("float32 with trailing bytes, float64, int8") {
        std::vector<float> f(2 * 3 * 2);
        for (size_t i = 0; i < f.size(); ++i) f[i] = 0.25f * float(i) - 1.0f;
        std::vector<uint8_t> bytes = bytesOf(f);
        for (uint8_t extra : {1, 2, 3}) bytes.push_back(extra);  // longer than the field: ignored
        const VolumeData d = ripple::apps::readRawVolume(writeBytes(dir / "f.raw", bytes), {"2,3,2", "float32", ""});
        CHECK(d.dims == glm::uvec3(2, 3, 2));
        for (size_t i = 0; i < f.size(); ++i) CHECK(d.values[i] == f[i]);
        const std::vector<double> g{1e-3, -2.5, 3.0, 4.0, 5.0, 6.0, 7.0, 1e6};
        const VolumeData e = ripple::apps::readRawVolume(writeBytes(dir / "g.raw", bytesOf(g)), {"2,2,2", "float64", ""});
        for (size_t i = 0; i < g.size(); ++i) CHECK(e.values[i] == float(g[i]));
        const std::vector<int8_t> c{-128, -1, 0, 1, 2, 3, 4, 127};
        const VolumeData h = ripple::apps::readRawVolume(writeBytes(dir / "c.raw", bytesOf(c)), {"2,2,2", "int8", ""});
        for (size_t i = 0; i < c.size(); ++i) CHECK(h.values[i] == float(c[i]));
    }
}

TEST_CASE("NRRD volumes: attached and detached data, spacings, directions, origin, endianness") {
    TempFolder dir;
    const std::vector<uint16_t> u{0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 1000};  // 2x3x2
    SUBCASE("attached, spacings, comments and key/value pairs skipped") {
        const auto file = writeBytes(dir / "a.nrrd", nrrd("NRRD0004\n# a comment\ntype: unsigned short\ndimension: 3\n"
                                                          "sizes: 2 3 2\nendian: little\nencoding: raw\n"
                                                          "spacings: 0.5 0.25 2\nspace origin: (1,-2,3.5)\n"
                                                          "creator:=test",
                                                          bytesOf(u)));
        const VolumeData d = ripple::apps::readNrrdVolume(file);
        CHECK(d.dims == glm::uvec3(2, 3, 2));
        for (size_t i = 0; i < u.size(); ++i) CHECK(d.values[i] == float(u[i]));
        CHECK(d.spacing == glm::vec3(0.5f, 0.25f, 2.0f));
        CHECK(d.origin == glm::vec3(1.0f, -2.0f, 3.5f));
        CHECK(d.maxValue == 1000.0f);
    }
    SUBCASE("big-endian, axis-aligned space directions, CRLF lines") {
        std::vector<uint8_t> big;
        for (uint16_t x : u) big.insert(big.end(), {uint8_t(x >> 8), uint8_t(x & 0xFF)});
        const std::string text = "NRRD0005\r\ntype: uint16\r\ndimension: 3\r\nsizes: 2 3 2\r\nendian: big\r\n"
                                 "encoding: raw\r\nspace: left-posterior-superior\r\n"
                                 "space directions: (0.5,0,0) (0,1.5,0) (0,0,3)\r\n\r\n";
        const std::string all = text + std::string(big.begin(), big.end());
        const auto file = writeBytes(dir / "b.nrrd", std::vector<uint8_t>(all.begin(), all.end()));
        const VolumeData d = ripple::apps::readNrrdVolume(file);
        for (size_t i = 0; i < u.size(); ++i) CHECK(d.values[i] == float(u[i]));
        CHECK(d.spacing == glm::vec3(0.5f, 1.5f, 3.0f));
    }
    SUBCASE("gzip-encoded, big-endian, with a byte skip of the decompressed data") {
        std::vector<uint8_t> big = {0xAB, 0xCD, 0xEF};  // three bytes the skip passes over
        for (uint16_t x : u) big.insert(big.end(), {uint8_t(x >> 8), uint8_t(x & 0xFF)});
        const auto file = writeBytes(dir / "g.nrrd", nrrd("NRRD0004\ntype: uint16\ndimension: 3\nsizes: 2 2 3\n"
                                                          "endian: big\nencoding: gzip\nbyte skip: 3",
                                                          gzipped(big)));
        const VolumeData d = ripple::apps::readNrrdVolume(file);
        CHECK(d.dims == glm::uvec3(2, 2, 3));
        for (size_t i = 0; i < u.size(); ++i) CHECK(d.values[i] == float(u[i]));
        // The second of two z-slabs (planes 1 and 2 of 0..2; plane 1 shared with the first) from the stream.
        const VolumeData slab = ripple::apps::readNrrdVolume(file, {1, 2});
        CHECK(slab.zFirst == 1);
        REQUIRE(slab.values.size() == 8);
        for (size_t i = 0; i < 8; ++i) CHECK(slab.values[i] == float(u[4 + i]));
    }
    SUBCASE("detached .nhdr with gzip data") {
        writeBytes(dir / "v.raw.gz", gzipped(bytesOf(u)));
        const auto file = writeText(dir / "v.nhdr", "NRRD0004\ntype: uint16\ndimension: 3\nsizes: 2 3 2\nendian: little\n"
                                                    "encoding: gz\ndata file: v.raw.gz\n");
        const VolumeData d = ripple::apps::readNrrdVolume(file);
        for (size_t i = 0; i < u.size(); ++i) CHECK(d.values[i] == float(u[i]));
    }
    SUBCASE("detached .nhdr with its data file in a subfolder") {
        std::filesystem::create_directory(dir / "data");
        writeBytes(dir / "data" / "v.raw", bytesOf(u));
        const auto file = writeText(dir / "v.nhdr", "NRRD0004\ntype: uint16\ndimension: 3\nsizes: 2 3 2\nendian: little\n"
                                                    "encoding: raw\ndata file: data/v.raw\n");
        const VolumeData d = ripple::apps::readNrrdVolume(file);
        for (size_t i = 0; i < u.size(); ++i) CHECK(d.values[i] == float(u[i]));
    }
}

// Data-parallel reads: 5 sample planes (4 cells) in 2 slabs are planes 0-2 and 2-4, sharing plane 2; 3 slabs
// deal the cells 1, 1, 2; more slabs than cells is refused.
TEST_CASE("z-slabs of a volume file hold their planes and share one with the next") {
    TempFolder dir;
    std::vector<uint8_t> v(3 * 2 * 5);
    for (size_t i = 0; i < v.size(); ++i) v[i] = uint8_t(i);
    const auto file = writeBytes(dir / "slabs.raw", v);
    const RawLayout layout{"3,2,5", "uint8", ""};
    const auto check = [&](uint32_t index, uint32_t count, uint32_t zFirst, uint32_t planes) {
        CAPTURE(index);
        CAPTURE(count);
        const VolumeData d = ripple::apps::readRawVolume(file, layout, {index, count});
        CHECK(d.wholeDims == glm::uvec3(3, 2, 5));
        CHECK(d.zFirst == zFirst);
        CHECK(d.dims == glm::uvec3(3, 2, planes));
        REQUIRE(d.values.size() == size_t(6 * planes));
        for (size_t i = 0; i < d.values.size(); ++i) CHECK(d.values[i] == float(6 * zFirst + i));
        CHECK(d.minValue == float(6 * zFirst));
    };
    check(0, 1, 0, 5);
    check(0, 2, 0, 3);
    check(1, 2, 2, 3);
    check(0, 3, 0, 2);
    check(1, 3, 1, 2);
    check(2, 3, 2, 3);
    CHECK(has(errorOf([&] { ripple::apps::readRawVolume(file, layout, {0, 5}); }),
              "its 5 sample planes along z cannot be split into 5 slabs"));
}

TEST_CASE("malformed volume files are refused with the file and the problem named") {
    TempFolder dir;
    const std::vector<uint8_t> eight(8, 7);
    const std::string good = "type: uint8\ndimension: 3\nsizes: 2 2 2\nencoding: raw\n";
    std::string message, expected;
    std::filesystem::path file;
    const auto raw = [&](const std::string& name, const std::vector<uint8_t>& bytes, RawLayout layout) {
        file = writeBytes(dir / name, bytes);
        message = errorOf([&] { ripple::apps::readRawVolume(file, layout); });
    };
    const auto header = [&](const std::string& name, const std::string& text, const std::vector<uint8_t>& bytes) {
        file = writeBytes(dir / name, nrrd(text, bytes));
        message = errorOf([&] { ripple::apps::readNrrdVolume(file); });
    };
    SUBCASE("missing raw file") {
        file = dir / "absent.raw";
        message = errorOf([&] { ripple::apps::readRawVolume(file, {"2,2,2", "uint8", ""}); });
        expected = "absent.raw: no such file";
    }
    SUBCASE("missing NRRD file") {
        file = dir / "absent.nrrd";
        message = errorOf([&] { ripple::apps::readNrrdVolume(file); });
        expected = "absent.nrrd: no such file";
    }
    SUBCASE("folder, not a file") {
        std::filesystem::create_directory(dir / "d.raw");
        file = dir / "d.raw";
        message = errorOf([&] { ripple::apps::readRawVolume(file, {"2,2,2", "uint8", ""}); });
        expected = "is not a regular file";
    }
    SUBCASE("file shorter than the field: both sizes") {
        raw("short.raw", std::vector<uint8_t>(100), {"4,4,4", "uint16", ""});
        expected = "holds 100 bytes of data but 4x4x4 uint16 voxels need 128 bytes";
    }
    SUBCASE("raw file longer than the field: the layout does not match it") {
        raw("long.raw", std::vector<uint8_t>(100), {"4,4,4", "uint8", ""});
        expected = "holds 100 bytes but 4x4x4 uint8 voxels need 64: the dimensions or the type do not match the file";
    }
    SUBCASE("zero dimension") {
        raw("z.raw", eight, {"2,0,2", "uint8", ""});
        expected = "dimensions 2x0x2 include a zero";
    }
    SUBCASE("dimension of one sample") {
        raw("one.raw", eight, {"8,1,1", "uint8", ""});
        expected = "at least 2 samples along each axis";
    }
    SUBCASE("voxel count overflowing 64 bits") {
        raw("o.raw", eight, {"4294967296,4294967296,2", "uint8", ""});
        expected = "the voxel count overflows 64 bits";
    }
    SUBCASE("absurdly many voxels") {
        raw("big.raw", eight, {"2048x2048x1024", "uint8", ""});
        expected = "are 4294967296 voxels, more than the limit of 2147483648 (2^31)";
    }
    SUBCASE("dims that are not three counts") {
        raw("bad.raw", eight, {"2,2,-2", "uint8", ""});
        expected = "--dims '2,2,-2' is not three counts";
    }
    SUBCASE("dims beyond 64 bits") {
        raw("huge.raw", eight, {"2,2,99999999999999999999", "uint8", ""});
        expected = "is not three counts";
    }
    SUBCASE("unknown raw type") {
        raw("t.raw", eight, {"2,2,2", "uint32", ""});
        expected = "unknown voxel type 'uint32' (known: uint8, int8, uint16, int16, float32, float64)";
    }
    SUBCASE("spacing not positive") {
        raw("s.raw", eight, {"2,2,2", "uint8", "1,0,1"});
        expected = "--spacing must be three positive finite numbers";
    }
    SUBCASE("NaN and Inf voxels, counted") {
        std::vector<float> f(8, 1.0f);
        f[2] = std::numeric_limits<float>::quiet_NaN();
        f[5] = std::numeric_limits<float>::infinity();
        raw("nan.raw", bytesOf(f), {"2,2,2", "float32", ""});
        expected = "2 of 8 voxels are NaN or infinite";
    }
    SUBCASE("float64 beyond float range") {
        std::vector<double> g(8, 1.0);
        g[0] = 1e300;
        raw("far.raw", bytesOf(g), {"2,2,2", "float64", ""});
        expected = "1 of 8 voxels are NaN or infinite (or beyond float range)";
    }
    SUBCASE("not NRRD") {
        header("x.nrrd", "PNG\n" + good, eight);
        expected = "not an NRRD file";
    }
    SUBCASE("empty file") {
        file = writeBytes(dir / "empty.nrrd", {});
        message = errorOf([&] { ripple::apps::readNrrdVolume(file); });
        expected = "empty.nrrd: is empty";
    }
    SUBCASE("bzip2 encoding") {
        header("bz.nrrd", "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 2 2 2\nencoding: bzip2", eight);
        expected = "encoding 'bzip2' is not supported: raw and gzip are";
    }
    SUBCASE("gzip encoding over uncompressed data") {
        header("plain.nrrd", "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 2 2 2\nencoding: gzip", eight);
        expected = "its encoding is gzip but its data is not gzip-compressed";
    }
    SUBCASE("gzip data cut short") {
        std::vector<uint8_t> packed = gzipped(std::vector<uint8_t>(4096, 9));
        packed.resize(packed.size() / 2);
        header("cut.nrrd", "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 16 16 16\nencoding: gzip", packed);
        expected = "its gzip data";
    }
    SUBCASE("gzip data of fewer bytes than the field") {
        header("few.nrrd", "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 2 2 3\nencoding: gz", gzipped(eight));
        expected = "its gzip data holds 8 bytes after decompression, but the field needs 12";
    }
    SUBCASE("gzip data whose checksum does not match") {
        std::vector<uint8_t> packed = gzipped(std::vector<uint8_t>(4096, 9));
        packed[packed.size() - 8] ^= 0x01;  // the CRC-32 in the stream's trailer
        header("crc.nrrd", "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 16 16 16\nencoding: gzip", packed);
        expected = "its gzip data is corrupt (incorrect data check)";
    }
    SUBCASE("corrupt gzip data") {
        std::vector<uint8_t> packed = gzipped(std::vector<uint8_t>(4096, 9));
        for (size_t i = 12; i < packed.size() - 8; ++i) packed[i] ^= 0x5A;
        header("bad.nrrd", "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 16 16 16\nencoding: gzip", packed);
        expected = "its gzip data is corrupt";
    }
    SUBCASE("unknown NRRD type") {
        header("t.nrrd", "NRRD0004\ntype: block\ndimension: 3\nsizes: 2 2 2\nencoding: raw", eight);
        expected = "type 'block' is not supported";
    }
    SUBCASE("dimension 4") {
        header("d4.nrrd", "NRRD0004\ntype: uint8\ndimension: 4\nsizes: 1 2 2 2\nencoding: raw", eight);
        expected = "only 3D scalar fields (dimension: 3)";
    }
    SUBCASE("missing sizes") {
        header("ns.nrrd", "NRRD0004\ntype: uint8\ndimension: 3\nencoding: raw", eight);
        expected = "the header has no 'sizes' field";
    }
    SUBCASE("multi-byte type without endian") {
        header("ne.nrrd", "NRRD0004\ntype: float\ndimension: 3\nsizes: 2 2 2\nencoding: raw", std::vector<uint8_t>(32));
        expected = "no 'endian' field";
    }
    SUBCASE("NRRD data shorter than its sizes") {
        header("sh.nrrd", "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 4 4 4\nencoding: raw", eight);
        expected = "holds 8 bytes of data but 4x4x4 uint8 voxels need 64 bytes";
    }
    SUBCASE("rotated space directions") {
        header("rot.nrrd", "NRRD0004\n" + good + "space directions: (0,1,0) (1,0,0) (0,0,1)", eight);
        expected = "are not axis-aligned";
    }
    SUBCASE("negative spacings") {
        header("neg.nrrd", "NRRD0004\n" + good + "spacings: 1 -1 1", eight);
        expected = "spacings must be three positive finite numbers";
    }
    SUBCASE("line that is not a field") {
        header("line.nrrd", "NRRD0004\n" + good + "what is this", eight);
        expected = "header line 6 is not 'field: value'";
    }
    SUBCASE("absolute data file") {
        header("abs.nhdr", "NRRD0004\n" + good + "data file: /etc/passwd", {});
        expected = "data file '/etc/passwd' is an absolute path";
    }
    SUBCASE("data file escaping the folder") {
        std::filesystem::create_directory(dir / "inner");
        writeBytes(dir / "outside.raw", eight);
        file = writeText(dir / "inner" / "esc.nhdr", "NRRD0004\n" + good + "data file: ../outside.raw\n");
        message = errorOf([&] { ripple::apps::readNrrdVolume(file); });
        expected = "data file '../outside.raw' resolves outside the header's folder";
    }
    SUBCASE("missing data file") {
        file = writeText(dir / "m.nhdr", "NRRD0004\n" + good + "data file: gone.raw\n");
        message = errorOf([&] { ripple::apps::readNrrdVolume(file); });
        expected = "gone.raw does not exist";
    }
    SUBCASE("list of data files") {
        header("list.nhdr", "NRRD0004\n" + good + "data file: LIST", {});
        expected = "lists and patterns of data files are not supported";
    }
    SUBCASE("no blank line and no data file") {
        file = writeText(dir / "nb.nrrd", "NRRD0004\n" + good);
        message = errorOf([&] { ripple::apps::readNrrdVolume(file); });
        expected = "no 'data file' and no blank line";
    }
    INFO(message);
    CHECK(has(message, file.filename().string() + ": "));
    CHECK(has(message, expected));
}
