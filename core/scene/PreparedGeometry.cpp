// Validation of triangle meshes, sphere sets and cylinder sets, and the BLAS over what is kept.
#include "core/scene/PreparedGeometry.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ripple::core {

namespace {

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
bool validRadius(float r) { return std::isfinite(r) && r > 0.0f; }

void note(PreparedGeometry& g, uint64_t count, const std::string& what) {
    if (count == 0) return;
    g.problems.push_back("skipped " + std::to_string(count) + " " + what);
    g.skipped += count;
}

std::shared_ptr<const PreparedGeometry> finish(std::shared_ptr<PreparedGeometry> g, const std::vector<bvh::Aabb>& boxes) {
    if (g->validPrims.empty()) return g;
    g->blas = bvh::buildBinnedSah(boxes, g->buildOptions);
    g->blas4 = bvh::collapseToBvh4(g->blas);
    g->blas.nodes = {};
    return g;
}

// Box of a round cylinder with caps: across axis i a cap disk reaches r * sqrt(1 - w_i^2) from its
// centre (w the unit axis). Computed in double and widened a little, so float rounding never makes it
// smaller than the cylinder.
bvh::Aabb cylinderBox(const glm::vec3& a, const glm::vec3& b, float r) {
    const glm::dvec3 w = glm::normalize(glm::dvec3(b) - glm::dvec3(a));
    const glm::dvec3 reach = double(r) * glm::sqrt(glm::max(glm::dvec3(0.0), 1.0 - w * w)) * (1.0 + 1e-6) +
                             1e-7 * glm::max(glm::abs(glm::dvec3(a)), glm::abs(glm::dvec3(b)));
    const glm::dvec3 lo = glm::min(glm::dvec3(a), glm::dvec3(b)) - reach;
    const glm::dvec3 hi = glm::max(glm::dvec3(a), glm::dvec3(b)) + reach;
    return {glm::vec3(lo), glm::vec3(hi)};
}

}  // namespace

bvh::Aabb coneBox(const glm::vec3& a, float ra, const glm::vec3& b, float rb, bool round) {
    if (round) {  // the tangent cone lies inside the hull of the two spheres
        bvh::Aabb box;
        box.extend(a - glm::vec3(ra));
        box.extend(a + glm::vec3(ra));
        box.extend(b - glm::vec3(rb));
        box.extend(b + glm::vec3(rb));
        const glm::vec3 pad = 1e-6f * glm::max(glm::abs(box.lo), glm::abs(box.hi)) + 1e-6f * std::max(ra, rb);
        return {box.lo - pad, box.hi + pad};
    }
    // Each end disk reaches r * sqrt(1 - w_i^2) across axis i, as for cylinders.
    bvh::Aabb box = cylinderBox(a, b, 0.0f);
    const glm::dvec3 w = glm::normalize(glm::dvec3(b) - glm::dvec3(a));
    const glm::dvec3 across = glm::sqrt(glm::max(glm::dvec3(0.0), 1.0 - w * w)) * (1.0 + 1e-6);
    box.extend(glm::vec3(glm::dvec3(a) - double(ra) * across));
    box.extend(glm::vec3(glm::dvec3(a) + double(ra) * across));
    box.extend(glm::vec3(glm::dvec3(b) - double(rb) * across));
    box.extend(glm::vec3(glm::dvec3(b) + double(rb) * across));
    const glm::vec3 pad = 1e-6f * glm::max(glm::abs(box.lo), glm::abs(box.hi)) + 1e-6f * std::max(ra, rb);
    return {box.lo - pad, box.hi + pad};
}

std::string geometryLabel(GeometryKind kind, uint32_t index) {
    switch (kind) {
    case GeometryKind::Triangles: return "mesh " + std::to_string(index);
    case GeometryKind::Spheres: return "sphere set " + std::to_string(index);
    case GeometryKind::Cylinders: return "cylinder set " + std::to_string(index);
    case GeometryKind::Cones: return "cone set " + std::to_string(index);
    case GeometryKind::Isosurfaces: return "isosurface set " + std::to_string(index);
    }
    return "geometry of kind " + std::to_string(static_cast<uint32_t>(kind)) + " " + std::to_string(index);
}

