// ripple-composite-bench: how long mpi/Compositor takes to depth-composite one RGBA-z frame from every
// rank, and how many bytes the ranks move for it (run under mpirun); prints a line and writes JSON.
#include "io/FileWrite.h"
#include "mpi/Communicator.h"
#include "mpi/Compositor.h"
#include "mpi/Runtime.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

struct Options {
    uint32_t width = 1920, height = 1080;
    uint32_t repeat = 9;
    double coverage = 0.5;  // fraction of each rank's pixels that hold a surface
    std::string json = "ripple-composite-bench.json";
    std::string pattern = "noise";
    std::string method = "auto";
};

// This rank's image: a surface on about `coverage` of the pixels (chosen by a hash of pixel and rank, so
// the ranks overlap as independent layers would), half of them half transparent, premultiplied; the rest
// background (infinite depth, transparent). Pattern "noise" draws each pixel on its own (the worst case:
// no two neighbours alike); "blocks" draws each 32x32 block as a whole, as a rendered part of a scene
// covers the screen in patches.
void makeImage(const Options& o, int rank, std::vector<float>& rgba, std::vector<float>& depth) {
    const size_t pixels = size_t(o.width) * o.height;
    rgba.assign(pixels * 4, 0.0f);
    depth.assign(pixels, INFINITY);
    const bool blocks = o.pattern == "blocks";
    for (size_t p = 0; p < pixels; ++p) {
        const size_t cell = blocks ? (p % o.width) / 32 + (p / o.width / 32) * 4096 : p;
        uint32_t h = uint32_t(cell) * 2654435761u ^ uint32_t(rank + 1) * 2246822519u;
        h ^= h >> 15;
        h *= 2246822519u;
        h ^= h >> 13;
        if (double(h & 0xFFFFu) / 65536.0 >= o.coverage) continue;
        const float alpha = (h >> 16) & 1u ? 1.0f : 0.5f;
        for (int c = 0; c < 3; ++c) rgba[p * 4 + size_t(c)] = alpha * 0.25f * float(c + 1);
        rgba[p * 4 + 3] = alpha;
        depth[p] = 1.0f + float((h >> 17) & 0xFFu);
    }
}

int run(const Options& o, const ripple::mpi::Communicator& ranks) {
    std::vector<float> rgba, depth;
    makeImage(o, ranks.rank(), rgba, depth);
    ripple::mpi::Compositor compositor(ranks, *ripple::mpi::parseCompositeMethod(o.method));
    std::string rounds;
    for (uint32_t k : compositor.rounds()) rounds += (rounds.empty() ? "" : "x") + std::to_string(k);
    compositor.resize(o.width, o.height);
    compositor.composite(rgba, depth);  // warm-up: first-touch of the buffers
    std::vector<double> seconds;
    uint64_t bytes = 0;
    for (uint32_t i = 0; i < o.repeat; ++i) {
        ranks.barrier();
        const auto start = std::chrono::steady_clock::now();
        compositor.composite(rgba, depth);
        ranks.barrier();  // the composite is done when the slowest rank is
        seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
        bytes = ranks.sum(compositor.bytesSent());
    }
    if (ranks.rank() != 0) return 0;
    std::sort(seconds.begin(), seconds.end());
    const double median = seconds[seconds.size() / 2];
    std::printf("ripple-composite-bench: %d rank(s), %s (rounds %s), %ux%u RGBA-z (%.0f%% coverage per rank, %s): "
                "%.2f ms per composite (median of %u, min %.2f, max %.2f), %.2f MiB moved per frame (all ranks)\n",
                ranks.size(), o.method.c_str(), rounds.empty() ? "none" : rounds.c_str(), o.width, o.height,
                100.0 * o.coverage, o.pattern.c_str(), 1e3 * median, o.repeat, 1e3 * seconds.front(),
                1e3 * seconds.back(), double(bytes) / 1048576.0);
    std::ostringstream out;
    out << "{\n  \"ranks\": " << ranks.size() << ",\n  \"width\": " << o.width << ",\n  \"height\": " << o.height
        << ",\n  \"coverage\": " << o.coverage << ",\n  \"pattern\": \"" << o.pattern << "\",\n  \"method\": \""
        << o.method << "\",\n  \"rounds\": \"" << rounds << "\",\n  \"repeat\": " << o.repeat
        << ",\n  \"medianSeconds\": " << median << ",\n  \"minSeconds\": " << seconds.front()
        << ",\n  \"maxSeconds\": " << seconds.back() << ",\n  \"bytesPerFrame\": " << bytes << "\n}\n";
    ripple::apps::writeFileAtomically(o.json, out.str(), "the benchmark results");
    std::printf("wrote %s\n", o.json.c_str());
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    ripple::mpi::Runtime runtime(&argc, &argv);
    const ripple::mpi::Communicator ranks = ripple::mpi::Communicator::world();
    Options options;
    CLI::App app{"ripple-composite-bench: time and bytes of depth compositing one RGBA-z frame over the MPI ranks"};
    app.add_option("--width", options.width, "image width")->check(CLI::Range(1u, 16384u))->capture_default_str();
    app.add_option("--height", options.height, "image height")->check(CLI::Range(1u, 16384u))->capture_default_str();
    app.add_option("--repeat", options.repeat, "timed composites (the median is reported)")
        ->check(CLI::Range(1u, 1000u))->capture_default_str();
    app.add_option("--coverage", options.coverage, "fraction of each rank's pixels covered by a surface")
        ->check(CLI::Range(0.0, 1.0))->capture_default_str();
    app.add_option("--pattern", options.pattern,
                   "which pixels are covered: noise (each pixel drawn alone) or blocks (32x32 blocks drawn whole)")
        ->check(CLI::IsMember({"noise", "blocks"}))->capture_default_str();
    app.add_option("--method", options.method,
                   "compositing rounds: auto (radix-k, groups of at most 8), directSend, binarySwap (power-of-two "
                   "rank counts) or radixK")
        ->check(CLI::IsMember({"auto", "directSend", "binarySwap", "radixK"}))->capture_default_str();
    app.add_option("--json", options.json, "where rank 0 writes the numbers")->capture_default_str();
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return ranks.rank() == 0 ? app.exit(e) : (e.get_exit_code() == 0 ? 0 : 1);
    }
    try {
        return run(options, ranks);
    } catch (const std::exception& e) {
        if (ranks.distributed()) ranks.abort(std::string("ripple-composite-bench: ") + e.what());
        std::fprintf(stderr, "[ripple-composite-bench] ERROR: %s\n", e.what());
        return 1;
    }
}
