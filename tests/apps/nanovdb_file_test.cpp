// NanoVDB and OpenVDB files through ripple-render --volume: a fog sphere written with NanoVDB's own IO renders
// on the stage, and reads back the same from zip- and blosc-compressed files; a fog volume made and written
// with OpenVDB's own tools converts to NanoVDB with every voxel's value; wrong codecs, truncated, non-float and
// non-NanoVDB files are refused naming the file and the problem.
#include "apps/scene/NanoVdbPartition.h"
#include "io/volume/NanoVdbFile.h"
#include "io/volume/OpenVdbFile.h"
#include "tests/apps/ProgramRun.h"
#include "tests/apps/TestFiles.h"

#include <doctest/doctest.h>
// NanoVDB's IO writes compressed files with these (zlib and blosc, linked into the tests).
#define NANOVDB_USE_ZIP
#define NANOVDB_USE_BLOSC
#include <nanovdb/util/IO.h>
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/LevelSetSphere.h>
#include <openvdb/tools/LevelSetUtil.h>
#include <nanovdb/util/Primitives.h>

#include <cstring>
#include <fstream>
#include <iterator>

using namespace ripple;
using namespace ripple::test;

namespace {

std::vector<uint8_t> sphereFile(const std::filesystem::path& file, nanovdb::io::Codec codec = nanovdb::io::Codec::NONE) {
    const auto handle = nanovdb::createFogVolumeSphere<float>(1.0f, nanovdb::Vec3f(0.0f), 0.05, 3.0);
    nanovdb::io::writeGrid(file.string(), handle, codec);
    std::ifstream in(file, std::ios::binary);
    return std::vector<uint8_t>(std::istreambuf_iterator<char>(in), {});
}

}  // namespace

TEST_CASE("NanoVDB files: a fog sphere renders through ripple-render --volume; broken files are refused by name") {
    TempFolder dir;
    const std::vector<uint8_t> good = sphereFile(dir / "sphere.nvdb");
    const apps::NanoVdbFile read = apps::readNanoVdbFile(dir / "sphere.nvdb");
    CHECK(read.minValue == 0.0f);
    CHECK(read.maxValue == doctest::Approx(1.0f));
    CHECK(read.worldHi.x == doctest::Approx(1.0).epsilon(0.1));

    const ProgramRun run = runRender("--volume '" + (dir / "sphere.nvdb").string() + "' --size 32x32 --spp 4 -o '" +
                                     (dir / "sphere.pfm").string() + "'");
    CHECK_MESSAGE(run.exitCode == 0, run.output);
    CHECK(!contains(run.output, "WARNING"));
    CHECK(contains(run.output, "real and"));  // its volume statistics: the sphere was tracked

    struct Broken {
        const char* name;
        std::vector<uint8_t> bytes;
        const char* problem;
    };
    std::vector<Broken> broken;
    broken.push_back({"zip.nvdb", good, "its first grid's compressed data runs past the file"});
    broken.back().bytes[14] = 1;  // the header's codec: zip, over uncompressed data
    broken.push_back({"codec.nvdb", good, "unknown compression codec 7"});
    broken.back().bytes[14] = 7;
    broken.push_back({"double.nvdb", good, "Ripple reads float grids"});
    const uint32_t doubleType = uint32_t(nanovdb::GridType::Double);
    std::memcpy(broken.back().bytes.data() + 16 + 32, &doubleType, sizeof doubleType);  // the first grid's type
    broken.push_back({"truncated.nvdb", std::vector<uint8_t>(good.begin(), good.begin() + 100000), "runs past the file"});
    broken.push_back({"magic.nvdb", good, "not a NanoVDB file"});
    broken.back().bytes[0] ^= 0xFF;
    for (const Broken& b : broken) {
        CAPTURE(b.name);
        writeBytes(dir / b.name, b.bytes);
        const ProgramRun refused = runRender("--volume '" + (dir / b.name).string() + "' -o '" + (dir / "x.png").string() + "'");
        CHECK(refused.exitCode == 1);
        CHECK_MESSAGE(contains(refused.output, b.problem), refused.output);
        CHECK(contains(refused.output, b.name));
    }
}

// Split over 2 to 4 ranks (apps/scene/NanoVdbPartition), the parts' active boxes tile the whole's, sharing only
// boundary planes, and every voxel of a part's box holds the whole grid's value there (active or not), so each
// rank's field is the whole's over its region.
TEST_CASE("NanoVDB files: a grid split over ranks keeps the whole's values on regions that tile its box") {
    TempFolder dir;
    sphereFile(dir / "sphere.nvdb");
    const apps::NanoVdbFile whole = apps::readNanoVdbFile(dir / "sphere.nvdb");
    const auto* grid = reinterpret_cast<const nanovdb::NanoGrid<float>*>(whole.grid.data());
    const nanovdb::CoordBBox wholeBox = grid->tree().root().bbox();
    const auto wholeValues = grid->getAccessor();
    const uint64_t wholeVolume = uint64_t(wholeBox.dim()[0]) * wholeBox.dim()[1] * wholeBox.dim()[2];
    for (uint32_t ranks = 2; ranks <= 4; ++ranks) {
        CAPTURE(ranks);
        uint64_t volume = 0, wrong = 0, voxels = 0;
        std::vector<nanovdb::CoordBBox> boxes;
        for (uint32_t r = 0; r < ranks; ++r) {
            const apps::NanoVdbFile part = apps::nanoVdbPart(whole, r, ranks);
            CHECK(part.worldLo == whole.worldLo);
            nanovdb::HostBuffer buffer = nanovdb::HostBuffer::create(part.grid.size());
            std::memcpy(buffer.data(), part.grid.data(), part.grid.size());
            const nanovdb::GridHandle<nanovdb::HostBuffer> handle(std::move(buffer));
            const auto* partGrid = handle.grid<float>();
            REQUIRE(partGrid != nullptr);
            const nanovdb::CoordBBox box = partGrid->tree().root().bbox();
            boxes.push_back(box);
            // Cells (between voxel planes) of the box: the parts' cells add up to the whole's.
            volume += uint64_t(box.dim()[0] - 1) * (box.dim()[1] - 1) * (box.dim()[2] - 1);
            const auto values = partGrid->getAccessor();
            for (auto it = box.begin(); it; ++it, ++voxels) wrong += values.getValue(*it) != wholeValues.getValue(*it);
        }
        CHECK(wrong == 0);
        CHECK(voxels >= wholeVolume);
        CHECK(volume == uint64_t(wholeBox.dim()[0] - 1) * (wholeBox.dim()[1] - 1) * (wholeBox.dim()[2] - 1));
        for (const nanovdb::CoordBBox& b : boxes) CHECK(wholeBox.isInside(b));
    }
}

