// ripple-render as a user runs it: every error must end the process with exit code 1 and a message naming
// the problem, never a crash (a crash shows as a signal); small renders through the Ripple device (the
// Cornell demo, a volume file); and the convergence options (--time, --target-error, --report) stopping and
// writing what they promise.
#include "io/image/ImageIO.h"
#include "metrics/HeatMap.h"
#include "metrics/ImageMetrics.h"
#include "tests/apps/ProgramRun.h"
#include "tests/apps/TestFiles.h"

#include <doctest/doctest.h>
#include <glm/glm.hpp>
#include <stb_image.h>
#include <stb_image_write.h>
#include <tinyexr.h>

#include <dlfcn.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

using namespace ripple::test;

TEST_CASE("ripple-render rejects bad input with a message and exit code 1") {
    TempFolder dir;
    std::string arguments, expected;
    SUBCASE("missing scene file") {
        arguments = "'" + (dir / "absent.glb").string() + "'";
        expected = "absent.glb: no such file";
    }
    SUBCASE("malformed glTF") {
        std::vector<uint8_t> bytes = glbBytes(triangleSource());
        bytes[1] = 'X';
        arguments = "'" + writeBytes(dir / "broken.glb", bytes).string() + "'";
        expected = "broken.glb: bad magic";
    }
    SUBCASE("library that does not exist") {
        arguments = "--library no_such_ripple_library --demo default";
        expected = "cannot load the ANARI library 'no_such_ripple_library'";
    }
    SUBCASE("unknown demo scene") {
        arguments = "--demo nonesuch --library no_such_ripple_library";
        expected = "unknown demo scene 'nonesuch' (known: default, cornell, volume, isosurface)";
    }
    SUBCASE("size that is not WIDTHxHEIGHT") {
        arguments = "--size 12by5";
        expected = "--size '12by5' is not WIDTHxHEIGHT";
    }
    SUBCASE("zero size") {
        arguments = "--size 0x10";
        expected = "each side must be 1 to 16384 pixels";
    }
    SUBCASE("scene file and demo together") {
        arguments = "'" + writeGlb(dir / "t.glb", triangleSource()).string() + "' --demo default";
        expected = "either a scene file or --demo";
    }
    SUBCASE("reference image that does not exist") {
        arguments = "--size 16x16 --reference '" + (dir / "absent.pfm").string() + "'";
        expected = "absent.pfm";
    }
    SUBCASE("reference image that is not an image") {
        arguments = "--size 16x16 --reference '" + writeText(dir / "text.pfm", "not a picture\n").string() + "'";
        expected = "text.pfm";
    }
    SUBCASE("reference image of another size") {
        const std::vector<float> pixels(4 * 4 * 4, 0.5f);
        ripple::apps::writePfmBottomUp(dir / "small.pfm", 4, 4, pixels.data());
        arguments = "--size 16x16 --reference '" + (dir / "small.pfm").string() + "'";
        expected = "small.pfm is 4x4 but the render is 16x16";
    }
    SUBCASE("report that is not a CSV") {
        arguments = "--report '" + (dir / "plot.png").string() + "'";
        expected = "give a .csv file";
    }
    SUBCASE("report whose plot would overwrite the image") {
        arguments = "--report '" + (dir / "out.csv").string() + "' -o '" + (dir / "out.png").string() + "'";
        expected = "would overwrite the output image";
    }
    SUBCASE("report of one sample") {
        arguments = "--report '" + (dir / "out.csv").string() + "' --spp 1";
        expected = "the error estimate needs 2 samples or more";
    }
    // The output is checked before anything renders, with the operating system's reason.
    SUBCASE("output in a missing folder") {
        arguments = "--size 8x8 -o '" + (dir / "absent" / "x.png").string() + "'";
        expected = "x.png: cannot write the image there: No such file or directory";
    }
    SUBCASE("output under a file, not a folder") {
        arguments = "--size 8x8 -o '" + (writeText(dir / "plain", "x\n") / "x.png").string() + "'";
        expected = "x.png: cannot write the image there: Not a directory";
    }
    SUBCASE("output that is a folder") {
        std::filesystem::create_directory(dir / "folder.png");
        arguments = "--size 8x8 -o '" + (dir / "folder.png").string() + "'";
        expected = "folder.png: cannot write the image there: Is a directory";
    }
    if (geteuid() != 0) {  // root writes into read-only folders
        SUBCASE("output in a read-only folder") {
            std::filesystem::create_directory(dir / "locked");
            std::filesystem::permissions(dir / "locked", std::filesystem::perms::owner_read | std::filesystem::perms::owner_exec);
            arguments = "--size 8x8 -o '" + (dir / "locked" / "x.png").string() + "'";
            expected = "x.png: cannot write the image there: Permission denied";
        }
    }
    SUBCASE("output of an unknown format") {
        arguments = "--size 8x8 -o '" + (dir / "x.bmp").string() + "'";
        expected = "unsupported image format '.bmp' (supported: .png, .jpg, .jpeg, .pfm, .exr)";
    }
    SUBCASE("library that is not a shared object") {
        writeText(dir / "libanari_library_text.so", "not a library\n");
        arguments = "--library 'text," + (dir / "").string() + "' --demo default";
        expected = "cannot load the ANARI library 'text,";
    }
    SUBCASE("shared object without the ANARI entry point") {
        // Any shared library will do: the C library exports no anari_library_c_new_library.
        Dl_info libc{};
        REQUIRE(dladdr(reinterpret_cast<void*>(&std::printf), &libc) != 0);
        std::filesystem::create_symlink(libc.dli_fname, dir / "libanari_library_c.so");
        arguments = "--library 'c," + (dir / "").string() + "' --demo default";
        expected = "does not export anari_library_c_new_library";
    }
    SUBCASE("volume file that does not exist") {
        arguments = "--volume '" + (dir / "absent.raw").string() + "' --dims 4,4,4 --type uint8";
        expected = "absent.raw: no such file";
    }
    SUBCASE("raw volume without its layout") {
        arguments = "--volume '" + writeText(dir / "v.raw", "12345678").string() + "' --type uint8";
        expected = "a raw file needs --dims X,Y,Z and --type";
    }
    SUBCASE("raw volume shorter than its dims") {
        arguments = "--volume '" + writeText(dir / "v.raw", "12345678").string() + "' --dims 4x4x4 --type uint16";
        expected = "v.raw: holds 8 bytes of data but 4x4x4 uint16 voxels need 128 bytes";
    }
    SUBCASE("raw layout for an NRRD file") {
        arguments = "--volume '" + (dir / "v.nrrd").string() + "' --dims 2,2,2";
        expected = "--dims, --type and --spacing are for raw files";
    }
    SUBCASE("volume opacity not a number") {
        arguments = "--volume '" + writeText(dir / "v.raw", "12345678").string() + "' --dims 2,2,2 --type uint8 --opacity nan";
        expected = "--opacity nan is not a number from 0 to 1";
    }
    SUBCASE("volume unit distance infinite") {
        arguments = "--volume '" + writeText(dir / "v.raw", "12345678").string() + "' --dims 2,2,2 --type uint8 --unit-distance inf";
        expected = "--unit-distance inf is not a finite positive number";
    }
    SUBCASE("volume options without a volume") {
        arguments = "--demo volume --tf viridis";
        expected = "need --volume FILE";
    }
    SUBCASE("volume and a demo together") {
        arguments = "--demo volume --volume '" + writeText(dir / "v.raw", "12345678").string() + "' --dims 2,2,2 --type uint8";
        expected = "give one of a scene file, --demo or --volume";
    }
    SUBCASE("view file that does not exist") {
        arguments = "--view '" + (dir / "absent.json").string() + "' --size 8x8";
        expected = "absent.json: cannot open the view file";
    }
    SUBCASE("view file and --camera together") {
        arguments = "--view '" + writeText(dir / "v.json", "{}").string() + "' --camera 0 --size 8x8";
        expected = "give one of --camera and --view";
    }
    SUBCASE("malformed view file") {
        arguments = "--view '" + writeText(dir / "v.json", R"({"ripple-view-state": 1, "camera": []})").string() + "' --size 8x8";
        expected = "v.json: \"camera\" must be an object";
    }
    SUBCASE("channels without an EXR output") {
        arguments = "--channels depth --size 8x8 -o '" + (dir / "x.png").string() + "'";
        expected = "--channels needs an .exr output (-o)";
    }
    SUBCASE("unknown channel") {
        arguments = "--channels depth,motion --size 8x8 -o '" + (dir / "x.exr").string() + "'";
        expected = "--channels: unknown channel 'motion' (known: depth, normal, albedo)";
    }
    SUBCASE("renderer the device does not have") {
        arguments = "--renderer raycast --size 8x8";
        expected = "--renderer: the device has no renderer 'raycast' (it has: default, eyeLight)";
    }
    SUBCASE("unknown transfer function") {
        arguments = "--volume '" + writeText(dir / "v.raw", "12345678").string() + "' --dims 2,2,2 --type uint8 --tf jet";
        expected = "unknown transfer function 'jet' (known: viridis, coolwarm, grayscale)";
    }
    const ProgramRun run = runRender(arguments);
    CHECK_MESSAGE(run.exitCode == 1, run.output);
    CHECK_MESSAGE(contains(run.output, "[ripple-render] ERROR: "), run.output);
    CHECK_MESSAGE(contains(run.output, expected), run.output);
    for (const char* leftover : {"absent", "locked/x.png"}) CHECK_FALSE(std::filesystem::exists(dir / leftover));
}

