// Closed meshes and number formatting shared by the precision and intersection cases: a cube placed in
// double precision (so only the final rounding to float loses anything), and labels such as "1e-6".
#pragma once

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <map>
#include <string>
#include <vector>

namespace ripple::robustness {

struct Mesh {
    std::vector<glm::vec3> positions;
    std::vector<glm::uvec3> indices;
};

// A closed cube, each face split along the diagonal from its (-,-) to its (+,+) corner, so the face centre
// lies on a shared edge (Ripple shades both sides: winding does not matter). Corners are computed in
// double, then rounded once.
inline Mesh cube(glm::dvec3 center, double halfSize) {
    Mesh m;
    for (int i = 0; i < 8; ++i) {
        const glm::dvec3 corner((i & 1) ? 1.0 : -1.0, (i & 2) ? 1.0 : -1.0, (i & 4) ? 1.0 : -1.0);
        m.positions.emplace_back(center + halfSize * corner);
    }
    // Per face: four corners in order around it, the first and third being its (-,-) and (+,+) corners.
    const glm::uvec4 faces[6] = {{0, 2, 6, 4}, {1, 5, 7, 3}, {0, 4, 5, 1}, {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 6, 7, 5}};
    for (const glm::uvec4& f : faces) {
        m.indices.emplace_back(f.x, f.y, f.z);
        m.indices.emplace_back(f.x, f.z, f.w);
    }
    return m;
}

// An icosahedron subdivided `levels` times and pushed onto the unit sphere: 20 * 4^levels triangles, every
// edge shared by exactly two of them (midpoints are shared through a lookup, so the mesh stays closed).
inline Mesh icosphere(int levels) {
    const double g = (1.0 + std::sqrt(5.0)) / 2.0;
    std::vector<glm::dvec3> points = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0}, {0, -1, g}, {0, 1, g},
                                      {0, -1, -g}, {0, 1, -g}, {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
    std::vector<glm::uvec3> triangles = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                         {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                         {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                         {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
    for (int level = 0; level < levels; ++level) {
        std::map<std::pair<uint32_t, uint32_t>, uint32_t> midpoints;
        auto midpoint = [&](uint32_t a, uint32_t b) {
            const auto key = std::minmax(a, b);
            auto [it, inserted] = midpoints.emplace(key, uint32_t(points.size()));
            if (inserted) points.push_back(0.5 * (points[a] + points[b]));
            return it->second;
        };
        std::vector<glm::uvec3> finer;
        for (const glm::uvec3& t : triangles) {
            const uint32_t ab = midpoint(t.x, t.y), bc = midpoint(t.y, t.z), ca = midpoint(t.z, t.x);
            finer.insert(finer.end(), {{t.x, ab, ca}, {t.y, bc, ab}, {t.z, ca, bc}, {ab, bc, ca}});
        }
        triangles = std::move(finer);
    }
    Mesh m;
    for (const glm::dvec3& p : points) m.positions.emplace_back(glm::normalize(p));
    m.indices = std::move(triangles);
    return m;
}

// The float spacing at `magnitude` (the distance to the next float up).
inline double floatSpacing(double magnitude) {
    const float m = float(std::abs(magnitude));
    return double(std::nextafter(m, std::numeric_limits<float>::infinity())) - double(m);
}

// "0", "1e-6", "1e7": the decade labels of the sweeps (values that are not powers of ten get %.3g).
inline std::string decade(double value) {
    if (value == 0.0) return "0";
    const double exponent = std::log10(std::abs(value));
    char text[32];
    if (std::abs(exponent - std::round(exponent)) < 1e-9)
        std::snprintf(text, sizeof text, "1e%d", int(std::round(exponent)));
    else
        std::snprintf(text, sizeof text, "%.3g", value);
    return text;
}

inline std::string format(const char* pattern, double a, double b = 0.0, double c = 0.0, double d = 0.0) {
    char text[256];
    std::snprintf(text, sizeof text, pattern, a, b, c, d);
    return text;
}

}  // namespace ripple::robustness
