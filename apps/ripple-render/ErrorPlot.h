// The error-against-time plot of ripple-render's --report: relMSE over render time on log-log axes, drawn
// into an RGBA8 image (lines by hand, labels with stb_easy_font) and written as PNG.
#pragma once

#include "apps/ripple-render/Convergence.h"

#include <filesystem>
#include <string>
#include <vector>

namespace ripple::apps {

// Plots the estimated relMSE and, where the points have them, the true relMSE against time, with a slope -1
// guide (error ~ 1/time) through the last estimate. Points with a non-positive time or error are left out.
// Throws std::runtime_error naming the file when it cannot be written or no point can be plotted.
void writeErrorPlot(const std::filesystem::path& file, const std::vector<ConvergencePoint>& points,
                    const std::string& title);

}  // namespace ripple::apps
