// Formats ripple-bench results: fixed-width tables for people, JSON for scripts and the README's numbers.
#include "bench/ripple-bench/Report.h"

#include "io/FileWrite.h"

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <sstream>
#include <stdexcept>

namespace ripple::bench {

namespace {

std::string format(const char* fmt, ...) __attribute__((format(printf, 1, 2)));
std::string format(const char* fmt, ...) {
    char buffer[512];
    va_list args;
    va_start(args, fmt);
    std::vsnprintf(buffer, sizeof buffer, fmt, args);
    va_end(args);
    return buffer;
}

double median(std::vector<double> v) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

double perSecond(double count, double seconds) { return seconds > 0.0 ? count / seconds : 0.0; }

// "12.34" or "-" when the tracer did not run; keeps columns aligned either way.
std::string number(bool present, double value, const char* fmt = "%.3g") {
    return present ? format(fmt, value) : std::string("-");
}

std::string withCommas(uint64_t n) {
    std::string digits = std::to_string(n), out;
    for (size_t i = 0; i < digits.size(); ++i) {
        if (i && (digits.size() - i) % 3 == 0) out += ',';
        out += digits[i];
    }
    return out;
}

// A small streaming JSON writer: enough for nested objects of numbers, strings and booleans.
class Json {
public:
    explicit Json(std::ostream& out) : out_(out) {}
    void open(const char* key, char bracket) { prefix(key); out_ << bracket; first_ = true; ++depth_; }
    void close(char bracket) { --depth_; out_ << '\n' << std::string(2 * depth_, ' ') << bracket; first_ = false; }
    void value(const char* key, double v) {
        prefix(key);
        if (std::isfinite(v)) out_ << format("%.9g", v); else out_ << "null";
    }
    void value(const char* key, uint64_t v) { prefix(key); out_ << v; }
    void value(const char* key, bool v) { prefix(key); out_ << (v ? "true" : "false"); }
    void value(const char* key, const std::string& v) { prefix(key); quoted(v); }
    void valueOrNull(const char* key, const std::string& v) {
        if (v.empty()) { prefix(key); out_ << "null"; } else { value(key, v); }
    }

private:
    void prefix(const char* key) {
        if (!first_) out_ << ',';
        first_ = false;
        if (depth_ > 0) out_ << '\n' << std::string(2 * depth_, ' ');
        if (key) { quoted(key); out_ << ": "; }
    }
    void quoted(const std::string& s) {
        out_ << '"';
        for (char c : s) {
            if (c == '"' || c == '\\') out_ << '\\' << c;
            else if (static_cast<unsigned char>(c) < 0x20) out_ << format("\\u%04x", c);
            else out_ << c;
        }
        out_ << '"';
    }
    std::ostream& out_;
    bool first_ = true;
    int depth_ = 0;
};

void writeSample(Json& j, const char* key, const Sample& s) {
    j.open(key, '{');
    j.value("wallSeconds", s.wall);
    j.value("cpuSeconds", s.cpu);
    if (s.gpu > 0.0) j.value("gpuSeconds", s.gpu);  // only Ripple's launches have GPU timestamps
    j.close('}');
}

void writeRuns(Json& j, const char* key, const TracerRuns& t, uint64_t rays, bool ripple) {
    j.open(key, '{');
    j.value("ran", t.ran);
    if (t.ran) {
        const Sample median = medianOf(t.runs), best = bestOf(t.runs);
        j.value("mraysPerSecondWall", perSecond(double(rays), median.wall) * 1e-6);
        j.value("mraysPerCpuSecond", perSecond(double(rays), median.cpu) * 1e-6);
        if (ripple) j.value("mraysPerSecondGpu", perSecond(double(rays), median.gpu) * 1e-6);
        writeSample(j, "median", median);
        writeSample(j, "best", best);
        j.open("runs", '[');
        for (const Sample& s : t.runs) writeSample(j, nullptr, s);
        j.close(']');
        if (ripple) j.value("roundTripWallSeconds", t.roundTripSeconds);
    }
    j.close('}');
}

void writeBuild(Json& j, const BuildResult& b, uint64_t triangles) {
    j.value("ran", b.ran);
    if (!b.ran) return;
    const Sample median = medianOf(b.runs);
    j.value("mtrisPerSecond", perSecond(double(triangles), median.wall) * 1e-6);
    writeSample(j, "median", median);
    j.open("runs", '[');
    for (const Sample& s : b.runs) writeSample(j, nullptr, s);
    j.close(']');
}

}  // namespace

void printTables(std::ostream& out, const RunInfo& info, const std::vector<SceneResult>& scenes) {
    out << format("ripple-bench: Ripple on \"%s\" (driver %s) vs %s; %u hardware threads, %ux%u rays, median of %u timed run(s)\n",
                  info.vkDevice.c_str(), info.vkDriver.c_str(),
                  info.embreeVersion.empty() ? "nothing (--no-embree)" : ("Embree " + info.embreeVersion).c_str(),
                  info.hardwareThreads, info.width, info.height, info.repeat);
    out << format("Ripple levers: --bvh-width %u (%s), --features %s, --nodes %s, --traversal %s, --ray-order %s.\n",
                  info.bvhWidth, info.singleLevel ? "single-level kernel, BVH4 layout" : "renderer's two-level kernel, compressed BVH4",
                  info.features.c_str(),
                  info.nodes.c_str(), info.traversal.c_str(), info.rayOrder.c_str());
    out << "Ripple trace times: device-side launch incl. submit+wait, excluding upload/download.\n"
        << (info.embreeVersion.empty() ? "Secondary rays start from Ripple's primary hits (--no-embree).\n\n"
                                       : "Secondary rays start from Embree's primary hits (the reference).\n\n");

    out << format("%-11s %-9s %11s %26s %10s %19s %12s\n", "scene", "back-end", "triangles",
                  "build ms Ripple (BLAS part)", "Embree", "Mtri/s Ripple / E", "AS Mprim/s");
    for (const SceneResult& s : scenes) {
        if (s.status != "ok") {
            out << format("%-11s %-9s %s: %s\n", s.name.c_str(), s.backend.c_str(), s.status.c_str(), s.message.c_str());
            continue;
        }
        const double rippleWall = medianOf(s.rippleBuild.runs).wall;
        const double embreeWall = medianOf(s.embreeBuild.runs).wall;
        const std::string ripple = s.rippleBuild.ran
            ? format("%.1f (%.1f)", 1e3 * rippleWall, 1e3 * median(s.rippleBuild.bvhSeconds)) : std::string("-");
        const double tris = double(s.triangles);
        // The BVH build rate (whole Scene construction) next to the acceleration-structure build rate
        // (host setup, device build and wait; rayQuery back-end only).
        const bool as = !s.rippleBuild.asSeconds.empty();
        out << format("%-11s %-9s %11s %26s %10s %8s / %-8s %12s\n", s.name.c_str(), s.backend.c_str(),
                      withCommas(s.triangles).c_str(), ripple.c_str(),
                      number(s.embreeBuild.ran, 1e3 * embreeWall, "%.1f").c_str(),
                      number(s.rippleBuild.ran, perSecond(tris, rippleWall) * 1e-6).c_str(),
                      number(s.embreeBuild.ran, perSecond(tris, embreeWall) * 1e-6).c_str(),
                      number(as, as ? perSecond(tris, median(s.rippleBuild.asSeconds)) * 1e-6 : 0.0).c_str());
    }

    out << format("\n%-11s %-9s %-8s %10s %19s %19s %9s %9s %6s %7s\n", "scene", "back-end", "rays", "count",
                  "Mrays/s wall R / E",
                  "Mrays/CPU-s R / E", "R/E CPU", "agree %", "ties", "flagged");
    for (const SceneResult& s : scenes) {
        for (const KindResult& k : s.kinds) {
            const Sample r = medianOf(k.ripple.runs), e = medianOf(k.embree.runs);
            const double n = double(k.rays);
            const double rCpu = perSecond(n, r.cpu), eCpu = perSecond(n, e.cpu);
            const bool both = k.ripple.ran && k.embree.ran;
            out << format("%-11s %-9s %-8s %10s %8s / %-8s %8s / %-8s %9s %9s %6s %7s\n", s.name.c_str(),
                          s.backend.c_str(), k.kind.c_str(),
                          withCommas(k.rays).c_str(), number(k.ripple.ran, perSecond(n, r.wall) * 1e-6).c_str(),
                          number(k.embree.ran, perSecond(n, e.wall) * 1e-6).c_str(),
                          number(k.ripple.ran, rCpu * 1e-6).c_str(), number(k.embree.ran, eCpu * 1e-6).c_str(),
                          number(both && eCpu > 0.0, rCpu / eCpu, "%.3f").c_str(),
                          number(k.compared, k.agreement.percent(), "%.4f").c_str(),
                          number(k.compared, double(k.agreement.ties), "%.0f").c_str(),
                          number(k.compared, double(k.agreement.flagged), "%.0f").c_str());
        }
    }
}

void writeJson(const std::filesystem::path& path, const RunInfo& info, const std::vector<SceneResult>& scenes) {
    std::ostringstream file;
    Json j(file);
    j.open(nullptr, '{');
    j.open("machine", '{');
    j.value("vkDevice", info.vkDevice);
    j.value("vkDriver", info.vkDriver);
    j.valueOrNull("embreeVersion", info.embreeVersion);
    j.value("cpuModel", info.cpuModel);
    j.value("hardwareThreads", uint64_t(info.hardwareThreads));
    j.value("tbbThreads", uint64_t(info.tbbThreads));
    j.valueOrNull("LP_NUM_THREADS", info.lpNumThreads);
    j.valueOrNull("LP_NATIVE_VECTOR_WIDTH", info.lpNativeVectorWidth);
    j.close('}');
    j.open("settings", '{');
    j.value("width", uint64_t(info.width));
    j.value("height", uint64_t(info.height));
    j.value("repeat", uint64_t(info.repeat));
    j.value("workgroupSize", uint64_t(info.workgroup));
    j.value("quick", info.quick);
    j.value("bvhWidth", uint64_t(info.bvhWidth));
    j.value("singleLevel", info.singleLevel);
    j.value("nodes", info.nodes);
    j.value("traversal", info.traversal);
    j.value("features", info.features);
    j.value("rayOrder", info.rayOrder);
    j.value("rippleTiming", std::string("device-side launch incl. submit+wait, excluding upload/download"));
    j.value("tieRelative", double(kTieRelative));
    j.close('}');
    j.open("scenes", '[');
    for (const SceneResult& s : scenes) {
        j.open(nullptr, '{');
        j.value("name", s.name);
        j.value("backend", s.backend);
        j.value("source", s.source);
        j.value("status", s.status);
        j.value("message", s.message);
        j.value("triangles", s.triangles);
        j.value("vertices", s.vertices);
        j.open("rippleBuild", '{');
        writeBuild(j, s.rippleBuild, s.triangles);
        if (s.rippleBuild.ran) {
            j.value("blasSecondsMedian", median(s.rippleBuild.bvhSeconds));
            j.open("blasSeconds", '[');
            for (double b : s.rippleBuild.bvhSeconds) j.value(nullptr, b);
            j.close(']');
            j.value("tlasSeconds", s.rippleTlasSeconds);
            if (!s.rippleBuild.asSeconds.empty()) {
                const double as = median(s.rippleBuild.asSeconds);
                j.value("accelerationStructureSecondsMedian", as);
                j.value("accelerationStructureMprimPerSecond", as > 0.0 ? double(s.triangles) / as * 1e-6 : 0.0);
            }
            j.value("trianglesSkipped", s.rippleTrianglesSkipped);
            j.value("gpuBytes", s.rippleGpuBytes);
            if (s.bvh4Nodes) {
                j.value("bvh4Nodes", s.bvh4Nodes);
                j.value("bvh4ChildSlotsUsed", s.bvh4ChildSlotsUsed);
                j.value("bvh4Depth", uint64_t(s.bvh4Depth));
                j.value("bvh4NodeBytes", s.bvh4NodeBytes);
                j.value("bvh4CollapseSeconds", s.bvh4CollapseSeconds);
            }
        }
        j.close('}');
        j.open("embreeBuild", '{');
        writeBuild(j, s.embreeBuild, s.triangles);
        j.close('}');
        j.value("secondaryRaysFrom", s.secondaryFrom);
        j.open("rays", '[');
        for (const KindResult& k : s.kinds) {
            j.open(nullptr, '{');
            j.value("kind", k.kind);
            j.value("anyHit", k.anyHit);
            j.value("count", k.rays);
            writeRuns(j, "ripple", k.ripple, k.rays, true);
            writeRuns(j, "embree", k.embree, k.rays, false);
            if (k.ripple.ran && k.embree.ran) {
                const double r = perSecond(double(k.rays), medianOf(k.ripple.runs).cpu);
                const double e = perSecond(double(k.rays), medianOf(k.embree.runs).cpu);
                j.value("rippleOverEmbreePerCpuSecond", e > 0.0 ? r / e : 0.0);
            }
            j.value("rippleRunMismatches", k.rippleRunMismatches);
            if (info.rayOrder != "none") j.value("rippleOrderSeconds", k.rippleOrderSeconds);
            if (k.compared) {
                j.open("agreement", '{');
                j.value("percent", k.agreement.percent());
                j.value("rays", k.agreement.rays);
                j.value("agree", k.agreement.agree);
                j.value("ties", k.agreement.ties);
                j.value("flagged", k.agreement.flagged);
                j.value("embreeHits", k.agreement.referenceHits);
                j.value("rippleHits", k.agreement.testHits);
                j.close('}');
            }
            j.close('}');
        }
        j.close(']');
        j.close('}');
    }
    j.close(']');
    j.close('}');
    file << '\n';
    apps::writeFileAtomically(path, file.str(), "the benchmark results");
}

}  // namespace ripple::bench