// -o x.jpg writes a JPEG (never PNG bytes under a .jpg name), of the render's size.
namespace {

// The channels of an EXR file by name (values as float, rows top first), read with tinyexr's full API.
std::map<std::string, std::vector<float>> exrChannels(const std::filesystem::path& file, std::map<std::string, int>& types) {
    EXRVersion version;
    REQUIRE(ParseEXRVersionFromFile(&version, file.string().c_str()) == TINYEXR_SUCCESS);
    EXRHeader header;
    InitEXRHeader(&header);
    const char* error = nullptr;
    REQUIRE(ParseEXRHeaderFromFile(&header, &version, file.string().c_str(), &error) == TINYEXR_SUCCESS);
    for (int c = 0; c < header.num_channels; ++c) {
        types[header.channels[c].name] = header.pixel_types[c];
        header.requested_pixel_types[c] = TINYEXR_PIXELTYPE_FLOAT;  // halves converted on load
    }
    EXRImage image;
    InitEXRImage(&image);
    REQUIRE(LoadEXRImageFromFile(&image, &header, file.string().c_str(), &error) == TINYEXR_SUCCESS);
    std::map<std::string, std::vector<float>> channels;
    for (int c = 0; c < header.num_channels; ++c) {
        const auto* values = reinterpret_cast<const float*>(image.images[c]);
        channels[header.channels[c].name].assign(values, values + size_t(image.width) * image.height);
    }
    FreeEXRImage(&image);
    FreeEXRHeader(&header);
    return channels;
}

}  // namespace