uint64_t primitiveCount(const TriangleMesh& mesh) {
    return mesh.indices.empty() ? mesh.positions.size() / 3 : mesh.indices.size();
}
uint64_t primitiveCount(const SphereSet& set) { return set.centers.size(); }
uint64_t primitiveCount(const CylinderSet& set) {
    return set.indices.empty() ? set.positions.size() / 2 : set.indices.size();
}

uint64_t primitiveCount(const ConeSet& set) {
    return set.indices.empty() ? set.positions.size() / 2 : set.indices.size();
}

glm::uvec2 coneIndices(const ConeSet& set, uint64_t i) {
    if (!set.indices.empty()) return set.indices[i];
    return glm::uvec2(uint32_t(2 * i), uint32_t(2 * i + 1));
}

glm::uvec2 cylinderIndices(const CylinderSet& set, uint64_t i) {
    if (!set.indices.empty()) return set.indices[i];
    return glm::uvec2(uint32_t(2 * i), uint32_t(2 * i + 1));
}

bool fits(const PreparedGeometry& prepared, const TriangleMesh& mesh) {
    if (prepared.inputPrimCount != primitiveCount(mesh) || prepared.positionCount != mesh.positions.size()) return false;
    if (mesh.indices.empty()) return true;
    for (uint32_t t : prepared.validPrims) {
        const glm::uvec3& idx = mesh.indices[t];
        if (idx.x >= mesh.positions.size() || idx.y >= mesh.positions.size() || idx.z >= mesh.positions.size()) return false;
    }
    return true;
}

bool fits(const PreparedGeometry& prepared, const SphereSet& set) {
    return prepared.inputPrimCount == primitiveCount(set) && prepared.positionCount == set.centers.size() &&
           (set.radii.size() == 1 || set.radii.size() == set.centers.size());
}

bool fits(const PreparedGeometry& prepared, const CylinderSet& set) {
    if (prepared.inputPrimCount != primitiveCount(set) || prepared.positionCount != set.positions.size()) return false;
    if (set.radii.size() != 1 && set.radii.size() != primitiveCount(set)) return false;
    for (uint32_t i : prepared.validPrims) {
        const glm::uvec2 idx = cylinderIndices(set, i);
        if (idx.x >= set.positions.size() || idx.y >= set.positions.size()) return false;
    }
    return true;
}

bool fits(const PreparedGeometry& prepared, const ConeSet& set) {
    if (prepared.inputPrimCount != primitiveCount(set) || prepared.positionCount != set.positions.size()) return false;
    if (set.radii.size() != 1 && set.radii.size() != set.positions.size()) return false;
    for (uint32_t i : prepared.validPrims) {
        const glm::uvec2 idx = coneIndices(set, i);
        if (idx.x >= set.positions.size() || idx.y >= set.positions.size()) return false;
    }
    return true;
}

std::shared_ptr<const PreparedGeometry> prepareGeometry(const TriangleMesh& mesh, const bvh::BuildOptions& options) {
    auto g = std::make_shared<PreparedGeometry>();
    g->kind = GeometryKind::Triangles;
    g->identity = mesh.identity;
    g->buildOptions = options;
    const uint64_t positionCount = mesh.positions.size();
    g->inputPrimCount = primitiveCount(mesh);
    g->positionCount = mesh.positions.size();
    std::vector<bvh::Aabb> boxes;
    uint64_t badIndex = 0, nonFinite = 0, zeroArea = 0;
    for (uint64_t t = 0; t < g->inputPrimCount; ++t) {
        const glm::uvec3 idx = mesh.indices.empty() ? glm::uvec3(3 * t, 3 * t + 1, 3 * t + 2) : mesh.indices[t];
        if (idx.x >= positionCount || idx.y >= positionCount || idx.z >= positionCount) { ++badIndex; continue; }
        const glm::vec3 &a = mesh.positions[idx.x], &b = mesh.positions[idx.y], &c = mesh.positions[idx.z];
        if (!finite(a) || !finite(b) || !finite(c)) { ++nonFinite; continue; }
        const glm::dvec3 n = glm::cross(glm::dvec3(b) - glm::dvec3(a), glm::dvec3(c) - glm::dvec3(a));
        if (n.x == 0.0 && n.y == 0.0 && n.z == 0.0) { ++zeroArea; continue; }
        bvh::Aabb box;
        box.extend(a);
        box.extend(b);
        box.extend(c);
        g->validPrims.push_back(static_cast<uint32_t>(t));
        boxes.push_back(box);
    }
    note(*g, badIndex, "triangle(s) with an index out of range (" + std::to_string(positionCount) + " positions)");
    note(*g, nonFinite, "triangle(s) with a NaN or Inf vertex");
    note(*g, zeroArea, "zero-area triangle(s)");
    return finish(std::move(g), boxes);
}

