// Wall-clock and process-CPU stopwatches for ripple-bench. CPU time covers the whole process (user + system):
// lavapipe's and oneTBB's worker threads run inside it, so rays per CPU-second compares the tracers fairly.
#pragma once

#include <algorithm>
#include <chrono>
#include <ctime>
#include <vector>

namespace ripple::bench {

inline double processCpuSeconds() {
    timespec ts{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

inline double wallSeconds() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// One timed run. gpu stays 0 where no GPU timestamps exist (Embree).
struct Sample {
    double wall = 0.0;
    double cpu = 0.0;
    double gpu = 0.0;
};

template <class F>
Sample measure(F&& work) {
    const double cpu0 = processCpuSeconds();
    const double wall0 = wallSeconds();
    work();
    Sample s;
    s.wall = wallSeconds() - wall0;
    s.cpu = processCpuSeconds() - cpu0;
    return s;
}

// Each field is summarised on its own: the run with the median wall time need not have the median CPU time.
inline Sample medianOf(std::vector<Sample> runs) {
    if (runs.empty()) return {};
    auto median = [&](double Sample::*field) {
        std::vector<double> v;
        for (const Sample& s : runs) v.push_back(s.*field);
        std::sort(v.begin(), v.end());
        const size_t n = v.size();
        return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
    };
    return {median(&Sample::wall), median(&Sample::cpu), median(&Sample::gpu)};
}

inline Sample bestOf(const std::vector<Sample>& runs) {
    if (runs.empty()) return {};
    Sample best = runs.front();
    for (const Sample& s : runs) {
        best.wall = std::min(best.wall, s.wall);
        best.cpu = std::min(best.cpu, s.cpu);
        best.gpu = std::min(best.gpu, s.gpu);
    }
    return best;
}

}  // namespace ripple::bench