TEST_CASE("NanoVDB files: zip- and blosc-compressed files read back the uncompressed grid") {
    TempFolder dir;
    sphereFile(dir / "plain.nvdb");
    sphereFile(dir / "zip.nvdb", nanovdb::io::Codec::ZIP);
    sphereFile(dir / "blosc.nvdb", nanovdb::io::Codec::BLOSC);
    const apps::NanoVdbFile plain = apps::readNanoVdbFile(dir / "plain.nvdb");
    for (const char* name : {"zip.nvdb", "blosc.nvdb"}) {
        CAPTURE(name);
        CHECK(std::filesystem::file_size(dir / name) < std::filesystem::file_size(dir / "plain.nvdb"));
        const apps::NanoVdbFile read = apps::readNanoVdbFile(dir / name);
        CHECK(read.grid == plain.grid);
        CHECK(read.minValue == plain.minValue);
        CHECK(read.maxValue == plain.maxValue);
    }
    // A compressed size that runs past the file is refused by name.
    std::ifstream in(dir / "zip.nvdb", std::ios::binary);
    std::vector<uint8_t> bytes(std::istreambuf_iterator<char>(in), {});
    writeBytes(dir / "short.nvdb", std::vector<uint8_t>(bytes.begin(), bytes.end() - 100));
    CHECK_THROWS_WITH_AS(apps::readNanoVdbFile(dir / "short.nvdb"), doctest::Contains("compressed data runs past the file"),
                         apps::VolumeError);
}

// OpenVDB's own tools make the grid (a level-set sphere turned into a fog volume) and write the file.
TEST_CASE("OpenVDB files: a fog volume made with OpenVDB's tools converts to NanoVDB voxel for voxel and renders") {
    TempFolder dir;
    openvdb::initialize();
    openvdb::FloatGrid::Ptr fog = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(1.0f, openvdb::Vec3f(0.0f), 0.05f);
    openvdb::tools::sdfToFogVolume(*fog);
    fog->setName("density");
    openvdb::Vec3SGrid::Ptr vectors = openvdb::Vec3SGrid::create();
    vectors->setName("velocity");
    openvdb::io::File(( dir / "fog.vdb").string()).write({vectors, fog});
    const apps::NanoVdbFile read = apps::readOpenVdbFile(dir / "fog.vdb");
    CHECK(read.name == "density");
    CHECK(read.minValue >= 0.0f);
    CHECK(read.maxValue == doctest::Approx(1.0f));
    nanovdb::HostBuffer buffer = nanovdb::HostBuffer::create(read.grid.size());
    std::memcpy(buffer.data(), read.grid.data(), read.grid.size());
    const nanovdb::GridHandle<nanovdb::HostBuffer> handle(std::move(buffer));
    REQUIRE(handle.grid<float>() != nullptr);
    const auto nano = handle.grid<float>()->getAccessor();
    uint64_t voxels = 0, wrong = 0;
    for (auto it = fog->cbeginValueOn(); it; ++it)  // voxels and tiles (every voxel of a tile)
        for (auto c = it.getBoundingBox().begin(); c; ++c, ++voxels) wrong += nano.getValue(nanovdb::Coord((*c).x(), (*c).y(), (*c).z())) != *it;
    CHECK(voxels == fog->activeVoxelCount());
    CHECK(voxels > 10000);
    CHECK(wrong == 0);
    const ProgramRun run = runRender("--volume '" + (dir / "fog.vdb").string() + "' --size 32x32 --spp 4 -o '" +
                                     (dir / "fog.pfm").string() + "'");
    CHECK_MESSAGE(run.exitCode == 0, run.output);
    CHECK(contains(run.output, "real and"));
    // By name: the float grid, not the vector one; a missing name, a file OpenVDB cannot read.
    CHECK_THROWS_WITH_AS(apps::readOpenVdbFile(dir / "fog.vdb", "velocity"),
                         doctest::Contains("no float grid 'velocity' (grids: density (float), velocity (vec3s))"), apps::VolumeError);
    writeText(dir / "text.vdb", "not an OpenVDB file\n");
    CHECK_THROWS_WITH_AS(apps::readOpenVdbFile(dir / "text.vdb"), doctest::Contains("OpenVDB cannot read it"), apps::VolumeError);
}