std::shared_ptr<const PreparedGeometry> prepareGeometry(const SphereSet& set, const bvh::BuildOptions& options) {
    auto g = std::make_shared<PreparedGeometry>();
    g->kind = GeometryKind::Spheres;
    g->identity = set.identity;
    g->buildOptions = options;
    g->inputPrimCount = primitiveCount(set);
    g->positionCount = set.centers.size();
    if (set.radii.size() != 1 && set.radii.size() != set.centers.size()) {
        g->problems.push_back(std::to_string(set.radii.size()) + " radii for " + std::to_string(set.centers.size()) +
                              " centers (need 1 or one each); set skipped");
        g->skipped = g->inputPrimCount;
        return g;
    }
    std::vector<bvh::Aabb> boxes;
    uint64_t badRadius = 0, nonFinite = 0;
    for (uint32_t i = 0; i < set.centers.size(); ++i) {
        const float r = radiusOf(set.radii, i);
        if (!finite(set.centers[i])) { ++nonFinite; continue; }
        if (!validRadius(r)) { ++badRadius; continue; }
        g->validPrims.push_back(i);
        boxes.push_back({set.centers[i] - glm::vec3(r), set.centers[i] + glm::vec3(r)});
    }
    note(*g, nonFinite, "sphere(s) with a NaN or Inf center");
    note(*g, badRadius, "sphere(s) with a radius that is not finite and positive");
    return finish(std::move(g), boxes);
}

std::shared_ptr<const PreparedGeometry> prepareGeometry(const CylinderSet& set, const bvh::BuildOptions& options) {
    auto g = std::make_shared<PreparedGeometry>();
    g->kind = GeometryKind::Cylinders;
    g->identity = set.identity;
    g->buildOptions = options;
    g->inputPrimCount = primitiveCount(set);
    g->positionCount = set.positions.size();
    if (set.radii.size() != 1 && set.radii.size() != g->inputPrimCount) {
        g->problems.push_back(std::to_string(set.radii.size()) + " radii for " + std::to_string(g->inputPrimCount) +
                              " cylinders (need 1 or one each); set skipped");
        g->skipped = g->inputPrimCount;
        return g;
    }
    std::vector<bvh::Aabb> boxes;
    uint64_t badIndex = 0, nonFinite = 0, badRadius = 0, zeroLength = 0;
    for (uint64_t i = 0; i < g->inputPrimCount; ++i) {
        const glm::uvec2 idx = cylinderIndices(set, i);
        if (idx.x >= set.positions.size() || idx.y >= set.positions.size()) { ++badIndex; continue; }
        const glm::vec3 &a = set.positions[idx.x], &b = set.positions[idx.y];
        const float r = radiusOf(set.radii, i);
        if (!finite(a) || !finite(b)) { ++nonFinite; continue; }
        if (!validRadius(r)) { ++badRadius; continue; }
        // The kernel divides by the axis length; one whose square is denormal (GPUs may flush it) is as
        // bad as zero.
        const glm::vec3 axis = b - a;
        if (!(glm::dot(axis, axis) >= std::numeric_limits<float>::min())) { ++zeroLength; continue; }
        g->validPrims.push_back(static_cast<uint32_t>(i));
        boxes.push_back(cylinderBox(a, b, r));
    }
    note(*g, badIndex, "cylinder(s) with an index out of range (" + std::to_string(set.positions.size()) + " positions)");
    note(*g, nonFinite, "cylinder(s) with a NaN or Inf end");
    note(*g, badRadius, "cylinder(s) with a radius that is not finite and positive");
    note(*g, zeroLength, "cylinder(s) of zero length");
    return finish(std::move(g), boxes);
}

}  // namespace ripple::core

