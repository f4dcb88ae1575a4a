// Checking and packing unstructured meshes for the kernels (see UnstructuredGrid.h).
#include "core/scene/UnstructuredGrid.h"

#include "core/bvh/BinnedSahBuilder.h"
#include "shaders/shared/volume.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <utility>

namespace ripple::core {

namespace {

using glm::dvec3;

constexpr uint32_t kMaxIndices = uint32_t(1) << 30;  // a cell's word keeps its first index in 30 bits
constexpr uint32_t kLeafCells = 8;                    // point location tests every cell of a leaf
// A start cell's side in median cells, as near as a whole number of them per macrocell edge allows: a walk
// from its tetrahedron to a point in it seldom crosses more than a face or two.
constexpr double kStartCellSide = 0.5;

uint32_t shapeOf(uint8_t type) {
    switch (type) {
        case 10: return gpu::UNSTRUCTURED_TETRAHEDRON;
        case 12: return gpu::UNSTRUCTURED_HEXAHEDRON;
        case 13: return gpu::UNSTRUCTURED_WEDGE;
        default: return gpu::UNSTRUCTURED_PYRAMID;
    }
}

double det(const dvec3& a, const dvec3& b, const dvec3& c) { return glm::dot(a, glm::cross(b, c)); }

// The Jacobian determinant of the cell's map from its parametric space (shaders/unstructured.glsl) at an
// inner point: its sign is the cell's orientation, positive for VTK's vertex order (VTK orders a wedge's
// first triangle with its normal pointing away from the second, hence the sign flip there).
double orientedVolume(uint8_t type, const dvec3* x) {
    switch (type) {
        case 10: return det(x[1] - x[0], x[2] - x[0], x[3] - x[0]);
        case 12:
            return det(0.25 * ((x[1] - x[0]) + (x[2] - x[3]) + (x[5] - x[4]) + (x[6] - x[7])),
                       0.25 * ((x[3] - x[0]) + (x[2] - x[1]) + (x[7] - x[4]) + (x[6] - x[5])),
                       0.25 * ((x[4] - x[0]) + (x[5] - x[1]) + (x[6] - x[2]) + (x[7] - x[3])));
        case 13: {
            const double third = 1.0 / 3.0;
            return -det(0.5 * ((x[1] - x[0]) + (x[4] - x[3])), 0.5 * ((x[2] - x[0]) + (x[5] - x[3])),
                        third * ((x[3] - x[0]) + (x[4] - x[1]) + (x[5] - x[2])));
        }
        default: {
            const dvec3 base = 0.25 * (x[0] + x[1] + x[2] + x[3]);
            return det(0.5 * ((x[1] - x[0]) + (x[2] - x[3])), 0.5 * ((x[3] - x[0]) + (x[2] - x[1])), x[4] - base);
        }
    }
}

void pushFloat(std::vector<uint32_t>& words, float f) {
    uint32_t bits = 0;
    std::memcpy(&bits, &f, sizeof bits);
    words.push_back(bits);
}

// Macrocells per axis over a box of `extent`: cubes as far as the box allows, their side `cellSize` (the
// median of the cells' longest box edges: a thin shell of cells in a large box still gets macrocells about as
// small as its cells, and majorants that follow it), at most 2^21 of them and 256 per axis. Larger macrocells
// are crossed faster but give looser majorants (docs/unstructured.md has the measurements).
glm::uvec3 macrocellCounts(glm::dvec3 extent, double cellSize) {
    const double longest = std::max({extent.x, extent.y, extent.z});
    const dvec3 e = glm::max(extent, dvec3(longest * 1e-3));
    double side = std::max(cellSize, longest / 256.0);
    side = std::max(side, std::cbrt(e.x * e.y * e.z / double(1 << 21)));
    glm::uvec3 counts;
    for (int a = 0; a < 3; ++a) counts[a] = uint32_t(std::clamp(std::round(e[a] / side), 1.0, 256.0));
    return counts;
}

std::string cellName(uint64_t c) { return "cell " + std::to_string(c); }

// The cells of a grid of `counts` cells, `perUnit` of them per grid unit, that the grid-space box [lo, hi]
// overlaps, clamped to the grid: macrocells (perUnit 1/8) or start cells.
struct CellSpan {
    glm::uvec3 first, last;
    double count() const {
        const glm::dvec3 n = glm::dvec3(last) - glm::dvec3(first) + 1.0;
        return n.x * n.y * n.z;
    }
    template <class Visit>
    void forEach(const Visit& visit) const {
        for (uint32_t z = first.z; z <= last.z; ++z)
            for (uint32_t y = first.y; y <= last.y; ++y)
                for (uint32_t x = first.x; x <= last.x; ++x) visit(glm::uvec3(x, y, z));
    }
};

CellSpan overlappedCells(glm::vec3 lo, glm::vec3 hi, float perUnit, glm::uvec3 counts) {
    return {glm::min(glm::uvec3(glm::max(lo * perUnit, 0.0f)), counts - 1u), glm::min(glm::uvec3(glm::max(hi * perUnit, 0.0f)), counts - 1u)};
}

// A tetrahedron's face planes, normals outward: a box wholly outside one of them misses the tetrahedron. Each
// plane is moved out by 1e-4 of the cell's size, more than the kernels' inside tolerance (1e-5 of a barycentric
// coordinate) reaches, plus the float rounding of those coordinates, which grows as the face's area shrinks
// against the cell's size (needles).
struct FacePlanes {
    std::array<dvec3, 4> normal;
    std::array<double, 4> offset;
    bool finite() const {
        for (int f = 0; f < 4; ++f)
            if (!std::isfinite(offset[f]) || !std::isfinite(normal[f].x) || !std::isfinite(normal[f].y) || !std::isfinite(normal[f].z))
                return false;
        return true;
    }
    // NaN planes (a face flat in grid space) miss nothing.
    bool miss(const dvec3& lo, const dvec3& hi) const {
        for (int f = 0; f < 4; ++f) {
            const dvec3 nearest = glm::mix(hi, lo, glm::greaterThan(normal[f], dvec3(0.0)));  // the corner deepest inside
            if (glm::dot(normal[f], nearest) > offset[f]) return true;
        }
        return false;
    }
};

template <class ToGrid>
FacePlanes facePlanes(const UnstructuredCells& cells, uint32_t c, const ToGrid& toGrid) {
    dvec3 x[4];
    for (uint32_t k = 0; k < 4; ++k) x[k] = dvec3(toGrid(cells.positions[cells.index[cells.cellIndex[c] + k]]));
    const dvec3 extent = glm::max(glm::max(x[0], x[1]), glm::max(x[2], x[3])) - glm::min(glm::min(x[0], x[1]), glm::min(x[2], x[3]));
    const double size = std::max({extent.x, extent.y, extent.z});
    FacePlanes planes;
    for (int k = 0; k < 4; ++k) {  // the face opposite corner k
        const dvec3 a = x[(k + 1) % 4], b = x[(k + 2) % 4], d = x[(k + 3) % 4];
        const dvec3 cross = glm::cross(b - a, d - a);
        dvec3 n = cross / glm::length(cross);
        if (glm::dot(n, x[k] - a) > 0.0) n = -n;
        planes.normal[k] = n;
        planes.offset[k] = glm::dot(n, a) + 1e-4 * size + 16.0 * std::ldexp(1.0, -24) * size * size * size / glm::length(cross);
    }
    return planes;
}

// For the walk from tetrahedron to tetrahedron (shaders/unstructured.glsl): per cell in leaf order, the
// leaf-order cells across the faces opposite its corners 0..3, UNSTRUCTURED_NO_CELL where no other
// tetrahedron shares the face (the boundary, a cell of another shape, or a face whose corners are other vertices
// at the same positions). Faces are matched by their sorted vertex indices; empty without tetrahedra.
std::vector<uint32_t> tetrahedronNeighbours(const UnstructuredCells& cells, const std::vector<uint32_t>& kept,
                                            const std::vector<uint32_t>& leafOrder) {
    struct Face {
        std::array<uint32_t, 3> corners;  // sorted
        uint32_t slot;                    // 4 * leaf-order cell + the corner the face is opposite
    };
    std::vector<Face> faces;
    for (uint32_t leaf = 0; leaf < leafOrder.size(); ++leaf) {
        const uint32_t c = kept[leafOrder[leaf]];
        if (cells.cellType[c] != 10) continue;
        const uint32_t* corner = cells.index.data() + cells.cellIndex[c];
        for (uint32_t k = 0; k < 4; ++k) {
            Face face{{corner[(k + 1) % 4], corner[(k + 2) % 4], corner[(k + 3) % 4]}, 4 * leaf + k};
            std::sort(face.corners.begin(), face.corners.end());
            faces.push_back(face);
        }
    }
    if (faces.empty()) return {};
    std::sort(faces.begin(), faces.end(), [](const Face& a, const Face& b) { return a.corners < b.corners; });
    std::vector<uint32_t> neighbours(4 * leafOrder.size(), gpu::UNSTRUCTURED_NO_CELL);
    // A face shared by exactly two tetrahedra links them; one held by three or more (overlapping cells) links
    // none, so that every link is mutual.
    for (size_t first = 0, last = 0; first < faces.size(); first = last) {
        while (last < faces.size() && faces[last].corners == faces[first].corners) ++last;
        if (last - first != 2) continue;
        neighbours[faces[first].slot] = faces[first + 1].slot / 4;
        neighbours[faces[first + 1].slot] = faces[first].slot / 4;
    }
    return neighbours;
}

// Each start cell's tetrahedron (leaf order), where walks to its points begin (shaders/unstructured.glsl):
// one that holds the start cell's centre; else, of those whose centroid lies in the start cell, the one whose
// centroid is nearest the centre; else, where some cell overlaps the start cell (`startNodes`), a neighbouring
// start cell's (two rounds); else none. `boxes`: the kept cells' grid-space boxes.
template <class ToGrid>
std::vector<uint32_t> startTetrahedra(const UnstructuredCells& cells, const std::vector<uint32_t>& kept, const std::vector<uint32_t>& leafOrder,
                                      const std::vector<bvh::Aabb>& boxes, const ToGrid& toGrid, glm::uvec3 startCells, float startScale,
                                      const std::vector<uint32_t>& startNodes) {
    const auto indexOf = [&](glm::uvec3 at) { return (size_t(at.z) * startCells.y + at.y) * startCells.x + at.x; };
    std::vector<uint32_t> start(size_t(startCells.x) * startCells.y * startCells.z, gpu::UNSTRUCTURED_NO_CELL);
    std::vector<double> distance(start.size(), INFINITY);  // of the chosen centroid from the centre; -1: holds it
    for (uint32_t leaf = 0; leaf < leafOrder.size(); ++leaf) {
        const uint32_t c = kept[leafOrder[leaf]];
        if (cells.cellType[c] != 10) continue;
        const FacePlanes planes = facePlanes(cells, c, toGrid);
        if (!planes.finite()) continue;  // flat in grid space: no walk should start there
        const bvh::Aabb& box = boxes[leafOrder[leaf]];
        overlappedCells(box.lo, box.hi, startScale, startCells).forEach([&](glm::uvec3 at) {
            const dvec3 centre = (dvec3(at) + 0.5) / double(startScale);
            const size_t i = indexOf(at);
            if (distance[i] >= 0.0 && !planes.miss(centre, centre)) {
                distance[i] = -1.0;
                start[i] = leaf;
            }
        });
        dvec3 centroid(0.0);
        for (uint32_t k = 0; k < 4; ++k) centroid += 0.25 * dvec3(toGrid(cells.positions[cells.index[cells.cellIndex[c] + k]]));
        const glm::uvec3 at = glm::min(glm::uvec3(glm::max(centroid * double(startScale), 0.0)), startCells - 1u);
        const double d = glm::length(centroid - (dvec3(at) + 0.5) / double(startScale));
        if (distance[indexOf(at)] >= 0.0 && d < distance[indexOf(at)]) {
            distance[indexOf(at)] = d;
            start[indexOf(at)] = leaf;
        }
    }
    for (int round = 0; round < 2; ++round) {
        std::vector<uint32_t> grown = start;
        for (uint32_t z = 0; z < startCells.z; ++z)
            for (uint32_t y = 0; y < startCells.y; ++y)
                for (uint32_t x = 0; x < startCells.x; ++x) {
                    uint32_t& s = grown[indexOf({x, y, z})];
                    if (startNodes[indexOf({x, y, z})] == gpu::UNSTRUCTURED_NO_NODE) continue;  // the query returns at once
                    for (int k = 0; k < 6 && s == gpu::UNSTRUCTURED_NO_CELL; ++k) {
                        glm::ivec3 there(x, y, z);
                        there[k / 2] += k % 2 ? 1 : -1;
                        if (glm::all(glm::greaterThanEqual(there, glm::ivec3(0))) && glm::all(glm::lessThan(there, glm::ivec3(startCells))))
                            s = start[indexOf(glm::uvec3(there))];
                    }
                }
        start = std::move(grown);
    }
    return start;
}

}  // namespace

uint32_t unstructuredCorners(uint8_t type) {
    switch (type) {
        case 10: return 4;
        case 12: return 8;
        case 13: return 6;
        case 14: return 5;
        default: return 0;
    }
}

std::shared_ptr<const UnstructuredGrid> prepareUnstructuredGrid(const UnstructuredCells& cells) {
    const size_t vertexCount = cells.positions.size(), cellCount = cells.cellType.size();
    if (vertexCount == 0) throw std::invalid_argument("no vertices");
    if (cellCount == 0) throw std::invalid_argument("no cells");
    if (cells.cellIndex.size() != cellCount)
        throw std::invalid_argument(std::to_string(cells.cellIndex.size()) + " cell indices for " + std::to_string(cellCount) +
                                    " cell types");
    const size_t valueCount = cells.cellCentered ? cellCount : vertexCount;
    if (cells.values.size() != valueCount)
        throw std::invalid_argument(std::to_string(cells.values.size()) + " values for " + std::to_string(valueCount) +
                                    (cells.cellCentered ? " cells" : " vertices"));
    if (cells.index.size() >= kMaxIndices)
        throw std::invalid_argument(std::to_string(cells.index.size()) + " indices, more than 2^30");
    for (size_t v = 0; v < vertexCount; ++v) {
        const glm::vec3 p = cells.positions[v];
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            throw std::invalid_argument("vertex " + std::to_string(v) + "'s position is not finite");
    }
    for (size_t i = 0; i < valueCount; ++i)
        if (!std::isfinite(cells.values[i]))
            throw std::invalid_argument((cells.cellCentered ? "cell " : "vertex ") + std::to_string(i) + "'s value is not finite");
    for (size_t i = 0; i < cells.index.size(); ++i)
        if (cells.index[i] >= vertexCount)
            throw std::invalid_argument("index " + std::to_string(i) + " is " + std::to_string(cells.index[i]) + ", past the " +
                                        std::to_string(vertexCount) + " vertices");

    auto grid = std::make_shared<UnstructuredGrid>();
    std::vector<uint32_t> kept;
    std::vector<bvh::Aabb> boxes;
    bvh::Aabb whole;
    uint64_t firstDegenerate = 0, firstInverted = 0;
    for (size_t c = 0; c < cellCount; ++c) {
        const uint8_t type = cells.cellType[c];
        const uint32_t corners = unstructuredCorners(type);
        if (corners == 0)
            throw std::invalid_argument(cellName(c) + " has type " + std::to_string(type) +
                                        "; Ripple takes 10 (tetrahedron), 12 (hexahedron), 13 (wedge) and 14 (pyramid)");
        if (uint64_t(cells.cellIndex[c]) + corners > cells.index.size())
            throw std::invalid_argument(cellName(c) + "'s " + std::to_string(corners) + " indices from " +
                                        std::to_string(cells.cellIndex[c]) + " run past the " +
                                        std::to_string(cells.index.size()) + " of the index array");
        dvec3 x[8];
        bvh::Aabb box;
        for (uint32_t k = 0; k < corners; ++k) {
            const glm::vec3 p = cells.positions[cells.index[cells.cellIndex[c] + k]];
            x[k] = dvec3(p);
            box.extend(p);
        }
        const double volume = orientedVolume(type, x);
        const dvec3 extent = dvec3(box.hi) - dvec3(box.lo);
        // Zero volume, relative to the cell's box (so that thin cells of any scale and aspect are kept):
        // no point is inside it, and its inverse map is singular.
        if (!(std::abs(volume) > 1e-12 * extent.x * extent.y * extent.z) || !(extent.x * extent.y * extent.z > 0.0)) {
            if (grid->degenerateCells++ == 0) firstDegenerate = c;
            continue;
        }
        if (volume < 0.0 && grid->invertedCells++ == 0) firstInverted = c;
        kept.push_back(uint32_t(c));
        boxes.push_back(box);
        whole.extend(box);
    }
    if (grid->degenerateCells)
        grid->warnings.push_back(std::to_string(grid->degenerateCells) + " cell(s) of zero volume dropped (the first is " +
                                 cellName(firstDegenerate) + ")");
    if (grid->invertedCells)
        grid->warnings.push_back(std::to_string(grid->invertedCells) + " cell(s) with corners in the order opposite to VTK's "
                                 "(inverted; rendered as given, the first is " + cellName(firstInverted) + ")");
    if (kept.empty()) throw std::invalid_argument("no cell has volume (all " + std::to_string(cellCount) + " are degenerate)");
    grid->cellsKept = kept.size();
    grid->lo = whole.lo;
    grid->hi = whole.hi;

    // Grid space: [lo, hi] onto [0, 8 * macrocells] per axis.
    const dvec3 extent = dvec3(whole.hi) - dvec3(whole.lo);
    std::vector<double> cellSizes(boxes.size());
    for (size_t k = 0; k < boxes.size(); ++k) {
        const dvec3 size = dvec3(boxes[k].hi) - dvec3(boxes[k].lo);
        cellSizes[k] = std::max({size.x, size.y, size.z});
    }
    // The kernels map rays into grid space in float: the box and its scale must stay finite there.
    if (!std::isfinite(float(extent.x)) || !std::isfinite(float(extent.y)) || !std::isfinite(float(extent.z)))
        throw std::invalid_argument("the mesh's box is wider than a float can hold");
    std::nth_element(cellSizes.begin(), cellSizes.begin() + std::ptrdiff_t(cellSizes.size() / 2), cellSizes.end());
    const double medianCell = cellSizes[cellSizes.size() / 2];
    grid->macrocells = macrocellCounts(extent, medianCell);
    // Every (cell, macrocell it overlaps) pair is visited below: macrocells are coarsened until there are at
    // most 64 per cell or macrocell (overlapping cells of very different sizes would otherwise multiply them).
    const auto overlaps = [&](glm::uvec3 counts) {
        const dvec3 perUnit = dvec3(counts) / extent;
        double pairs = 0.0;
        for (const bvh::Aabb& box : boxes) {
            const dvec3 first = glm::floor((dvec3(box.lo) - dvec3(whole.lo)) * perUnit);
            const dvec3 last = glm::min(glm::floor((dvec3(box.hi) - dvec3(whole.lo)) * perUnit), dvec3(counts) - 1.0);
            pairs += (last.x - first.x + 1.0) * (last.y - first.y + 1.0) * (last.z - first.z + 1.0);
        }
        return pairs;
    };
    while (glm::any(glm::greaterThan(grid->macrocells, glm::uvec3(1u))) &&
           overlaps(grid->macrocells) > 64.0 * double(boxes.size() + size_t(grid->macrocells.x) * grid->macrocells.y * grid->macrocells.z))
        grid->macrocells = glm::max(grid->macrocells / 2u, glm::uvec3(1u));
    const dvec3 scale = dvec3(grid->macrocells) * double(gpu::VOLUME_MACROCELL) / extent;
    if (!std::isfinite(float(scale.x)) || !std::isfinite(float(scale.y)) || !std::isfinite(float(scale.z)))
        throw std::invalid_argument("the mesh's box is narrower than a float can scale to its macrocells");
    grid->gridScale = glm::vec3(scale);
    grid->cellCentered = cells.cellCentered;
    const auto toGrid = [&](glm::vec3 p) { return glm::vec3((dvec3(p) - dvec3(whole.lo)) * scale); };
    std::vector<bvh::Aabb> objectBoxes = boxes;
    for (bvh::Aabb& box : boxes) box = bvh::Aabb{toGrid(box.lo), toGrid(box.hi)};

    bvh::BuildOptions options;
    options.maxLeafSize = kLeafCells;
    const bvh::Bvh tree = bvh::buildBinnedSah(boxes, options);
    grid->bvhDepth = tree.depth;

    // The value range of each macrocell, over the cells that overlap it: an interpolated value lies between
    // its cell's lowest and highest corner values (every shape function is non-negative inside). A cell
    // overlaps the macrocells its box does, less, for a tetrahedron, those wholly outside one of its faces'
    // planes (a sliver's box holds many macrocells the sliver misses).
    const glm::uvec3 m = grid->macrocells;
    grid->macrocellRanges.assign(size_t(m.x) * m.y * m.z, glm::vec2(INFINITY, -INFINITY));
    std::vector<glm::vec2> cellRanges(kept.size());
    for (size_t k = 0; k < kept.size(); ++k) {
        const uint32_t c = kept[k];
        glm::vec2 range(INFINITY, -INFINITY);
        if (cells.cellCentered) {
            range = glm::vec2(cells.values[c]);
        } else {
            for (uint32_t j = 0; j < unstructuredCorners(cells.cellType[c]); ++j) {
                const float value = cells.values[cells.index[cells.cellIndex[c] + j]];
                range = glm::vec2(std::min(range.x, value), std::max(range.y, value));
            }
        }
        cellRanges[k] = range;
        // The walk (shaders/unstructured.glsl) takes points up to 1e-5 of a barycentric coordinate outside a
        // tetrahedron as inside, also past its box where a face lies in the box's side. With values on the
        // vertices the field there is the neighbour's, to rounding; with a value per cell it may jump, so
        // the box is grown by 1e-4 of its size. (Growing every box cost the million-tetrahedra benchmark, whose
        // cubes' faces lie on macrocell planes, 0.53 -> 0.58 null/real.)
        const double size = double(gpu::VOLUME_MACROCELL);
        const glm::vec3 extentK = boxes[k].hi - boxes[k].lo;
        const glm::vec3 grow(cells.cellCentered ? 1e-4f * std::max({extentK.x, extentK.y, extentK.z}) : 0.0f);
        const CellSpan span = overlappedCells(boxes[k].lo - grow, boxes[k].hi + grow, 1.0f / float(size), m);
        const bool tetrahedron = cells.cellType[c] == 10 && span.first != span.last;
        const FacePlanes planes = tetrahedron ? facePlanes(cells, c, toGrid) : FacePlanes{};
        span.forEach([&](glm::uvec3 at) {
            if (tetrahedron && planes.miss(dvec3(at) * size, (dvec3(at) + 1.0) * size)) return;
            glm::vec2& r = grid->macrocellRanges[(size_t(at.z) * m.y + at.y) * m.x + at.x];
            r = glm::vec2(std::min(r.x, range.x), std::max(r.y, range.y));
        });
    }

    for (uint32_t slot : tree.primOrder) {
        grid->cellBoxes.emplace_back(objectBoxes[slot].lo, objectBoxes[slot].hi);
        grid->cellRanges.push_back(cellRanges[slot]);
    }

    // Each start cell's node: the lowest common ancestor of the nodes holding the leaves of the cells that
    // overlap it (a cell's leaf is a child slot of one node).
    const size_t nodeCount = tree.nodes.size();
    std::vector<uint32_t> parent(nodeCount, gpu::UNSTRUCTURED_NO_NODE), depth(nodeCount, 0), nodeOfSlot(kept.size(), 0);
    for (uint32_t n = 0; n < nodeCount; ++n) {
        const gpu::BvhNode& node = tree.nodes[n];
        for (const auto& [lo, hi] : {std::pair{node.leftMin, node.leftMax}, std::pair{node.rightMin, node.rightMax}}) {
            uint32_t ref = 0, count = 0;
            std::memcpy(&ref, &lo.w, sizeof ref);
            std::memcpy(&count, &hi.w, sizeof count);
            if (count > 0)
                for (uint32_t slot = ref; slot < ref + count; ++slot) nodeOfSlot[slot] = n;
            else if (ref != 0)
                parent[ref] = n;
        }
    }
    for (uint32_t n = 1; n < nodeCount; ++n) depth[n] = depth[parent[n]] + 1;  // parents come first
    const auto commonAncestor = [&](uint32_t a, uint32_t b) {
        while (a != b) {
            if (depth[a] >= depth[b]) a = parent[a];
            else b = parent[b];
        }
        return a;
    };
    // Start cells per macrocell edge, at most 8; fewer while there are more than 2 per cell in all (or 2^15), or
    // more than 64 (cell, start cell it overlaps) pairs, visited below, per cell or start cell. A start cell
    // spans startPerMacrocell / 8 grid units (exact in float, and the kernels scale by the same product).
    const dvec3 macrocellSide = extent / dvec3(m);
    uint32_t startPerMacrocell = uint32_t(std::clamp(
        std::round(std::max({macrocellSide.x, macrocellSide.y, macrocellSide.z}) / (kStartCellSide * medianCell)), 1.0, 8.0));
    const auto startPairs = [&](uint32_t perMacrocell) {
        double pairs = 0.0;
        for (const bvh::Aabb& box : boxes) pairs += overlappedCells(box.lo, box.hi, float(perMacrocell) * 0.125f, m * perMacrocell).count();
        return pairs;
    };
    while (startPerMacrocell > 1) {
        const double count = double(m.x) * m.y * m.z * std::pow(double(startPerMacrocell), 3.0);
        if (count <= std::max(2.0 * double(kept.size()), double(1 << 15)) &&
            startPairs(startPerMacrocell) <= 64.0 * (double(kept.size()) + count))
            break;
        --startPerMacrocell;
    }
    const glm::uvec3 startCells = m * startPerMacrocell;
    const float startScale = float(startPerMacrocell) * 0.125f;  // start cells per grid unit
    std::vector<uint32_t> start(size_t(startCells.x) * startCells.y * startCells.z, gpu::UNSTRUCTURED_NO_NODE);
    for (size_t slot = 0; slot < kept.size(); ++slot) {
        const bvh::Aabb& box = boxes[tree.primOrder[slot]];
        overlappedCells(box.lo, box.hi, startScale, startCells).forEach([&](glm::uvec3 at) {
            uint32_t& s = start[(size_t(at.z) * startCells.y + at.y) * startCells.x + at.x];
            s = s == gpu::UNSTRUCTURED_NO_NODE ? nodeOfSlot[slot] : commonAncestor(s, nodeOfSlot[slot]);
        });
    }

    // The words: header, vertices (grid space, with their values), cell values, cells in leaf order,
    // indices (and tetrahedra's neighbours), nodes, start nodes, start tetrahedra.
    std::vector<uint32_t>& words = grid->words;
    gpu::UnstructuredHeader header{};
    header.cellCount = uint32_t(kept.size());
    header.nodeCount = uint32_t(nodeCount);
    header.cellCentered = cells.cellCentered ? 1u : 0u;
    header.startX = startCells.x;
    header.startY = startCells.y;
    header.startZ = startCells.z;
    header.startPerMacrocell = startPerMacrocell;
    const auto align4 = [&] { words.resize((words.size() + 3) / 4 * 4); };
    words.resize(sizeof(header) / sizeof(uint32_t));
    align4();
    // Vertices in the order the leaf-order cells first use them (those no kept cell uses are left out), so
    // that cells near each other in the BVH find their corners near each other in memory.
    std::vector<uint32_t> renumbered(vertexCount, gpu::UNSTRUCTURED_NO_CELL), usedVertices;
    for (uint32_t slot : tree.primOrder) {
        const uint32_t c = kept[slot];
        for (uint32_t k = 0; k < unstructuredCorners(cells.cellType[c]); ++k) {
            const uint32_t v = cells.index[cells.cellIndex[c] + k];
            if (renumbered[v] == gpu::UNSTRUCTURED_NO_CELL) {
                renumbered[v] = uint32_t(usedVertices.size());
                usedVertices.push_back(v);
            }
        }
    }
    header.vertexOffset = uint32_t(words.size());
    for (uint32_t v : usedVertices) {
        const glm::vec3 g = toGrid(cells.positions[v]);
        pushFloat(words, g.x);
        pushFloat(words, g.y);
        pushFloat(words, g.z);
        pushFloat(words, cells.cellCentered ? 0.0f : cells.values[v]);
    }
    header.cellValueOffset = uint32_t(words.size());
    if (cells.cellCentered)
        for (uint32_t slot : tree.primOrder) pushFloat(words, cells.values[kept[slot]]);
    // Each cell's corners in leaf order, a tetrahedron's followed by its neighbours when the mesh has them:
    // a step of the walk reads one cell's 8 words together.
    uint64_t indexWords = 0;
    for (uint32_t c : kept) indexWords += unstructuredCorners(cells.cellType[c]) + (cells.cellType[c] == 10 ? 4 : 0);
    if (indexWords >= kMaxIndices) throw std::invalid_argument("the mesh's cells need more than 2^30 index words on the device");
    const std::vector<uint32_t> neighbours = tetrahedronNeighbours(cells, kept, tree.primOrder);
    const bool allTetrahedra = std::all_of(kept.begin(), kept.end(), [&](uint32_t c) { return cells.cellType[c] == 10; });
    header.neighbours = neighbours.empty() ? gpu::UNSTRUCTURED_NEIGHBOURS_NONE
                        : allTetrahedra    ? gpu::UNSTRUCTURED_NEIGHBOURS_ALL_TETRAHEDRA
                                           : gpu::UNSTRUCTURED_NEIGHBOURS_SOME_TETRAHEDRA;
    std::vector<uint32_t> index, cellWords;
    for (uint32_t leaf = 0; leaf < tree.primOrder.size(); ++leaf) {
        const uint32_t c = kept[tree.primOrder[leaf]];
        cellWords.push_back(uint32_t(index.size()) << 2 | shapeOf(cells.cellType[c]));
        for (uint32_t k = 0; k < unstructuredCorners(cells.cellType[c]); ++k) index.push_back(renumbered[cells.index[cells.cellIndex[c] + k]]);
        if (header.neighbours && cells.cellType[c] == 10) index.insert(index.end(), &neighbours[4 * leaf], &neighbours[4 * leaf] + 4);
    }
    header.cellOffset = uint32_t(words.size());
    words.insert(words.end(), cellWords.begin(), cellWords.end());
    header.indexOffset = uint32_t(words.size());
    if (uint64_t(words.size()) + index.size() > uint64_t(UINT32_MAX))
        throw std::invalid_argument("the mesh needs more than 2^32 words on the device");
    words.insert(words.end(), index.begin(), index.end());
    align4();
    header.nodeOffset = uint32_t(words.size());
    const size_t nodeWords = nodeCount * sizeof(gpu::BvhNode) / sizeof(uint32_t);
    const std::vector<uint32_t> startCell =
        header.neighbours ? startTetrahedra(cells, kept, tree.primOrder, boxes, toGrid, startCells, startScale, start) : std::vector<uint32_t>();
    if (uint64_t(words.size()) + nodeWords + start.size() + startCell.size() > uint64_t(UINT32_MAX))
        throw std::invalid_argument("the mesh needs more than 2^32 words on the device");
    words.resize(words.size() + nodeWords);
    std::memcpy(words.data() + header.nodeOffset, tree.nodes.data(), nodeWords * sizeof(uint32_t));
    header.startOffset = uint32_t(words.size());
    words.insert(words.end(), start.begin(), start.end());
    header.startCellOffset = uint32_t(words.size());
    words.insert(words.end(), startCell.begin(), startCell.end());
    std::memcpy(words.data(), &header, sizeof(header));
    return grid;
}

}  // namespace ripple::core
