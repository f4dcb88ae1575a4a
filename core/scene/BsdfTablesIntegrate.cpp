// Computes the GGX albedo tables of core/scene/BsdfTables.h at build time and writes them as C++ (exact
// hexadecimal floats) for BsdfTables.cpp, so no process spends start-up on them (0.08 s on two cores).
// Stratified visible-normal sampling, where f cos / pdf = G2 / G1 for F = 1, so each entry is a mean of
// G2 / G1 (times the Schlick weight for W). Usage: ripple_bsdf_tables OUTPUT.inc
#include "core/scene/BsdfTables.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <vector>

using namespace ripple::core;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr float kMinAlpha = 1e-3f;        // MIN_GGX_ALPHA in shaders/bsdf.glsl
constexpr uint32_t kStrata = 48;          // kStrata^2 samples per entry: error well under 1e-3

double lambda(double c, double a2) {
    const double c2 = c * c;
    return 0.5 * (-1.0 + std::sqrt(1.0 + a2 * std::max(0.0, 1.0 - c2) / std::max(c2, 1e-12)));
}

// A visible normal for the view v (v.z > 0), the same construction as the shader's.
glm::dvec3 visibleNormal(const glm::dvec3& v, double alpha, double u1, double u2) {
    const glm::dvec3 vh = glm::normalize(glm::dvec3(alpha * v.x, alpha * v.y, v.z));
    const double lensq = vh.x * vh.x + vh.y * vh.y;
    const glm::dvec3 t1 = lensq > 0.0 ? glm::dvec3(-vh.y, vh.x, 0.0) / std::sqrt(lensq) : glm::dvec3(1.0, 0.0, 0.0);
    const glm::dvec3 t2 = glm::cross(vh, t1);
    const double r = std::sqrt(u1), phi = 2.0 * kPi * u2;
    const double p1 = r * std::cos(phi);
    const double s = 0.5 * (1.0 + vh.z);
    const double p2 = (1.0 - s) * std::sqrt(std::max(0.0, 1.0 - p1 * p1)) + s * r * std::sin(phi);
    const glm::dvec3 nh = p1 * t1 + p2 * t2 + std::sqrt(std::max(0.0, 1.0 - p1 * p1 - p2 * p2)) * vh;
    return glm::normalize(glm::dvec3(alpha * nh.x, alpha * nh.y, std::max(0.0, nh.z)));
}

std::vector<float> integrate() {
    const uint32_t n = kBsdfTableSize;
    std::vector<float> tables(2 * n * n);
    for (uint32_t j = 0; j < n; ++j) {
        const double roughness = double(j) / double(n - 1);
        const double alpha = std::max(roughness * roughness, double(kMinAlpha));
        const double a2 = alpha * alpha;
        for (uint32_t i = 0; i < n; ++i) {
            const double mu = (i + 0.5) / n;
            const glm::dvec3 v(std::sqrt(1.0 - mu * mu), 0.0, mu);
            const double lambdaV = lambda(mu, a2);
            double e = 0.0, w = 0.0;
            for (uint32_t a = 0; a < kStrata; ++a)
                for (uint32_t b = 0; b < kStrata; ++b) {
                    const glm::dvec3 h = visibleNormal(v, alpha, (a + 0.5) / kStrata, (b + 0.5) / kStrata);
                    const double vh = glm::dot(v, h);
                    const glm::dvec3 l = 2.0 * vh * h - v;
                    if (l.z <= 0.0) continue;
                    const double g2OverG1 = (1.0 + lambdaV) / (1.0 + lambdaV + lambda(l.z, a2));
                    const double m = std::clamp(1.0 - vh, 0.0, 1.0);
                    e += g2OverG1;
                    w += g2OverG1 * m * m * m * m * m;
                }
            const double count = double(kStrata) * kStrata;
            tables[j * n + i] = float(e / count);
            tables[n * n + j * n + i] = float(w / count);
        }
    }
    return tables;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: ripple_bsdf_tables OUTPUT.inc\n");
        return 2;
    }
    const std::vector<float> tables = integrate();
    std::FILE* out = std::fopen(argv[1], "w");
    if (!out) {
        std::fprintf(stderr, "ripple_bsdf_tables: cannot write %s\n", argv[1]);
        return 1;
    }
    std::fprintf(out, "// Written by ripple_bsdf_tables (core/scene/BsdfTablesIntegrate.cpp): E then W, %u x %u each.\n",
                 kBsdfTableSize, kBsdfTableSize);
    for (size_t i = 0; i < tables.size(); ++i) std::fprintf(out, "%a,%s", double(tables[i]), i % 8 == 7 ? "\n" : " ");
    return std::fclose(out) == 0 ? 0 : 1;
}
