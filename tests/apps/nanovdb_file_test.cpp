// NanoVDB files through ripple-render --volume: a fog sphere written with NanoVDB's own IO renders on the
// stage; compressed, truncated, non-float and non-NanoVDB files are refused naming the file and the problem.
#include "io/volume/NanoVdbFile.h"
#include "tests/apps/ProgramRun.h"
#include "tests/apps/TestFiles.h"

#include <doctest/doctest.h>
#include <nanovdb/util/IO.h>
#include <nanovdb/util/Primitives.h>

#include <cstring>
#include <fstream>
#include <iterator>

using namespace ripple;
using namespace ripple::test;

namespace {

std::vector<uint8_t> sphereFile(const std::filesystem::path& file) {
    const auto handle = nanovdb::createFogVolumeSphere<float>(1.0f, nanovdb::Vec3f(0.0f), 0.05, 3.0);
    nanovdb::io::writeGrid(file.string(), handle, nanovdb::io::Codec::NONE);
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
    broken.push_back({"zip.nvdb", good, "its grids are compressed (zip)"});
    broken.back().bytes[14] = 1;  // the header's codec
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