namespace ripple::core {

std::shared_ptr<const PreparedGeometry> prepareGeometry(const ConeSet& set, const bvh::BuildOptions& options) {
    auto g = std::make_shared<PreparedGeometry>();
    g->kind = GeometryKind::Cones;
    g->identity = set.identity;
    g->buildOptions = options;
    g->inputPrimCount = primitiveCount(set);
    g->positionCount = set.positions.size();
    if (set.radii.size() != 1 && set.radii.size() != set.positions.size()) {
        g->problems.push_back(std::to_string(set.radii.size()) + " radii for " + std::to_string(set.positions.size()) +
                              " positions (need 1 or one each); set skipped");
        g->skipped = g->inputPrimCount;
        return g;
    }
    std::vector<bvh::Aabb> boxes;
    uint64_t badIndex = 0, nonFinite = 0, badRadius = 0, zeroLength = 0;
    for (uint64_t i = 0; i < g->inputPrimCount; ++i) {
        const glm::uvec2 idx = coneIndices(set, i);
        if (idx.x >= set.positions.size() || idx.y >= set.positions.size()) { ++badIndex; continue; }
        const glm::vec3 &a = set.positions[idx.x], &b = set.positions[idx.y];
        const float ra = radiusOf(set.radii, idx.x), rb = radiusOf(set.radii, idx.y);
        if (!finite(a) || !finite(b)) { ++nonFinite; continue; }
        if (!(std::isfinite(ra) && std::isfinite(rb) && ra >= 0.0f && rb >= 0.0f && ra + rb > 0.0f)) { ++badRadius; continue; }
        const glm::vec3 axis = b - a;
        if (!(glm::dot(axis, axis) >= std::numeric_limits<float>::min())) { ++zeroLength; continue; }
        g->validPrims.push_back(static_cast<uint32_t>(i));
        boxes.push_back(coneBox(a, ra, b, rb, set.round));
    }
    note(*g, badIndex, "segment(s) with an index out of range (" + std::to_string(set.positions.size()) + " positions)");
    note(*g, nonFinite, "segment(s) with a NaN or Inf end");
    note(*g, badRadius, "segment(s) with a radius that is negative or not finite, or 0 at both ends");
    note(*g, zeroLength, "segment(s) of zero length");
    return finish(std::move(g), boxes);
}

namespace {

// Whether an iso-surface set's arrays describe a field of at least one cell with a usable grid.
std::string isosurfaceFieldProblem(const IsosurfaceSet& set) {
    for (float v : set.isovalues)
        if (!std::isfinite(v)) return "an isovalue is not finite";
    if (set.mesh) return {};  // checked when it was prepared
    const glm::uvec3 d = set.dims;
    if (d.x < 2 || d.y < 2 || d.z < 2) return "a field needs at least 2 voxels along each axis";
    uint64_t voxels = 0;
    if (__builtin_mul_overflow(uint64_t(d.x) * d.y, uint64_t(d.z), &voxels) || voxels != set.values.size())
        return "the voxel count does not match the dimensions";
    if (!finite(set.origin)) return "origin is not finite";
    if (!(finite(set.spacing) && set.spacing.x > 0.0f && set.spacing.y > 0.0f && set.spacing.z > 0.0f))
        return "spacing is not finite and positive";
    for (float v : set.isovalues)
        if (!std::isfinite(v)) return "an isovalue is not finite";
    return {};
}

// The cells an iso-surface's (cell, isovalue) pairs number: the grid's, or the mesh's in leaf order.
uint64_t isosurfaceCells(const IsosurfaceSet& set) {
    if (set.mesh) return set.mesh->cellRanges.size();
    const glm::uvec3 cells = set.dims - 1u;
    return uint64_t(cells.x) * cells.y * cells.z;
}

}  // namespace

bool fits(const PreparedGeometry& prepared, const IsosurfaceSet& set) {
    const uint64_t samples = set.mesh ? set.mesh->words.size() : set.values.size();
    if (!isosurfaceFieldProblem(set).empty() || prepared.positionCount != samples) return false;
    const uint64_t pairs = isosurfaceCells(set) * set.isovalues.size();
    for (uint64_t pair : prepared.isoCells)
        if (pair >= pairs) return false;
    return true;
}

std::shared_ptr<const PreparedGeometry> prepareGeometry(const IsosurfaceSet& set, const bvh::BuildOptions& options) {
    auto g = std::make_shared<PreparedGeometry>();
    g->kind = GeometryKind::Isosurfaces;
    g->identity = set.identity;
    g->buildOptions = options;
    g->positionCount = set.mesh ? set.mesh->words.size() : set.values.size();
    if (const std::string problem = isosurfaceFieldProblem(set); !problem.empty()) {
        g->problems.push_back(problem + "; set skipped");
        return g;
    }
    const uint64_t isoCount = set.isovalues.size();
    std::vector<bvh::Aabb> boxes;
    if (set.mesh) {
        // A mesh cell is crossed when its corner values span the isovalue (its interpolant stays within them).
        const UnstructuredGrid& mesh = *set.mesh;
        for (uint64_t cell = 0; cell < mesh.cellRanges.size(); ++cell) {
            const glm::vec2 range = mesh.cellRanges[cell];
            if (!(range.x < range.y)) continue;
            const auto& [lo, hi] = mesh.cellBoxes[cell];
            const glm::vec3 pad = 1e-6f * (glm::abs(lo) + glm::abs(hi));
            for (uint64_t i = 0; i < isoCount; ++i) {
                if (set.isovalues[i] < range.x || set.isovalues[i] > range.y) continue;
                g->isoCells.push_back(cell * isoCount + i);
                boxes.push_back({lo - pad, hi + pad});
            }
        }
    }
    const glm::uvec3 d = set.mesh ? glm::uvec3(1u) : set.dims;
    auto at = [&](uint32_t x, uint32_t y, uint32_t z) { return set.values[(uint64_t(z) * d.y + y) * d.x + x]; };
    uint64_t nonFinite = 0;
    for (uint32_t z = 0; z + 1 < d.z; ++z)
        for (uint32_t y = 0; y + 1 < d.y; ++y)
            for (uint32_t x = 0; x + 1 < d.x; ++x) {
                float lo = std::numeric_limits<float>::infinity(), hi = -lo;
                bool finiteCorners = true;
                for (uint32_t n = 0; n < 8; ++n) {
                    const float v = at(x + (n & 1), y + ((n >> 1) & 1), z + (n >> 2));
                    finiteCorners = finiteCorners && std::isfinite(v);
                    lo = std::min(lo, v);
                    hi = std::max(hi, v);
                }
                if (!finiteCorners) { ++nonFinite; continue; }
                if (!(lo < hi)) continue;  // constant: no surface, or the whole cell (left out)
                const uint64_t cell = (uint64_t(z) * (d.y - 1) + y) * (d.x - 1) + x;
                const glm::vec3 corner = set.origin + glm::vec3(x, y, z) * set.spacing;
                const glm::vec3 pad = 1e-6f * (glm::abs(corner) + set.spacing);
                for (uint64_t i = 0; i < isoCount; ++i) {
                    if (set.isovalues[i] < lo || set.isovalues[i] > hi) continue;
                    g->isoCells.push_back(cell * isoCount + i);
                    boxes.push_back({corner - pad, corner + set.spacing + pad});
                }
            }
    note(*g, nonFinite, "cell(s) with a NaN or Inf voxel");
    g->inputPrimCount = g->isoCells.size();
    if (g->inputPrimCount > std::numeric_limits<uint32_t>::max()) {
        g->problems.push_back("more than 2^32 cells crossed; set skipped");
        g->isoCells.clear();
        g->inputPrimCount = 0;
        return g;
    }
    g->validPrims.resize(g->inputPrimCount);
    for (uint32_t i = 0; i < g->validPrims.size(); ++i) g->validPrims[i] = i;
    return finish(std::move(g), boxes);
}

}  // namespace ripple::core