// --channels adds the frame's depth, normal and albedo as layers of the EXR beside an unchanged colour;
// --exr-half stores colour, normal and albedo as halves (within half precision of the floats).
TEST_CASE("ripple-render --channels: depth, normal and albedo as EXR layers; --exr-half") {
    TempFolder dir;
    const std::string common = "--demo cornell --size 24x16 --spp 2 --quiet -o '";
    const auto plain = dir / "plain.exr", layered = dir / "layered.exr", half = dir / "half.exr";
    for (const auto& [file, extra] : {std::pair{plain, std::string()}, {layered, std::string(" --channels depth,normal,albedo")},
                                      {half, std::string(" --channels depth,normal --channels albedo --exr-half")}}) {
        const ProgramRun run = runRender(common + file.string() + "'" + extra);
        REQUIRE_MESSAGE(run.exitCode == 0, run.output);
    }
    std::map<std::string, int> plainTypes, types, halfTypes;
    const auto a = exrChannels(plain, plainTypes), b = exrChannels(layered, types), c = exrChannels(half, halfTypes);
    CHECK(a.size() == 4);
    const std::vector<std::string> names = {"A", "B", "G", "R", "Z", "albedo.B", "albedo.G", "albedo.R", "normal.X", "normal.Y", "normal.Z"};
    for (const std::string& name : names) {
        CAPTURE(name);
        REQUIRE(b.count(name) == 1);
        REQUIRE(c.count(name) == 1);
        CHECK(types[name] == TINYEXR_PIXELTYPE_FLOAT);
        CHECK(halfTypes[name] == (name == "Z" ? TINYEXR_PIXELTYPE_FLOAT : TINYEXR_PIXELTYPE_HALF));
        if (a.count(name)) CHECK(a.at(name) == b.at(name));  // the colour is unchanged by the layers
        if (name == "Z") CHECK(c.at(name) == b.at(name));  // depth stays 32-bit (+inf where nothing is hit)
        else
            for (size_t i = 0; i < b.at(name).size(); ++i)  // half: 11 significant bits
                CHECK(std::abs(c.at(name)[i] - b.at(name)[i]) <= std::abs(b.at(name)[i]) / 1024.0f + 1e-7f);
    }
    // Where a pixel's camera ray meets a wall: a finite, positive depth, a unit normal and an albedo within
    // [0, 1]; where it meets nothing (the box's open front, seen past its edges), depth +inf. Most of the
    // image is the box.
    size_t hits = 0;
    for (size_t i = 0; i < b.at("Z").size(); ++i) {
        INFO("pixel " << i);
        const float depth = b.at("Z")[i];
        if (std::isinf(depth)) continue;
        ++hits;
        CHECK(depth > 0.0f);
        const float x = b.at("normal.X")[i], y = b.at("normal.Y")[i], z = b.at("normal.Z")[i];
        CHECK(std::abs(std::sqrt(x * x + y * y + z * z) - 1.0f) < 1e-4f);
        for (const char* albedo : {"albedo.R", "albedo.G", "albedo.B"}) {
            CHECK(b.at(albedo)[i] >= 0.0f);
            CHECK(b.at(albedo)[i] <= 1.0f);
        }
    }
    CHECK(hits > b.at("Z").size() / 2);
    // At mid height the side walls are seen at columns 4-6 and 16-18 (past them the open box's outside):
    // the left one red, the right one green, both facing along x into the box; a permuted channel order
    // shows here.
    const auto at = [&](const char* name, uint32_t x, uint32_t y) { return b.at(name)[size_t(y) * 24 + x]; };
    for (uint32_t y = 6; y < 10; ++y) {
        CAPTURE(y);
        CHECK(at("albedo.R", 5, y) > 2.0f * at("albedo.G", 5, y));
        CHECK(at("albedo.R", 5, y) > 2.0f * at("albedo.B", 5, y));
        CHECK(at("albedo.G", 17, y) > 2.0f * at("albedo.R", 17, y));
        CHECK(at("albedo.G", 17, y) > 2.0f * at("albedo.B", 17, y));
        CHECK(std::abs(at("normal.X", 5, y)) > 0.99f);
        CHECK(std::abs(at("normal.X", 17, y)) > 0.99f);
        CHECK(at("normal.X", 5, y) * at("normal.X", 17, y) < 0.0f);  // facing each other
    }

    // The same render written as PFM: the EXR's colour read back equals it to the bit (both hold 32-bit
    // floats; the EXR's alpha aside), the half EXR's within half precision.
    const auto pfm = dir / "plain.pfm";
    const ProgramRun run = runRender(common + pfm.string() + "'");
    REQUIRE_MESSAGE(run.exitCode == 0, run.output);
    const ripple::apps::LinearImage fromPfm = ripple::apps::readLinearImage(pfm), fromExr = ripple::apps::readLinearImage(plain),
                                    fromHalf = ripple::apps::readLinearImage(half);
    REQUIRE(fromPfm.width == 24);
    REQUIRE(fromExr.width == 24);
    REQUIRE(fromPfm.rgb.size() == fromExr.rgb.size());
    REQUIRE(fromPfm.rgb.size() == fromHalf.rgb.size());
    size_t unequal = 0, outsideHalf = 0;
    for (size_t i = 0; i < fromPfm.rgb.size(); ++i) {
        unequal += fromExr.rgb[i] != fromPfm.rgb[i];
        outsideHalf += std::abs(fromHalf.rgb[i] - fromPfm.rgb[i]) > std::abs(fromPfm.rgb[i]) / 1024.0f + 1e-7f;
    }
    CHECK(unequal == 0);
    CHECK(outsideHalf == 0);
}

// --seed: the same seed gives the same image to the bit, another seed other samples (a reference must not
// share samples with the image it judges).
TEST_CASE("ripple-render --seed: the same seed repeats the image, another changes it") {
    TempFolder dir;
    const auto renderWithSeed = [&](const std::string& seed, const std::string& name) {
        const auto file = dir / name;
        const ProgramRun run =
            runRender("--demo cornell --size 16x16 --spp 2 --quiet" + seed + " -o '" + file.string() + "'");
        REQUIRE_MESSAGE(run.exitCode == 0, run.output);
        return ripple::apps::readLinearImage(file).rgb;
    };
    const auto first = renderWithSeed(" --seed 7", "a.pfm"), again = renderWithSeed(" --seed 7", "b.pfm");
    const auto other = renderWithSeed(" --seed 8", "c.pfm"), byDefault = renderWithSeed("", "d.pfm");
    REQUIRE(first.size() == 16 * 16 * 3);
    CHECK(first == again);
    size_t differ = 0, differFromDefault = 0;
    for (size_t i = 0; i < first.size(); ++i) {
        differ += first[i] != other[i];
        differFromDefault += first[i] != byDefault[i];
    }
    CHECK(differ > first.size() / 2);  // noisy at 2 spp: most values change with the samples
    CHECK(differFromDefault > first.size() / 2);
}

