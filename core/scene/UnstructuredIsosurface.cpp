// Marching tetrahedra over an unstructured field (see UnstructuredIsosurface.h).
#include "core/scene/UnstructuredIsosurface.h"

#include <array>

namespace ripple::core {

namespace {

using Tetrahedron = std::array<int, 4>;

// Each shape's cut into tetrahedra, as corners of VTK's order.
const std::vector<Tetrahedron>& tetrahedraOf(uint8_t type) {
    static const std::vector<Tetrahedron> tetrahedron = {{0, 1, 2, 3}};
    static const std::vector<Tetrahedron> hexahedron = {{0, 1, 2, 6}, {0, 2, 3, 6}, {0, 3, 7, 6},
                                                        {0, 7, 4, 6}, {0, 4, 5, 6}, {0, 5, 1, 6}};
    static const std::vector<Tetrahedron> wedge = {{0, 1, 2, 5}, {0, 1, 5, 4}, {0, 4, 5, 3}};
    static const std::vector<Tetrahedron> pyramid = {{0, 1, 2, 4}, {0, 2, 3, 4}};
    return type == 10 ? tetrahedron : type == 12 ? hexahedron : type == 13 ? wedge : pyramid;
}

// The surface at `iso` in one tetrahedron (corners p, values v): the points where it crosses the edges
// between corners below and at-or-above, as a triangle or a quad, facing up the field's gradient.
void march(const glm::vec3 (&p)[4], const float (&v)[4], float iso, uint32_t isovalue, UnstructuredIsosurface& out) {
    int above[4], below[4], na = 0, nb = 0;
    for (int k = 0; k < 4; ++k) (v[k] >= iso ? above[na++] : below[nb++]) = k;
    if (na == 0 || nb == 0) return;
    const auto cross = [&](int a, int b) {  // a below, b above
        const double t = (double(iso) - v[a]) / (double(v[b]) - v[a]);
        return glm::vec3(glm::dvec3(p[a]) + t * (glm::dvec3(p[b]) - glm::dvec3(p[a])));
    };
    std::vector<glm::vec3> polygon;
    if (na == 1 || nb == 1) {
        const bool loneAbove = na == 1;
        const int lone = loneAbove ? above[0] : below[0];
        for (int k = 0; k < 3; ++k) {
            const int other = loneAbove ? below[k] : above[k];
            polygon.push_back(loneAbove ? cross(other, lone) : cross(lone, other));
        }
    } else {  // two and two: a quad, its corners in order around it
        polygon = {cross(below[0], above[0]), cross(below[0], above[1]), cross(below[1], above[1]), cross(below[1], above[0])};
    }
    // The field's gradient in the tetrahedron: solve [p1-p0, p2-p0, p3-p0]^T g = [v1-v0, v2-v0, v3-v0].
    const glm::dmat3 edges(glm::dvec3(p[1] - p[0]), glm::dvec3(p[2] - p[0]), glm::dvec3(p[3] - p[0]));
    const glm::dvec3 gradient = glm::inverse(glm::transpose(edges)) * glm::dvec3(v[1] - v[0], v[2] - v[0], v[3] - v[0]);
    for (size_t k = 1; k + 1 < polygon.size(); ++k) {
        glm::vec3 a = polygon[0], b = polygon[k], c = polygon[k + 1];
        const glm::vec3 normal = glm::cross(b - a, c - a);
        if (!(glm::dot(normal, normal) > 0.0f)) continue;  // a corner exactly on the surface: nothing to draw
        if (glm::dot(glm::dvec3(normal), gradient) < 0.0) std::swap(b, c);
        out.mesh.positions.insert(out.mesh.positions.end(), {a, b, c});
        out.isovalueOf.push_back(isovalue);
    }
}

}  // namespace

UnstructuredIsosurface extractIsosurface(const UnstructuredCells& cells, const std::vector<float>& isovalues) {
    UnstructuredIsosurface out;
    for (size_t c = 0; c < cells.cellType.size(); ++c) {
        const uint32_t first = cells.cellIndex[c];
        float lowest = INFINITY, highest = -INFINITY;
        for (uint32_t k = 0; k < unstructuredCorners(cells.cellType[c]); ++k) {
            const float value = cells.values[cells.index[first + k]];
            lowest = std::min(lowest, value);
            highest = std::max(highest, value);
        }
        for (uint32_t i = 0; i < isovalues.size(); ++i) {
            if (!(isovalues[i] >= lowest && isovalues[i] <= highest)) continue;
            for (const Tetrahedron& t : tetrahedraOf(cells.cellType[c])) {
                glm::vec3 p[4];
                float v[4];
                for (int k = 0; k < 4; ++k) {
                    const uint32_t vertex = cells.index[first + uint32_t(t[k])];
                    p[k] = cells.positions[vertex];
                    v[k] = cells.values[vertex];
                }
                march(p, v, isovalues[i], i, out);
            }
        }
    }
    return out;
}

}  // namespace ripple::core
