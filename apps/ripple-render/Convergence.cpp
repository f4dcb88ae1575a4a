// The report series, its CSV and the render clock.
#include "apps/ripple-render/Convergence.h"

#include "io/FileWrite.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

namespace ripple::apps {

ReferenceMetrics compareToReference(const LinearImage& image, const LinearImage& reference, const FlipReference& flip) {
    ReferenceMetrics m;
    m.relMse = relMse(image, reference, kRelMseEpsilon);
    m.psnr = psnr(image, reference);
    m.ssim = ssim(image, reference);
    m.flipLdr = flip.ldr(image);
    m.flipHdr = flip.hdr(image);
    return m;
}

uint32_t nextReportSpp(uint32_t spp) {
    const uint32_t next = std::max(spp + 1, uint32_t(std::lround(double(spp) * 1.2)));
    uint32_t powerOfTwo = 1;
    while (powerOfTwo <= spp) powerOfTwo *= 2;
    return std::min(next, powerOfTwo);
}

std::string formatConvergencePoint(const ConvergencePoint& point) {
    char line[256];
    int n = std::snprintf(line, sizeof line, "%8.2f s %7u spp  estimated relMSE %.3e (%.1e .. %.1e)", point.seconds,
                          point.spp, point.estimate.relMse, point.estimate.low, point.estimate.high);
    if (point.reference && n > 0 && size_t(n) < sizeof line) {
        const ReferenceMetrics& r = *point.reference;
        std::snprintf(line + n, sizeof line - size_t(n), "  relMSE %.3e  PSNR %.2f dB  SSIM %.4f  FLIP %.4f (HDR %.4f)",
                      r.relMse, r.psnr, r.ssim, r.flipLdr, r.flipHdr);
    }
    return line;
}

void writeConvergenceCsv(const std::filesystem::path& file, const std::vector<ConvergencePoint>& points) {
    std::ostringstream out;
    const bool withReference = !points.empty() && points.front().reference.has_value();
    out << "time_s,spp,estimated_relmse,band_low,band_high" << (withReference ? ",relmse,psnr_db,ssim,flip_ldr,flip_hdr" : "") << "\n";
    char line[256];
    for (const ConvergencePoint& p : points) {
        std::snprintf(line, sizeof line, "%.4f,%u,%.6e,%.6e,%.6e", p.seconds, p.spp, p.estimate.relMse, p.estimate.low,
                      p.estimate.high);
        out << line;
        if (withReference && p.reference) {
            const ReferenceMetrics& r = *p.reference;
            std::snprintf(line, sizeof line, ",%.6e,%.4f,%.6f,%.6f,%.6f", r.relMse, r.psnr, r.ssim, r.flipLdr, r.flipHdr);
            out << line;
        }
        out << "\n";
    }
    writeFileAtomically(file, out.str(), "the report");
}

double RenderClock::seconds() const {
    const auto now = paused_ ? pausedAt_ : std::chrono::steady_clock::now();
    return std::chrono::duration<double>(now - start_).count() - excluded_;
}

void RenderClock::pause() {
    if (paused_) return;
    paused_ = true;
    pausedAt_ = std::chrono::steady_clock::now();
}

void RenderClock::resume() {
    if (!paused_) return;
    paused_ = false;
    excluded_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - pausedAt_).count();
}

}  // namespace ripple::apps