// glTF alpha modes reach the device: a triangle of base colour alpha 0.25 drawn as MASK with cutoff 0.5 is cut
// away (where it lies the background shows, as beside it), as BLEND it covers a quarter of what is behind
// it, and as OPAQUE it ignores the alpha. Pixels are read at (0.25, 0.25) on the triangle (x = 1/4 of the
// width, 3/4 of the height down) and at (0.75, 0.75) beside it.
TEST_CASE("ripple-render: glTF alpha modes MASK, BLEND and OPAQUE as the device draws them") {
    TempFolder dir;
    const auto renderWithAlpha = [&](const std::string& mode) {
        GltfSource source = triangleSource();
        source.replace(R"({"POSITION":0},"indices":1})", R"({"POSITION":0},"indices":1,"material":0})");
        std::string material = R"("materials":[{"pbrMetallicRoughness":{"baseColorFactor":[0.9,0.2,0.2,0.25]},"alphaMode":")";
        material.append(mode).append(R"(","alphaCutoff":0.5,"doubleSided":true}],"buffers":)");
        source.replace(R"("buffers":)", material);
        const auto scene = writeGlb(dir / (mode + ".glb"), source);
        const auto image = dir / (mode + ".pfm");
        std::string arguments = "'";
        arguments.append(scene.string()).append("' --size 32x32 --spp 64 --quiet -o '").append(image.string()).append("'");
        const ProgramRun run = runRender(arguments);
        REQUIRE_MESSAGE(run.exitCode == 0, run.output);
        return ripple::apps::readLinearImage(image);
    };
    // readLinearImage gives row 0 at the top.
    const auto pixel = [](const ripple::apps::LinearImage& image, uint32_t x, uint32_t y) {
        const float* p = &image.rgb[(size_t(y) * image.width + x) * 3];
        return glm::vec3(p[0], p[1], p[2]);
    };
    const auto mask = renderWithAlpha("MASK"), blend = renderWithAlpha("BLEND"), opaque = renderWithAlpha("OPAQUE");
    const glm::uvec2 on{8, 24}, beside{24, 8};
    CHECK(pixel(mask, on.x, on.y) == pixel(mask, beside.x, beside.y));
    CHECK(pixel(blend, on.x, on.y) != pixel(blend, beside.x, beside.y));
    CHECK(pixel(opaque, on.x, on.y) != pixel(opaque, beside.x, beside.y));
    // Over a 4x4 block on the triangle (1,024 samples) its red shows about a quarter as much blended as
    // opaque, against the background's red (the binomial spread of that share is 0.014).
    const auto blockRed = [&](const ripple::apps::LinearImage& image) {
        float sum = 0;
        for (uint32_t y = 22; y < 26; ++y)
            for (uint32_t x = 6; x < 10; ++x) sum += pixel(image, x, y).r;
        return sum / 16 - pixel(image, beside.x, beside.y).r;
    };
    const float opaqueRed = blockRed(opaque), blendRed = blockRed(blend);
    CHECK(opaqueRed > 0.05f);
    CHECK(blendRed > 0.15f * opaqueRed);
    CHECK(blendRed < 0.35f * opaqueRed);
}

TEST_CASE("ripple-render writes JPEG for .jpg and .jpeg") {
    TempFolder dir;
    for (const char* name : {"out.jpg", "out.JPEG"}) {
        const auto image = dir / name;
        const ProgramRun run = runRender("--demo cornell --size 24x16 --spp 2 --quiet -o '" + image.string() + "'");
        REQUIRE_MESSAGE(run.exitCode == 0, run.output);
        std::ifstream in(image, std::ios::binary);
        unsigned char magic[3] = {};
        in.read(reinterpret_cast<char*>(magic), 3);
        CHECK_MESSAGE((magic[0] == 0xFF && magic[1] == 0xD8 && magic[2] == 0xFF), name);  // JPEG's SOI marker
        int w = 0, h = 0, comp = 0;
        CHECK(stbi_info(image.string().c_str(), &w, &h, &comp) == 1);
        CHECK(w == 24);
        CHECK(h == 16);
        CHECK(comp == 3);
    }
}

// A frame too large for memory is refused before anything is allocated, with its size and the bytes it
// needs. RIPPLE_MEMORY_LIMIT caps the memory both ripple-render and the device take as available, so that
// the refusal does not depend on this machine's memory: 1024x1024 passes ripple-render's own check (144
// bytes a pixel: 151 MB) but not the device's (its buffers of paths in flight alone take more than 200 MB);
// 16384x16384 fails ripple-render's own check (38.7 GB).
TEST_CASE("ripple-render refuses a frame too large for memory, naming size and bytes") {
    TempFolder dir;
    const std::string output = " --quiet -o '" + (dir / "big.png").string() + "'";
    SUBCASE("the device's frame buffers") {
        const ProgramRun run = runProgram(RIPPLE_RENDER_PATH, "--demo cornell --size 1024x1024" + output,
                                          "RIPPLE_MEMORY_LIMIT=200000000");
        CHECK_MESSAGE(run.exitCode == 1, run.output);
        CHECK_MESSAGE(contains(run.output, "cannot render: a 1024x1024 frame with its channels needs "), run.output);
        CHECK_MESSAGE(contains(run.output, " but only 200000000 bytes (190.7 MiB) are available"), run.output);
        const size_t at = run.output.find("frame with its channels needs ");
        REQUIRE(at != std::string::npos);
        const uint64_t needed = std::stoull(run.output.substr(at + 29));
        CHECK(needed > 200000000u);
        CHECK(needed >= 1024u * 1024u * (16 + 16 + 4 + 16 + 16));  // accumulation, radiance, counts, color, host copy
    }
    SUBCASE("ripple-render's own buffers") {
        const ProgramRun run = runProgram(RIPPLE_RENDER_PATH, "--demo cornell --size 16384x16384" + output,
                                          "RIPPLE_MEMORY_LIMIT=8000000000");
        CHECK_MESSAGE(run.exitCode == 1, run.output);
        CHECK_MESSAGE(contains(run.output, "--size 16384x16384: ripple-render's image buffers need 38654705664 bytes but "
                                           "only 8000000000 are available"), run.output);
    }
    CHECK_FALSE(std::filesystem::exists(dir / "big.png"));
}

TEST_CASE("ripple-render option errors from the parser exit non-zero") {
    const ProgramRun run = runRender("--spp 0");
    CHECK(run.exitCode > 0);
    CHECK(contains(run.output, "--spp"));
}

// The whole path through the Ripple device: a small Cornell box, checked by properties any correct render
// has even at 4 samples, with margins measured on a correct render (ratios 3.7, 1.5 and 3.1): the red wall
// (-X) shows on the left and the green (+X) on the right, and the upper back wall (rows 12-20, lit directly
// by the ceiling light) is brighter than the boxes' camera-facing sides below it (rows 33-41, lit only
// indirectly). A frame written with its rows or columns the wrong way round fails one of them.
TEST_CASE("ripple-render renders the Cornell demo through the Ripple device") {
    TempFolder dir;
    const auto image = dir / "cornell.png";
    const ProgramRun run = runRender("--demo cornell --size 48x48 --spp 4 --quiet -o '" + image.string() + "'");
    REQUIRE_MESSAGE(run.exitCode == 0, run.output);
    CHECK(contains(run.output, "rendered 48x48, 4 spp"));
    int w = 0, h = 0, comp = 0;
    unsigned char* pixels = stbi_load(image.string().c_str(), &w, &h, &comp, 4);
    REQUIRE(pixels != nullptr);
    CHECK(w == 48);
    CHECK(h == 48);
    // Mean of channel c over a rectangle of the PNG (row 0 at the top).
    const auto mean = [&](int x0, int x1, int y0, int y1, int c) {
        double sum = 0.0;
        for (int y = y0; y < y1; ++y)
            for (int x = x0; x < x1; ++x) sum += pixels[(y * w + x) * 4 + c];
        return sum / double((x1 - x0) * (y1 - y0));
    };
    const auto luminance = [&](int x0, int x1, int y0, int y1) {
        return 0.2126 * mean(x0, x1, y0, y1, 0) + 0.7152 * mean(x0, x1, y0, y1, 1) + 0.0722 * mean(x0, x1, y0, y1, 2);
    };
    // The side walls fill the outer eighths of the image at mid height.
    CHECK(mean(0, 6, 16, 32, 0) > 2.0 * mean(0, 6, 16, 32, 1));        // left: red
    CHECK(mean(42, 48, 16, 32, 1) > 1.25 * mean(42, 48, 16, 32, 0));   // right: green
    CHECK(luminance(12, 36, 12, 20) > 2.0 * luminance(12, 36, 33, 41)); // lit wall above, shaded boxes below
    stbi_image_free(pixels);
}

