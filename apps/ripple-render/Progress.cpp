// Progress line on stderr; the estimate assumes every remaining sample costs what the ones so far did.
#include "apps/ripple-render/Progress.h"

#include <unistd.h>

#include <cstdio>

namespace ripple::apps {

Progress::Progress(uint32_t totalSamples, bool enabled)
    : total_(totalSamples), enabled_(enabled), terminal_(isatty(STDERR_FILENO) != 0),
      start_(std::chrono::steady_clock::now()) {}

double Progress::elapsedSeconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

void Progress::update(uint32_t samplesDone, float raysPerSecond) {
    if (!enabled_) return;
    const double elapsed = elapsedSeconds();
    const double fraction = total_ ? double(samplesDone) / double(total_) : 1.0;
    constexpr int kWidth = 30;
    char bar[kWidth + 1];
    const int filled = int(fraction * kWidth + 0.5);
    for (int i = 0; i < kWidth; ++i) bar[i] = i < filled ? '#' : '.';
    bar[kWidth] = '\0';
    const double eta = samplesDone ? elapsed * (double(total_) - double(samplesDone)) / double(samplesDone) : 0.0;
    std::fprintf(stderr, "%s[%s] %u/%u spp  %.1f s  ETA %.1f s", terminal_ ? "\r" : "", bar, samplesDone, total_,
                 elapsed, eta);
    if (raysPerSecond > 0.0f) std::fprintf(stderr, "  %.2f Mrays/s", double(raysPerSecond) * 1e-6);
    std::fprintf(stderr, terminal_ ? "  " : "\n");
    std::fflush(stderr);
}

void Progress::finish() {
    if (enabled_ && terminal_) std::fprintf(stderr, "\n");
}

}  // namespace ripple::apps
