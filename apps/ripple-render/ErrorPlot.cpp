// Log-log plot on a small RGBA8 canvas: decade grid with labelled ticks, thick polylines with point marks,
// and text from stb_easy_font's quads scaled up for legibility.
#include "apps/ripple-render/ErrorPlot.h"

#include "io/image/ImageIO.h"

#include <stb_easy_font.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace ripple::apps {
namespace {

using Color = std::array<uint8_t, 3>;
constexpr Color kBlack{0, 0, 0}, kGrid{225, 225, 225}, kGuide{140, 140, 140}, kEstimate{31, 119, 180},
    kBand{198, 219, 239}, kTrue{214, 39, 40};

// RGBA8 pixels, row 0 at the top (as text is laid out); flipped when written.
class Canvas {
public:
    Canvas(int width, int height) : width_(width), height_(height), rgba_(size_t(width) * height * 4, 255) {}

    void fill(int x0, int y0, int x1, int y1, Color c) {  // [x0, x1) x [y0, y1), clipped to the clip box
        x0 = std::max(x0, clip_[0]), y0 = std::max(y0, clip_[1]);
        x1 = std::min(x1, clip_[2]), y1 = std::min(y1, clip_[3]);
        for (int y = y0; y < y1; ++y)
            for (int x = x0; x < x1; ++x) {
                uint8_t* p = &rgba_[(size_t(y) * width_ + x) * 4];
                p[0] = c[0], p[1] = c[1], p[2] = c[2];
            }
    }
    // A line `thickness` pixels wide; dashed lines draw 8 steps of every 14.
    void line(double x0, double y0, double x1, double y1, Color c, int thickness, bool dashed = false) {
        const int steps = std::max(1, int(std::ceil(std::max(std::abs(x1 - x0), std::abs(y1 - y0)))));
        const int lo = -(thickness / 2), hi = lo + thickness;
        for (int i = 0; i <= steps; ++i) {
            if (dashed && i % 14 >= 8) continue;
            const double t = double(i) / steps;
            const int x = int(std::lround(x0 + (x1 - x0) * t)), y = int(std::lround(y0 + (y1 - y0) * t));
            fill(x + lo, y + lo, x + hi, y + hi, c);
        }
    }
    // Text with its top-left corner at (x, y), each font pixel `scale` pixels wide; rotated a quarter turn
    // counter-clockwise (reading upwards, the top-left corner then at the bottom-left) when `vertical`.
    void text(int x, int y, const std::string& s, Color c, int scale, bool vertical = false) {
        std::string copy = s;  // stb_easy_font takes char*
        std::vector<char> vertices(270 * (s.size() + 1));  // its documentation: about 270 bytes a character
        const int quads = stb_easy_font_print(0.0f, 0.0f, copy.data(), nullptr, vertices.data(), int(vertices.size()));
        for (int q = 0; q < quads; ++q) {
            float corner[2][2];  // top-left and bottom-right of the quad (vertices 0 and 2, 16 bytes each)
            for (int v = 0; v < 2; ++v)
                std::memcpy(corner[v], vertices.data() + size_t(q) * 64 + size_t(v) * 32, 2 * sizeof(float));
            const int qx0 = int(corner[0][0]) * scale, qy0 = int(corner[0][1]) * scale;
            const int qx1 = int(corner[1][0]) * scale, qy1 = int(corner[1][1]) * scale;
            if (vertical) fill(x + qy0, y - qx1, x + qy1, y - qx0, c);
            else fill(x + qx0, y + qy0, x + qx1, y + qy1, c);
        }
    }
    static int textWidth(const std::string& s, int scale) {
        std::string copy = s;
        return stb_easy_font_width(copy.data()) * scale;
    }
    void setClip(int x0, int y0, int x1, int y1) { clip_ = {x0, y0, x1, y1}; }
    void resetClip() { clip_ = {0, 0, width_, height_}; }