namespace {

// The number after `key` in ripple-render's last line ("... in 1.23 s, estimated relMSE 4.5e-02 -> ...").
double numberAfter(const std::string& output, const std::string& key) {
    const size_t at = output.rfind(key);
    REQUIRE_MESSAGE(at != std::string::npos, output);
    return std::stod(output.substr(at + key.size()));
}

}  // namespace

// --time bounds the whole run, start-up included, counted from the process's start; it stops on time, not on
// the default --spp (which it does not cap unless given). The loop stops before a frame that the longest of
// the last few predicts to end past the limit, so the run the program reports ends within it and less than
// its longest frame early; the process, measured from outside, adds only its exit (at most one more frame's
// time and 10%). A start-up past the limit (a cold shader cache) leaves one frame of one sample, said so.
TEST_CASE("ripple-render --time bounds the whole run, start-up included") {
    TempFolder dir;
    constexpr double kLimit = 4.0;  // above the Cornell demo's start-up with validation on two loaded CPU cores
    const auto begin = std::chrono::steady_clock::now();
    const ProgramRun run = runRender("--demo cornell --size 16x16 --time 4 -o '" + (dir / "t.pfm").string() + "'");
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
    REQUIRE_MESSAGE(run.exitCode == 0, run.output);
    INFO(run.output);
    CHECK(contains(run.output, "start-up "));
    CHECK(contains(run.output, "(library and scene "));
    const double whole = numberAfter(run.output, " in ");
    const double startUp = numberAfter(run.output, "(start-up ");
    CHECK(whole <= wall);
    if (startUp >= kLimit) {
        CHECK(contains(run.output, "time limit exceeded by start-up"));
        CHECK(contains(run.output, "1 spp (1 frames of 1)"));
        CHECK(wall <= startUp * 1.1 + 0.5);
        return;
    }
    CHECK_FALSE(contains(run.output, "exceeded"));
    const double longestFrame = numberAfter(run.output, "then frames of up to ");
    CHECK(whole <= kLimit * 1.1);
    // The run is printed to 0.01 s and its longest frame to 0.001 s: compared within that rounding (a run of
    // 3.9904 s with a longest frame of 0.0104 s prints as 3.99 and 0.010, and stopped as it should).
    constexpr double kPrintRounding = 0.005 + 0.0005;
    CHECK(whole > kLimit - longestFrame - kPrintRounding);
    CHECK(wall <= kLimit * 1.1 + longestFrame);
}

// A limit no start-up can meet: exactly one frame of one sample, an image, and a line saying why.
TEST_CASE("ripple-render --time shorter than the start-up renders one frame and says so") {
    TempFolder dir;
    const auto image = dir / "t.pfm";
    const ProgramRun run = runRender("--demo cornell --size 16x16 --time 0.01 --quiet -o '" + image.string() + "'");
    REQUIRE_MESSAGE(run.exitCode == 0, run.output);
    INFO(run.output);
    CHECK(contains(run.output, "rendered 16x16, 1 spp (1 frames of 1)"));
    CHECK(contains(run.output, "time limit exceeded by start-up: --time 0.01 s"));
    CHECK_FALSE(contains(run.output, "(library and scene "));  // --quiet: no start-up line, only the final ones
    CHECK(std::filesystem::file_size(image) > 16 * 16 * 12);
}

// --target-error stops at the first frame whose estimate reaches the target (from 8 spp on): every earlier
// report point's estimate is above it, the last one's at or below.
TEST_CASE("ripple-render --target-error stops when the estimate reaches it") {
    TempFolder dir;
    const auto report = dir / "series.csv";
    const ProgramRun run = runRender("--demo cornell --size 16x16 --target-error 0.04 --spp 400 --quiet --report '" +
                                    report.string() + "' -o '" + (dir / "t.png").string() + "'");
    REQUIRE_MESSAGE(run.exitCode == 0, run.output);
    const auto rows = readCsv(report);
    REQUIRE(rows.size() >= 3);
    CHECK(std::stod(rows.back()[2]) <= 0.04);
    CHECK(numberAfter(run.output, "estimated relMSE ") <= 0.04);
    CHECK(std::stoul(rows.back()[1]) >= 8);
    CHECK(std::stoul(rows.back()[1]) < 400);  // reached, not capped
    for (size_t i = 1; i + 1 < rows.size(); ++i)
        if (std::stoul(rows[i][1]) >= 8) CHECK_MESSAGE(std::stod(rows[i][2]) > 0.04, "row " << i);
}

