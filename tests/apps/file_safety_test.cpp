// A user's output is never lost, and no input waits on something that is not a file. The helpers
// (io/FileWrite.h, io/FileRead.h) and the programs through them: every output of ripple-render and
// ripple-imgdiff aimed at a full disk (a link to /dev/full, whose writes fail with ENOSPC) or past a file
// size limit ends with exit code 1, a message naming the file and the system's reason, and whatever had the
// name before intact; every input option given /dev/zero or a FIFO is refused at once; a truncated Radiance
// HDR image is refused.
#include "io/FileRead.h"
#include "io/FileWrite.h"
#include "io/image/ImageIO.h"
#include "tests/apps/ProgramRun.h"
#include "tests/apps/TestFiles.h"

#include <doctest/doctest.h>
#include <stb_image_write.h>

#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

using namespace ripple::test;
namespace fs = std::filesystem;

namespace {

std::string readText(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

// The names in a folder: a failed write must leave no temporary file behind.
std::vector<std::string> folderEntries(const fs::path& folder) {
    std::vector<std::string> names;
    for (const fs::directory_entry& e : fs::directory_iterator(folder)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

// A link named `name` in `dir` to /dev/full, where every write fails with ENOSPC: a full disk.
fs::path fullDisk(const TempFolder& dir, const std::string& name) {
    const fs::path link = dir / name;
    fs::create_symlink("/dev/full", link);
    return link;
}

bool pointsToDevFull(const fs::path& link) { return fs::is_symlink(link) && fs::read_symlink(link) == "/dev/full"; }

// The shell prefix that caps the size of files a program writes at 8 KiB (dash counts 512-byte blocks), with
// SIGXFSZ ignored so that a write past it fails with EFBIG instead of killing the program.
const char* kFileSizeCap = "trap '' XFSZ; ulimit -f 16;";

std::string quoted(const fs::path& p) { return "'" + p.string() + "'"; }

// Runs a program and gives its output and the seconds it took.
struct TimedRun {
    ProgramRun run;
    double seconds = 0;
};
TimedRun timedRun(const std::string& program, const std::string& arguments) {
    const auto start = std::chrono::steady_clock::now();
    // A hang is ended after 20 s (exit code 124), so the test fails instead of waiting forever.
    ProgramRun run = runProgram(program, arguments, "timeout 20");
    return {run, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()};
}

// A small RGB image as a Radiance .hdr (stb writes rows of 8 or more pixels run-length encoded, and
// narrower ones flat).
std::string hdrBytes(int width, int height) {
    std::vector<float> rgb(size_t(width) * size_t(height) * 3);
    for (size_t i = 0; i < rgb.size(); ++i) rgb[i] = 0.25f + 0.5f * float(i % 7) / 7.0f;
    std::string bytes;
    const auto append = [](void* context, void* data, int size) {
        static_cast<std::string*>(context)->append(static_cast<const char*>(data), size_t(size));
    };
    REQUIRE(stbi_write_hdr_to_func(append, &bytes, width, height, 3, rgb.data()));
    return bytes;
}

}  // namespace

TEST_CASE("writeFileAtomically: the new content whole, or the old file untouched") {
    TempFolder dir;
    const fs::path file = dir / "out.txt";
    ripple::apps::writeFileAtomically(file, "first\n");
    CHECK(readText(file) == "first\n");
    ripple::apps::writeFileAtomically(file, "second\n");
    CHECK(readText(file) == "second\n");
    CHECK(folderEntries(dir / "") == std::vector<std::string>{"out.txt"});

    SUBCASE("a new file gets the mode the umask allows, a replaced one keeps its own") {
        const mode_t mask = ::umask(0);
        ::umask(mask);
        struct stat st {};
        REQUIRE(::stat(file.c_str(), &st) == 0);
        CHECK((st.st_mode & 0777) == (0666 & ~mask));
        REQUIRE(::chmod(file.c_str(), 0640) == 0);
        ripple::apps::writeFileAtomically(file, "third\n");
        REQUIRE(::stat(file.c_str(), &st) == 0);
        CHECK((st.st_mode & 0777) == 0640);
    }
    SUBCASE("a symbolic link is followed and stays a link") {
        const fs::path link = dir / "link.txt";
        fs::create_symlink(file, link);
        ripple::apps::writeFileAtomically(link, "through the link\n");
        CHECK(fs::is_symlink(link));
        CHECK(readText(file) == "through the link\n");
    }
    SUBCASE("a full disk: ENOSPC, named, and the link left as it was") {
        const fs::path link = fullDisk(dir, "full.txt");
        try {
            ripple::apps::writeFileAtomically(link, "lost\n", "the report");
            FAIL("a write to /dev/full succeeded");
        } catch (const std::runtime_error& e) {
            CHECK_MESSAGE(contains(e.what(), link.string() + ": cannot write the report: No space left on device (ENOSPC)"),
                          e.what());
        }
        CHECK(pointsToDevFull(link));
    }
    SUBCASE("past the file size limit: EFBIG, the old content intact, no temporary file left") {
        const int child = ::fork();
        REQUIRE(child >= 0);
        if (child == 0) {  // the limit would stay with the test process: a child of its own takes it
            std::signal(SIGXFSZ, SIG_IGN);
            const rlimit limit{4096, 4096};
            ::setrlimit(RLIMIT_FSIZE, &limit);
            try {
                ripple::apps::writeFileAtomically(file, std::string(100000, 'x'));
            } catch (const std::runtime_error& e) {
                std::ofstream(dir / "message") << e.what();  // 0 bytes past the limit: a short file is fine
                ::_exit(contains(e.what(), "File too large (EFBIG)") ? 0 : 2);
            }
            ::_exit(1);
        }
        int status = 0;
        REQUIRE(::waitpid(child, &status, 0) == child);
        CHECK_MESSAGE(WIFEXITED(status), "the child was killed");
        CHECK_MESSAGE(WEXITSTATUS(status) == 0, readText(dir / "message"));
        CHECK(readText(file) == "second\n");
        CHECK(folderEntries(dir / "") == std::vector<std::string>{"message", "out.txt"});
    }
    SUBCASE("a folder of that name is refused") {
        fs::create_directory(dir / "folder");
        CHECK_THROWS_WITH_AS(ripple::apps::writeFileAtomically(dir / "folder", "x"),
                             doctest::Contains("cannot write the file: Is a directory (EISDIR)"), std::runtime_error);
    }
    SUBCASE("a FIFO with no reader is refused, not waited on") {
        REQUIRE(::mkfifo((dir / "fifo").c_str(), 0600) == 0);
        const auto start = std::chrono::steady_clock::now();
        CHECK_THROWS_WITH_AS(ripple::apps::writeFileAtomically(dir / "fifo", "x"),
                             doctest::Contains("a FIFO with no reader"), std::runtime_error);
        CHECK(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() < 1.0);
    }
}

TEST_CASE("checkWritable touches nothing of the target") {
    TempFolder dir;
    const fs::path file = writeText(dir / "kept.png", "old");
    ripple::apps::checkWritable(file, "the image");
    CHECK(readText(file) == "old");
    ripple::apps::checkWritable(dir / "new.png", "the image");
    CHECK(folderEntries(dir / "") == std::vector<std::string>{"kept.png"});
    CHECK_THROWS_WITH_AS(ripple::apps::checkWritable(dir / "absent" / "x.png", "the image"),
                         doctest::Contains("x.png: cannot write the image there: No such file or directory (ENOENT)"),
                         std::runtime_error);
}

TEST_CASE("readRegularFile refuses at once what is not a regular file") {
    TempFolder dir;
    REQUIRE(::mkfifo((dir / "fifo").c_str(), 0600) == 0);
    fs::create_directory(dir / "folder");
    const fs::path big = writeText(dir / "big", std::string(2000, 'x'));
    struct Case {
        fs::path file;
        std::string expected;
    };
    for (const Case& c : {Case{"/dev/zero", "is not a regular file (a character device)"},
                          Case{dir / "fifo", "is not a regular file (a FIFO)"},
                          Case{dir / "folder", "is not a regular file (a directory)"},
                          Case{dir / "absent", "no such file"},
                          Case{big, "2000 bytes is larger than the limit of 1000"}}) {
        CAPTURE(c.file);
        const auto start = std::chrono::steady_clock::now();
        const std::string expected = c.file.string() + ": the image: " + c.expected;
        CHECK_THROWS_WITH_AS(ripple::apps::readRegularFile(c.file, 1000, "the image"), doctest::Contains(expected.c_str()),
                             std::runtime_error);
        CHECK(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() < 1.0);
    }
    CHECK(ripple::apps::readRegularFile(big, 2000, "the image").size() == 2000);
}

TEST_CASE("truncated images are refused: Radiance HDR, PNG, EXR") {
    TempFolder dir;
    std::vector<float> noise(32 * 32 * 4);
    for (size_t i = 0; i < noise.size(); ++i) noise[i] = float((i * 2654435761u) >> 20) / 4096.0f;
    ripple::apps::writePngFromLinearBottomUp(dir / "whole.png", 32, 32, noise.data());
    ripple::apps::writeExrBottomUp(dir / "whole.exr", 32, 32, noise.data());
    for (const char* format : {"png", "exr"}) {
        const std::string bytes = readText(dir / (std::string("whole.") + format));
        for (const size_t kept : {bytes.size() - 20, bytes.size() / 2, size_t(100)}) {
            CAPTURE(format);
            CAPTURE(kept);
            const fs::path cut = writeText(dir / (std::string("cut.") + format), bytes.substr(0, kept));
            CHECK_THROWS_WITH_AS(ripple::apps::readLinearImage(cut), doctest::Contains("malformed image"), std::runtime_error);
        }
    }
    for (const int width : {4, 16}) {  // flat rows, run-length encoded rows
        CAPTURE(width);
        const std::string bytes = hdrBytes(width, 6);
        const fs::path whole = writeText(dir / "whole.hdr", bytes);
        const ripple::apps::LinearImage image = ripple::apps::readLinearImage(whole);
        CHECK(image.width == uint32_t(width));
        CHECK(image.height == 6);
        // Cut in the last row, and after the header with no pixels at all.
        const size_t header = bytes.find("\n\n") + 2 + std::string("-Y 6 +X ").size() + std::to_string(width).size() + 1;
        for (const size_t kept : {bytes.size() - 5, header}) {
            CAPTURE(kept);
            const fs::path cut = writeText(dir / "cut.hdr", bytes.substr(0, kept));
            CHECK_THROWS_WITH_AS(ripple::apps::readLinearImage(cut), doctest::Contains("cut.hdr: malformed image: Radiance HDR"),
                                 std::runtime_error);
        }
    }
}

TEST_CASE("ripple-render: an output on a full disk fails the run, named, and the link stays") {
    TempFolder dir;
    const std::string render = "--demo cornell --size 16x16 --spp 2 -q ";
    struct Case {
        std::string name, arguments, what;
    };
    // Each output ripple-render writes; `name` is the one on the full disk ({} in the arguments, or the plot
    // beside --report's CSV).
    for (const Case& c : {Case{"out.png", "-o {}", "the image"}, Case{"out.jpg", "-o {}", "the image"},
                          Case{"out.pfm", "-o {}", "the image"}, Case{"out.exr", "-o {}", "the image"},
                          Case{"layers.exr", "--channels depth,normal,albedo -o {}", "the image"},
                          Case{"map.png", "--error-map {} -o " + quoted(dir / "a.png"), "the image"},
                          Case{"map.exr", "--error-map {} -o " + quoted(dir / "b.png"), "the image"},
                          Case{"report.csv", "--report {} -o " + quoted(dir / "c.png"), "the report"},
                          Case{"plot.png", "--report " + quoted(dir / "plot.csv") + " -o " + quoted(dir / "d.png"),
                               "the image"}}) {
        CAPTURE(c.name);
        const fs::path link = fullDisk(dir, c.name);
        std::string arguments = c.arguments;
        if (const size_t at = arguments.find("{}"); at != std::string::npos) arguments.replace(at, 2, quoted(link));
        const ProgramRun run = runProgram(RIPPLE_RENDER_PATH, render + arguments);
        CHECK_MESSAGE(run.exitCode == 1, run.output);
        CHECK_MESSAGE(contains(run.output, c.name + ": cannot write " + c.what + ": No space left on device (ENOSPC)"),
                      run.output);
        CHECK(pointsToDevFull(link));
    }
}

// ripple-render cannot run under a file size limit (lavapipe's device memory is a memory file, cut by it), so a
// failed write to a regular file is shown through ripple-imgdiff, whose outputs go through the same writer.
TEST_CASE("ripple-imgdiff past a file size limit: exit 1, the previous file intact, nothing beside it") {
    TempFolder dir;
    // Two images of noise: their heat map (a PNG of 128x128 noisy pixels) is past the cap too.
    std::vector<uint8_t> a(128 * 128 * 4), b(a.size());
    for (size_t i = 0; i < a.size(); ++i) {
        a[i] = uint8_t((i * 2654435761u) >> 24);
        b[i] = uint8_t((i * 40503u + 7) >> 3);
    }
    const fs::path test = writeBytes(dir / "test.png", pngBytes(128, 128, a));
    const fs::path reference = writeBytes(dir / "reference.png", pngBytes(128, 128, b));
    const fs::path heatmap = writeText(dir / "heat.png", "the previous heat map\n");
    const ProgramRun diff = runProgram(RIPPLE_IMGDIFF_PATH, quoted(test) + " " + quoted(reference) + " --heatmap " +
                                                                quoted(heatmap), kFileSizeCap);
    CHECK_MESSAGE(diff.exitCode == 1, diff.output);
    CHECK_MESSAGE(contains(diff.output, "heat.png: cannot write the image: File too large (EFBIG)"), diff.output);
    CHECK(readText(heatmap) == "the previous heat map\n");
    CHECK(folderEntries(dir / "") == std::vector<std::string>{"heat.png", "reference.png", "test.png"});

    // Its JSON on a full disk.
    const fs::path json = fullDisk(dir, "results.json");
    const ProgramRun full = runProgram(RIPPLE_IMGDIFF_PATH, quoted(test) + " " + quoted(reference) + " --json " + quoted(json));
    CHECK_MESSAGE(full.exitCode == 1, full.output);
    CHECK_MESSAGE(contains(full.output, "results.json: cannot write the JSON results: No space left on device (ENOSPC)"),
                  full.output);
    CHECK(pointsToDevFull(json));
}

TEST_CASE("every input option refuses /dev/zero and a FIFO at once, by name") {
    TempFolder dir;
    const fs::path image = writeBytes(dir / "image.png", pngBytes(2, 2, std::vector<uint8_t>(16, 128)));
    for (const char* name : {"scene.glb", "sky.hdr", "view.json", "reference.pfm", "field.raw", "test.png"})
        REQUIRE(::mkfifo((dir / name).c_str(), 0600) == 0);
    struct Case {
        std::string program, arguments, fifo;
    };
    const std::string render = RIPPLE_RENDER_PATH, imgdiff = RIPPLE_IMGDIFF_PATH;
    const std::string out = " --size 16x16 --spp 1 -o " + quoted(dir / "out.png");
    for (const Case& c : {Case{render, "{}" + out, "scene.glb"}, Case{render, "--environment {}" + out, "sky.hdr"},
                          Case{render, "--view {}" + out, "view.json"}, Case{render, "--reference {}" + out, "reference.pfm"},
                          Case{render, "--volume {} --dims 4,4,4 --type uint8" + out, "field.raw"},
                          Case{imgdiff, "{} " + quoted(image), "test.png"}, Case{imgdiff, quoted(image) + " {}", "test.png"}}) {
        for (const fs::path& input : {fs::path("/dev/zero"), dir / c.fifo}) {
            std::string arguments = c.arguments;
            arguments.replace(arguments.find("{}"), 2, quoted(input));
            CAPTURE(arguments);
            const TimedRun t = timedRun(c.program, arguments);
            CHECK_MESSAGE(t.run.exitCode == 1, t.run.output);
            CHECK_MESSAGE(contains(t.run.output, input.string()), t.run.output);
            CHECK_MESSAGE(contains(t.run.output, "is not a regular file"), t.run.output);
            MESSAGE(t.seconds << " s: " << c.program.substr(c.program.rfind('/') + 1) << " " << arguments);
            CHECK(t.seconds < 1.0);
        }
    }
}