    void writePng(const std::filesystem::path& file) const {
        std::vector<uint8_t> bottomUp(rgba_.size());
        const size_t row = size_t(width_) * 4;
        for (int y = 0; y < height_; ++y)
            std::copy_n(&rgba_[size_t(height_ - 1 - y) * row], row, &bottomUp[size_t(y) * row]);
        writePngBottomUp(file, uint32_t(width_), uint32_t(height_), bottomUp.data());
    }

private:
    int width_, height_;
    std::vector<uint8_t> rgba_;
    std::array<int, 4> clip_{0, 0, width_, height_};
};

// Whole decades [lo, hi] of 10 covering the values, at least one decade wide.
std::pair<int, int> decadeRange(const std::vector<double>& values) {
    const auto [mn, mx] = std::minmax_element(values.begin(), values.end());
    int lo = int(std::floor(std::log10(*mn))), hi = int(std::ceil(std::log10(*mx)));
    if (hi <= lo) hi = lo + 1;
    return {lo, hi};
}

std::string decadeLabel(int exponent) {
    if (exponent >= -3 && exponent <= 4) {
        char text[16];
        std::snprintf(text, sizeof text, "%g", std::pow(10.0, exponent));
        return text;
    }
    return "1e" + std::to_string(exponent);
}

}  // namespace