// --report: the CSV has the documented columns, one row per report point with spp rising to --spp, and the
// plot beside it is a PNG of the plot's size.
TEST_CASE("ripple-render --report writes the series as CSV and a plot") {
    TempFolder dir;
    const auto report = dir / "series.csv";
    const auto output = dir / "t.pfm";
    std::string arguments = "--demo cornell --size 16x16 --spp 12 --quiet --report '" + report.string() + "' -o '" +
                            output.string() + "'";
    std::vector<std::string> header{"time_s", "spp", "estimated_relmse", "band_low", "band_high"};
    bool withReference = false;
    SUBCASE("without a reference") {}
    SUBCASE("with a reference: the true error too") {
        std::vector<float> gradient(16 * 16 * 4, 1.0f);  // a ramp across, brighter than the walls on the right
        for (size_t i = 0; i < 16 * 16; ++i)
            for (size_t c = 0; c < 3; ++c) gradient[i * 4 + c] = 0.05f + 0.1f * float(i % 16) + 0.05f * float(c);
        ripple::apps::writePfmBottomUp(dir / "ramp.pfm", 16, 16, gradient.data());
        arguments += " --reference '" + (dir / "ramp.pfm").string() + "'";
        header.insert(header.end(), {"relmse", "psnr_db", "ssim", "flip_ldr", "flip_hdr"});
        withReference = true;
    }
    const ProgramRun run = runRender(arguments);
    REQUIRE_MESSAGE(run.exitCode == 0, run.output);
    const auto rows = readCsv(report);
    REQUIRE(rows.size() == 10);  // header, then spp 2 3 4 5 6 7 8 10 12 (nextReportSpp)
    CHECK(rows[0] == header);
    const std::vector<unsigned long> spp{2, 3, 4, 5, 6, 7, 8, 10, 12};
    for (size_t i = 1; i < rows.size(); ++i) {
        CHECK(rows[i].size() == header.size());
        CHECK(std::stoul(rows[i][1]) == spp[i - 1]);
        CHECK(std::stod(rows[i][2]) > 0.0);
        if (i > 1) CHECK(std::stod(rows[i][0]) >= std::stod(rows[i - 1][0]));
    }
    // The last point is the image written: its columns are that image's metrics against the reference, as
    // ripple-imgdiff's functions compute them (to the CSV's printed digits).
    if (withReference) {
        const ripple::apps::LinearImage image = ripple::apps::readLinearImage(output);
        const ripple::apps::LinearImage reference = ripple::apps::readLinearImage(dir / "ramp.pfm");
        const std::vector<std::string>& last = rows.back();
        const double expected[] = {ripple::apps::relMse(image, reference), ripple::apps::psnr(image, reference),
                                   ripple::apps::ssim(image, reference), ripple::apps::flipLdr(image, reference),
                                   ripple::apps::flipHdr(image, reference)};
        for (size_t k = 0; k < 5; ++k) {
            CAPTURE(header[5 + k]);
            CHECK(std::stod(last[5 + k]) == doctest::Approx(expected[k]).epsilon(1e-4));
        }
        CHECK(expected[2] > 0.0);  // a real SSIM and FLIP, neither 0 nor 1, so a swap shows
        CHECK(expected[2] < 0.9);
        CHECK(expected[3] > 0.05);
    }
    int w = 0, h = 0, comp = 0;
    unsigned char* plot = stbi_load((dir / "series.png").string().c_str(), &w, &h, &comp, 4);
    REQUIRE(plot != nullptr);
    CHECK(w == 880);
    CHECK(h == 560);
    stbi_image_free(plot);
}

// --error-map: the per-pixel estimate, whose mean is the estimate printed (both from the same half-buffers;
// the printed one has 4 significant digits), in PFM; a magma heat map in PNG; a JPEG is refused.
TEST_CASE("ripple-render --error-map writes each pixel's estimated relMSE") {
    TempFolder dir;
    const std::string common = "--demo cornell --size 24x16 --spp 8 --quiet -o '" + (dir / "t.png").string() + "'";
    const ProgramRun run = runRender(common + " --error-map '" + (dir / "map.pfm").string() + "'");
    REQUIRE_MESSAGE(run.exitCode == 0, run.output);
    const ripple::apps::LinearImage map = ripple::apps::readLinearImage(dir / "map.pfm");
    REQUIRE(map.width == 24);
    REQUIRE(map.height == 16);
    double sum = 0.0;
    for (uint32_t y = 0; y < map.height; ++y)
        for (uint32_t x = 0; x < map.width; ++x) {
            CHECK(map.at(x, y, 0) == map.at(x, y, 2));  // grey
            CHECK(map.at(x, y, 0) >= 0.0f);
            sum += map.at(x, y, 0);
        }
    CHECK(sum / (24.0 * 16.0) == doctest::Approx(numberAfter(run.output, "estimated relMSE ")).epsilon(1e-3));
    const ProgramRun png = runRender(common + " --error-map '" + (dir / "map.png").string() + "'");
    REQUIRE_MESSAGE(png.exitCode == 0, png.output);
    int w = 0, h = 0, comp = 0;
    unsigned char* heat = stbi_load((dir / "map.png").string().c_str(), &w, &h, &comp, 3);
    REQUIRE(heat != nullptr);
    CHECK(w == 24);
    CHECK(h == 16);
    // Every PNG pixel is the magma colour of log10 of the PFM's value at the same place, -4 to 0 (same rows).
    int mismatches = 0;
    for (uint32_t y = 0; y < 16; ++y)
        for (uint32_t x = 0; x < 24; ++x) {
            const float value = map.at(x, y, 0);
            const auto expected = ripple::apps::magma(value > 0.0f ? (std::log10(value) + 4.0f) / 4.0f : 0.0f);
            for (int c = 0; c < 3; ++c) mismatches += std::abs(int(heat[(y * 24 + x) * 3 + c]) - int(expected[c])) > 1;
        }
    CHECK(mismatches == 0);
    stbi_image_free(heat);
    const ProgramRun jpeg = runRender(common + " --error-map '" + (dir / "map.jpg").string() + "'");
    CHECK(jpeg.exitCode == 1);
    CHECK(contains(jpeg.output, "give a .png (heat map), .pfm or .exr file"));
}

// --environment lights the scene with an hdri light and replaces the key light and ambient fill a glTF
// without lights gets: rendered twice with the same seed, at intensity 1 and 2, every pixel of the triangle
// doubles (to float rounding) while the background stays as it was, which holds only when the environment
// is the sole source of light. A Radiance .hdr and a PFM read the same.
TEST_CASE("ripple-render --environment: an hdri light scaled by --environment-intensity, nothing else lights the scene") {
    TempFolder dir;
    const auto scene = writeBytes(dir / "triangle.glb", glbBytes(triangleSource()));
    std::vector<float> sky(8 * 4 * 4);
    for (size_t i = 0; i < sky.size(); ++i) sky[i] = i % 4 == 3 ? 1.0f : 0.25f + 0.05f * float((i / 4) % 8);
    const auto environment = dir / "sky.pfm";
    ripple::apps::writePfmBottomUp(environment, 8, 4, sky.data());
    auto render = [&](const char* intensity, const char* name) {
        const auto image = dir / name;
        // Appended piece by piece: GCC 12 warns falsely (-Wrestrict) on "'" + std::string at -O3.
        std::string arguments = "'";
        arguments.append(scene.string()).append("' --size 24x24 --spp 4 --max-path-length 2 --quiet --environment '");
        arguments.append(environment.string()).append("' --environment-intensity ").append(intensity);
        arguments.append(" -o '").append(image.string()).append("'");
        const ProgramRun run = runRender(arguments);
        REQUIRE_MESSAGE(run.exitCode == 0, run.output);
        return ripple::apps::readLinearImage(image);
    };
    const ripple::apps::LinearImage once = render("1", "once.pfm"), twice = render("2", "twice.pfm");
    REQUIRE(once.rgb.size() == twice.rgb.size());
    // Pixels on the triangle's edge mix background (unchanged) and triangle (doubled) samples: brighter,
    // but less than twice as bright.
    uint32_t doubled = 0, unchanged = 0, edge = 0, other = 0;
    for (size_t p = 0; p < once.rgb.size(); p += 3) {
        bool same = true, two = once.rgb[p] > 1e-3f, between = true;
        for (size_t c = 0; c < 3; ++c) {
            same = same && twice.rgb[p + c] == once.rgb[p + c];
            two = two && std::abs(twice.rgb[p + c] - 2.0f * once.rgb[p + c]) <= 1e-5f * twice.rgb[p + c];
            between = between && twice.rgb[p + c] > once.rgb[p + c] && twice.rgb[p + c] < 2.0f * once.rgb[p + c];
        }
        doubled += two;
        unchanged += same && !two;
        edge += !same && !two && between;
        other += !same && !two && !between;
    }
    MESSAGE(doubled << " pixels doubled, " << unchanged << " background, " << edge << " on the edge, " << other << " else");
    CHECK(doubled >= 20);
    CHECK(unchanged >= 20);
    CHECK(edge <= 48);  // about the triangle's perimeter in pixels
    CHECK(other == 0);

    {  // bad environment files are named
        std::vector<float> bad = sky;
        bad[5] = -1.0f;
        const auto negative = dir / "negative.pfm";
        ripple::apps::writePfmBottomUp(negative, 8, 4, bad.data());
        const ProgramRun run = runRender("--demo cornell --size 8x8 --environment '" + negative.string() + "' -o '" +
                                         (dir / "x.png").string() + "'");
        CHECK(run.exitCode == 1);
        CHECK_MESSAGE(contains(run.output, "negative.pfm: holds a negative, NaN or Inf radiance"), run.output);
        const ProgramRun missing = runRender("--demo cornell --size 8x8 --environment '" + (dir / "absent.hdr").string() +
                                             "' -o '" + (dir / "x.png").string() + "'");
        CHECK(missing.exitCode == 1);
        CHECK_MESSAGE(contains(missing.output, "absent.hdr: cannot open the image (no such file)"), missing.output);
    }
}

// A closed, convex, white (baseColor 1, metallic 0) UV sphere of radius 1 at the origin with flat faces (no
// normals: the geometric normal shades): every triangle with its own three vertices, none degenerate.
std::filesystem::path writeWhiteSphere(const std::filesystem::path& file) {
    const int rings = 12, segments = 24;
    std::vector<float> positions;
    const auto point = [&](int ring, int segment) {
        const float theta = 3.14159265f * float(ring) / float(rings), phi = 6.2831853f * float(segment) / float(segments);
        return std::array<float, 3>{std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi)};
    };
    const auto triangle = [&](std::array<float, 3> a, std::array<float, 3> b, std::array<float, 3> c) {
        for (const auto& v : {a, c, b}) positions.insert(positions.end(), v.begin(), v.end());  // outward winding
    };
    for (int r = 0; r < rings; ++r)
        for (int g = 0; g < segments; ++g) {
            if (r > 0) triangle(point(r, g), point(r, g + 1), point(r + 1, g));
            if (r < rings - 1) triangle(point(r, g + 1), point(r + 1, g + 1), point(r + 1, g));
        }
    const size_t count = positions.size() / 3;
    GltfSource sphere;
    sphere.json = "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],"
                  "\"materials\":[{\"pbrMetallicRoughness\":{\"baseColorFactor\":[1,1,1,1],\"metallicFactor\":0,"
                  "\"roughnessFactor\":1}}],"
                  "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"material\":0}]}],"
                  "\"buffers\":[{\"byteLength\":" + std::to_string(positions.size() * 4) + "}],"
                  "\"bufferViews\":[{\"buffer\":0,\"byteLength\":" + std::to_string(positions.size() * 4) + "}],"
                  "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":" + std::to_string(count) +
                  ",\"type\":\"VEC3\",\"min\":[-1,-1,-1],\"max\":[1,1,1]}]}";
    sphere.bin.resize(positions.size() * 4);
    std::memcpy(sphere.bin.data(), positions.data(), sphere.bin.size());
    return writeGlb(file, sphere);
}

// The furnace through the command line: the white sphere lit only by a constant Radiance .hdr environment
// of radiance L reflects L everywhere, however many bounces a path takes (each sees the environment), so
// the pixels inside its silhouette average L.
TEST_CASE("ripple-render --environment: a constant .hdr on a white diffuse sphere gives the furnace result") {
    TempFolder dir;
    const auto scene = writeWhiteSphere(dir / "sphere.glb");
    const float radiance = 0.5f;  // exact in RGBE
    const std::vector<float> sky(16 * 8 * 3, radiance);
    const auto environment = dir / "constant.hdr";
    REQUIRE(stbi_write_hdr(environment.string().c_str(), 16, 8, 3, sky.data()) != 0);
    const auto image = dir / "furnace.pfm";
    std::string arguments = "'";
    arguments.append(scene.string()).append("' --size 32x32 --spp 64 --max-path-length 8 --quiet --environment '");
    arguments.append(environment.string()).append("' -o '").append(image.string()).append("'");
    const ProgramRun run = runRender(arguments);
    REQUIRE_MESSAGE(run.exitCode == 0, run.output);
    const ripple::apps::LinearImage furnace = ripple::apps::readLinearImage(image);
    REQUIRE(furnace.width == 32);
    // The framed view shows the sphere in the middle; its central 8x8 pixels lie well inside the silhouette.
    double sum = 0.0;
    for (uint32_t y = 12; y < 20; ++y)
        for (uint32_t x = 12; x < 20; ++x)
            for (size_t c = 0; c < 3; ++c) sum += furnace.rgb[(size_t(y) * furnace.width + x) * 3 + c];
    const double mean = sum / (8.0 * 8.0 * 3.0);
    MESSAGE("furnace: mean " << mean << " inside the sphere, environment radiance " << radiance);
    CHECK(mean == doctest::Approx(radiance).epsilon(0.02));
}