void writeErrorPlot(const std::filesystem::path& file, const std::vector<ConvergencePoint>& points,
                    const std::string& title) {
    std::vector<const ConvergencePoint*> estimate, truth;
    std::vector<double> times, errors;
    for (const ConvergencePoint& p : points) {
        if (!(p.seconds > 0.0)) continue;
        const ErrorEstimate& e = p.estimate;
        if (e.relMse > 0.0 && e.low > 0.0 && std::isfinite(e.high)) {
            estimate.push_back(&p);
            times.push_back(p.seconds);
            errors.insert(errors.end(), {e.low, e.high});
        }
        if (p.reference && p.reference->relMse > 0.0 && std::isfinite(p.reference->relMse)) {
            truth.push_back(&p);
            times.push_back(p.seconds);
            errors.push_back(p.reference->relMse);
        }
    }
    if (times.empty()) throw std::runtime_error(file.string() + ": no report point with a positive time and error to plot");

    constexpr int kWidth = 880, kHeight = 560, kScale = 2;
    constexpr int left = 110, right = kWidth - 30, top = 56, bottom = kHeight - 76;
    Canvas canvas(kWidth, kHeight);
    const auto [xLo, xHi] = decadeRange(times);
    const auto [yLo, yHi] = decadeRange(errors);
    const auto px = [&, xLo = xLo, xHi = xHi](double t) { return left + (std::log10(t) - xLo) / (xHi - xLo) * (right - left); };
    const auto py = [&, yLo = yLo, yHi = yHi](double e) { return bottom - (std::log10(e) - yLo) / (yHi - yLo) * (bottom - top); };

    // Grid at 1..9 times each decade, darker ticks and labels at the decades.
    for (int d = xLo; d <= xHi; ++d)
        for (int m = 1; m <= (d < xHi ? 9 : 1); ++m) {
            const int x = int(std::lround(px(m * std::pow(10.0, d))));
            canvas.line(x, top, x, bottom, kGrid, 1);
            canvas.line(x, bottom, x, bottom + (m == 1 ? 8 : 4), kBlack, 1);
            if (m == 1) {
                const std::string label = decadeLabel(d);
                canvas.text(x - Canvas::textWidth(label, kScale) / 2, bottom + 14, label, kBlack, kScale);
            }
        }
    for (int d = yLo; d <= yHi; ++d)
        for (int m = 1; m <= (d < yHi ? 9 : 1); ++m) {
            const int y = int(std::lround(py(m * std::pow(10.0, d))));
            canvas.line(left, y, right, y, kGrid, 1);
            canvas.line(left - (m == 1 ? 8 : 4), y, left, y, kBlack, 1);
            if (m == 1) {
                const std::string label = decadeLabel(d);
                canvas.text(left - 14 - Canvas::textWidth(label, kScale), y - 6, label, kBlack, kScale);
            }
        }
    canvas.line(left, top, left, bottom, kBlack, 2);
    canvas.line(left, bottom, right, bottom, kBlack, 2);
    canvas.line(left, top, right, top, kBlack, 1);
    canvas.line(right, top, right, bottom, kBlack, 1);

    const std::string xLabel = "render time (s)", yLabel = "relMSE";
    canvas.text((left + right - Canvas::textWidth(xLabel, kScale)) / 2, kHeight - 34, xLabel, kBlack, kScale);
    canvas.text(16, (top + bottom + Canvas::textWidth(yLabel, kScale)) / 2, yLabel, kBlack, kScale, true);
    canvas.text((kWidth - Canvas::textWidth(title, kScale)) / 2, 18, title, kBlack, kScale);

    // Series, clipped to the plot area.
    canvas.setClip(left + 1, top + 1, right, bottom);
    // The estimate's band, filled column by column between the points (straight on the log axes).
    for (size_t i = 1; i < estimate.size(); ++i) {
        const ErrorEstimate &a = estimate[i - 1]->estimate, &b = estimate[i]->estimate;
        const double xa = px(estimate[i - 1]->seconds), xb = px(estimate[i]->seconds);
        for (int x = int(std::lround(xa)); x <= int(std::lround(xb)); ++x) {
            const double t = xb > xa ? std::clamp((x - xa) / (xb - xa), 0.0, 1.0) : 0.0;
            const double yLow = py(a.low) + (py(b.low) - py(a.low)) * t, yHigh = py(a.high) + (py(b.high) - py(a.high)) * t;
            canvas.fill(x, int(std::lround(yHigh)), x + 1, int(std::lround(yLow)) + 1, kBand);
        }
    }
    if (!estimate.empty()) {  // error ~ 1/time through the last estimate, where start-up costs weigh least
        const double t0 = estimate.back()->seconds, e0 = estimate.back()->estimate.relMse;
        const double tLo = std::pow(10.0, xLo), tHi = std::pow(10.0, xHi);
        canvas.line(px(tLo), py(e0 * t0 / tLo), px(tHi), py(e0 * t0 / tHi), kGuide, 2, true);
    }
    const auto drawSeries = [&](const std::vector<const ConvergencePoint*>& series, auto error, Color c) {
        for (size_t i = 0; i < series.size(); ++i) {
            const double x = px(series[i]->seconds), y = py(error(*series[i]));
            if (i > 0) canvas.line(px(series[i - 1]->seconds), py(error(*series[i - 1])), x, y, c, 2);
            canvas.fill(int(x) - 3, int(y) - 3, int(x) + 4, int(y) + 4, c);
        }
    };
    drawSeries(estimate, [](const ConvergencePoint& p) { return p.estimate.relMse; }, kEstimate);
    drawSeries(truth, [](const ConvergencePoint& p) { return p.reference->relMse; }, kTrue);
    canvas.resetClip();

    // Legend, top right inside the plot.
    struct Entry { std::string text; Color color; bool dashed; };
    std::vector<Entry> legend{{"estimated (half buffers)", kEstimate, false}, {"its band", kBand, false}};
    if (!truth.empty()) legend.push_back({"true (against reference)", kTrue, false});
    legend.push_back({"slope -1 (error ~ 1/time)", kGuide, true});
    int legendWidth = 0;
    for (const Entry& e : legend) legendWidth = std::max(legendWidth, Canvas::textWidth(e.text, kScale));
    const int lx = right - legendWidth - 70, ly = top + 12;
    canvas.fill(lx - 8, ly - 8, right - 8, ly + int(legend.size()) * 24 + 2, Color{255, 255, 255});
    for (size_t i = 0; i < legend.size(); ++i) {
        const int y = ly + int(i) * 24;
        canvas.line(lx, y + 7, lx + 40, y + 7, legend[i].color, 2, legend[i].dashed);
        canvas.text(lx + 52, y, legend[i].text, kBlack, kScale);
    }
    canvas.writePng(file);
}

}  // namespace ripple::apps