// --environment-rotation turns the map about +Y: its centre column, seen along -Z at 0 degrees, is seen along
// -X at 90 and along +X at 270 (environmentDirection). A map dark but for a bright band of centre columns
// lights the white sphere from there: from its left at 90 and its right at 270 (the framed camera looks
// down -Z), and from the camera's side at 180, where the face the camera sees is far brighter than at 0.
TEST_CASE("ripple-render --environment-rotation: the map's centre turns to where the rotation says") {
    TempFolder dir;
    const auto scene = writeWhiteSphere(dir / "sphere.glb");
    const int width = 16, height = 8;
    std::vector<float> sky(size_t(width * height * 3), 0.0f);
    for (int y = 0; y < height; ++y)
        for (int x = width / 2 - 1; x <= width / 2; ++x)
            for (int c = 0; c < 3; ++c) sky[size_t((y * width + x) * 3 + c)] = 4.0f;
    const auto environment = dir / "band.hdr";
    REQUIRE(stbi_write_hdr(environment.string().c_str(), width, height, 3, sky.data()) != 0);
    struct Halves {
        double left = 0.0, right = 0.0;
    };
    const auto render = [&](const char* degrees) {
        const auto image = dir / (std::string("turn") + degrees + ".pfm");
        std::string arguments = "'";
        arguments.append(scene.string()).append("' --size 32x32 --spp 16 --max-path-length 2 --quiet --environment '");
        arguments.append(environment.string()).append("' --environment-rotation ").append(degrees);
        arguments.append(" -o '").append(image.string()).append("'");
        const ProgramRun run = runRender(arguments);
        REQUIRE_MESSAGE(run.exitCode == 0, run.output);
        const ripple::apps::LinearImage picture = ripple::apps::readLinearImage(image);
        REQUIRE(picture.width == 32);
        Halves h;  // the sphere's central rows, its left and right thirds
        for (uint32_t y = 12; y < 20; ++y)
            for (uint32_t x = 8; x < 24; ++x)
                if (x < 13 || x >= 19) (x < 16 ? h.left : h.right) += picture.rgb[(size_t(y) * picture.width + x) * 3 + 1];
        return h;
    };
    const Halves turn0 = render("0"), turn90 = render("90"), turn180 = render("180"), turn270 = render("270");
    MESSAGE("left/right thirds: 0: " << turn0.left << "/" << turn0.right << ", 90: " << turn90.left << "/" << turn90.right
                                     << ", 180: " << turn180.left << "/" << turn180.right << ", 270: " << turn270.left
                                     << "/" << turn270.right);
    CHECK(turn90.left > 4.0 * turn90.right);
    CHECK(turn270.right > 4.0 * turn270.left);
    CHECK(turn180.left + turn180.right > 4.0 * (turn0.left + turn0.right));
}

namespace {

// A 16^3 uint8 distance field: 255 - 32 r clamped to 0..255, r the distance in samples from the centre
// (7.5, 7.5, 7.5), so 0..227 (the 128 surface is a sphere of radius 4 samples); or 0 everywhere.
std::vector<uint8_t> sphereField(bool empty) {
    std::vector<uint8_t> v;
    for (int z = 0; z < 16; ++z)
        for (int y = 0; y < 16; ++y)
            for (int x = 0; x < 16; ++x) {
                const double r = std::sqrt((x - 7.5) * (x - 7.5) + (y - 7.5) * (y - 7.5) + (z - 7.5) * (z - 7.5));
                v.push_back(empty ? 0 : uint8_t(std::clamp(255.0 - 32.0 * r, 0.0, 255.0)));
            }
    return v;
}

struct Rgba8 {
    int w = 0, h = 0;
    std::vector<unsigned char> pixels;
    // Mean of channel c over the centre square of side `side`.
    double centreMean(int c, int side) const {
        double sum = 0.0;
        for (int y = (h - side) / 2; y < (h + side) / 2; ++y)
            for (int x = (w - side) / 2; x < (w + side) / 2; ++x) sum += pixels[size_t((y * w + x) * 4 + c)];
        return sum / double(side * side);
    }
};

Rgba8 renderVolume(const std::string& arguments, const std::filesystem::path& image) {
    const ProgramRun run = runRender(arguments + " --size 32x32 --spp 4 --quiet -o '" + image.string() + "'");
    REQUIRE_MESSAGE(run.exitCode == 0, run.output);
    CHECK(contains(run.output, "rendered 32x32, 4 spp"));
    Rgba8 out;
    int comp = 0;
    unsigned char* pixels = stbi_load(image.string().c_str(), &out.w, &out.h, &comp, 4);
    REQUIRE(pixels != nullptr);
    out.pixels.assign(pixels, pixels + size_t(out.w) * size_t(out.h) * 4);
    stbi_image_free(pixels);
    REQUIRE(out.w == 32);
    REQUIRE(out.h == 32);
    return out;
}

}  // namespace

// --volume end to end: a 16^3 sphere distance field, as an isosurface (raw file) and as a volume (the same
// samples through a detached NRRD header), against the same scene with a field of zeros (where neither
// draws anything). The field stands in the middle of the view, so the centre 8x8 pixels change (mean
// absolute difference over RGB, 8-bit sRGB, measured 49 for the isosurface and 113 for the volume); the
// isosurface at 128 of 0..227 takes viridis' middle, teal, so green outweighs red there (measured 1.52x).
TEST_CASE("ripple-render --volume draws a raw or NRRD field as an isosurface or a volume") {
    TempFolder dir;
    const std::string layout = " --dims 16,16,16 --type uint8";
    const std::string sphere = "--volume '" + writeBytes(dir / "sphere.raw", sphereField(false)).string() + "'";
    const std::string zeros = "--volume '" + writeBytes(dir / "zeros.raw", sphereField(true)).string() + "'";
    writeText(dir / "sphere.nhdr", "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 16 16 16\nencoding: raw\n"
                                   "spacings: 1 1 1\ndata file: sphere.raw\n");
    const Rgba8 background = renderVolume(zeros + layout + " --isovalue 128 --tf viridis", dir / "zeros.png");
    const Rgba8 iso = renderVolume(sphere + layout + " --isovalue 128", dir / "iso.png");
    const Rgba8 volume = renderVolume("--volume '" + (dir / "sphere.nhdr").string() + "' --tf viridis --opacity 0.9",
                                      dir / "volume.png");
    const auto difference = [&](const Rgba8& a) {
        double d = 0.0;
        for (int c = 0; c < 3; ++c) d += std::abs(a.centreMean(c, 8) - background.centreMean(c, 8));
        return d / 3.0;
    };
    INFO("iso differs by " << difference(iso) << ", volume by " << difference(volume));
    CHECK(difference(iso) > 25.0);
    CHECK(difference(volume) > 50.0);
    CHECK(iso.centreMean(1, 8) > 1.25 * iso.centreMean(0, 8));
}
