// Shared parameter pulling and validation of the geometry subtypes, and the triangle/quad mesh builder.
#include "anari/device/geometry/Geometry.h"

#include "anari/device/object/ArrayChecks.h"
#include "anari/device/scene/ArrayConversion.h"

#include <algorithm>
#include <string>

namespace ripple::device {
namespace {

std::string quoted(std::string_view name) {
    // Appending, not "'" + std::string(name): GCC 12 at -O3 warns (-Wrestrict) on the latter falsely.
    std::string text = "'";
    text.append(name).append("'");
    return text;
}

struct BoundsOf {
    bvh::Aabb operator()(const std::monostate&) const { return {}; }
    bvh::Aabb operator()(const core::TriangleMesh& mesh) const {
        bvh::Aabb box;
        for (const glm::vec3& p : mesh.positions) box.extend(p);
        return box;
    }
    bvh::Aabb operator()(const core::SphereSet& spheres) const {
        bvh::Aabb box;
        for (size_t i = 0; i < spheres.centers.size(); ++i) {
            const float r = spheres.radii.size() == 1 ? spheres.radii[0] : spheres.radii[i];
            box.extend(spheres.centers[i] - glm::vec3(r));
            box.extend(spheres.centers[i] + glm::vec3(r));
        }
        return box;
    }
    bvh::Aabb operator()(const core::CylinderSet& cylinders) const {
        // Every position is an endpoint of some cylinder; the largest radius bounds them all.
        float r = 0.0f;
        for (float radius : cylinders.radii) r = std::max(r, radius);
        bvh::Aabb box;
        for (const glm::vec3& p : cylinders.positions) {
            box.extend(p - glm::vec3(r));
            box.extend(p + glm::vec3(r));
        }
        return box;
    }
    bvh::Aabb operator()(const core::IsosurfaceSet& set) const {  // the whole field: no surface leaves it
        if (set.mesh) return bvh::Aabb{set.mesh->lo, set.mesh->hi};
        return {set.origin, set.origin + glm::vec3(set.dims - 1u) * set.spacing};
    }
    bvh::Aabb operator()(const core::ConeSet& cones) const {
        bvh::Aabb box;
        for (size_t i = 0; i < cones.positions.size(); ++i) {
            const float r = cones.radii.size() == 1 ? cones.radii[0] : cones.radii[i];
            box.extend(cones.positions[i] - glm::vec3(r));
            box.extend(cones.positions[i] + glm::vec3(r));
        }
        return box;
    }
};

}  // namespace

Geometry::Geometry(DeviceState& state, std::string subtype) : SceneObject(state, ANARI_GEOMETRY, std::move(subtype)) {}

void Geometry::commit() {
    forgetDependencies();
    shape_ = build();
    bounds_ = std::visit(BoundsOf{}, shape_);
}

bool Geometry::isValid() const {
    return Object::isValid() && !std::holds_alternative<std::monostate>(shape_);
}

std::optional<std::vector<glm::vec3>> Geometry::pullPositions() {
    Array* array = getArray("vertex.position");
    if (!array) {
        invalidate(has("vertex.position") ? "parameter 'vertex.position' must be an ARRAY1D of FLOAT32_VEC3"
                                          : "missing required parameter 'vertex.position'");
        return std::nullopt;
    }
    useArray(array);
    if (componentCount(array->elementType()) != 3) {
        invalidate(elementTypeProblem("vertex.position", array->elementType(), "FLOAT32_VEC3"));
        return std::nullopt;
    }
    const std::vector<glm::vec4> values = *readFloatVectors(*array);
    if (std::optional<std::string> problem = nonFiniteProblem("vertex.position", values)) {
        invalidate(*problem);
        return std::nullopt;
    }
    std::vector<glm::vec3> positions(values.size());
    for (size_t i = 0; i < values.size(); ++i) positions[i] = glm::vec3(values[i]);
    return positions;
}

bool Geometry::pullIndices(std::string_view name, int components, size_t vertexCount, std::vector<uint64_t>& indices) {
    indices.clear();
    if (!has(name)) return true;
    Array* array = getArray(name);
    if (!array) {
        invalidate("parameter " + quoted(name) + " must be an ARRAY1D of indices");
        return false;
    }
    useArray(array);
    std::optional<std::vector<uint64_t>> values = readIndices(*array, components);
    if (!values) {
        invalidate(elementTypeProblem(name, array->elementType(),
                                      std::to_string(components) + " integers per element (e.g. UINT32" +
                                          (components > 1 ? "_VEC" + std::to_string(components) : "") + ")"));
        return false;
    }
    if (std::optional<std::string> problem = indexProblem(name, *values, components, vertexCount)) {
        invalidate(*problem);
        return false;
    }
    indices = std::move(*values);
    return true;
}

std::vector<glm::vec4> Geometry::pullVectors(std::string_view name, size_t count, glm::vec4 fill) {
    if (!has(name)) return {};
    Array* array = getArray(name);
    if (!array) {
        invalidate("parameter " + quoted(name) + " must be an ARRAY1D");
        return {};
    }
    useArray(array);
    std::optional<std::vector<glm::vec4>> values = readFloatVectors(*array, fill);
    if (!values) {
        invalidate(elementTypeProblem(name, array->elementType(), "numbers (e.g. FLOAT32_VEC3)"));
        return {};
    }
    // Longer than needed is allowed (the SDK's CTS passes per-primitive arrays sized for the vertices, as
    // helide reads only the first elements); shorter is not.
    if (values->size() < count) {
        invalidate("parameter " + quoted(name) + " has " + std::to_string(values->size()) + " elements, needs " +
                   std::to_string(count));
        return {};
    }
    values->resize(count);
    if (std::optional<std::string> problem = nonFiniteProblem(name, *values)) {
        invalidate(*problem);
        return {};
    }
    return std::move(*values);
}

std::vector<glm::vec4> Geometry::pullUniformColor(size_t count) {
    const std::optional<glm::vec4> uniform = getOptional<glm::vec4>("color");
    return uniform ? std::vector<glm::vec4>(count, *uniform) : std::vector<glm::vec4>{};
}

core::GeometryAttributes Geometry::pullAttributes(size_t vertexCount, size_t primitiveCount) {
    using Rate = core::GeometryAttribute::Rate;
    core::GeometryAttributes attributes;
    for (size_t a = 0; a < attributes.size(); ++a) {
        const std::string n = std::to_string(a);
        core::GeometryAttribute& attribute = attributes[a];
        if (vertexCount > 0) attribute = {Rate::Vertex, pullVectors("vertex.attribute" + n, vertexCount)};
        if (attribute.values.empty()) attribute = {Rate::Primitive, pullVectors("primitive.attribute" + n, primitiveCount)};
        if (attribute.values.empty()) {
            if (const std::optional<glm::vec4> uniform = getOptional<glm::vec4>("attribute" + n))
                attribute = {Rate::Uniform, {*uniform}};
        } else {
            // The fallbacks, legitimately set beside the array that wins: not unused parameters.
            (void)findParameter("primitive.attribute" + n);
            (void)findParameter("attribute" + n);
        }
    }
    return attributes;
}

std::optional<Geometry::Segments> Geometry::pullSegments() {
    std::optional<std::vector<glm::vec3>> positions = pullPositions();
    if (!positions) return std::nullopt;
    std::vector<uint64_t> index;
    if (!pullIndices("primitive.index", 2, positions->size(), index)) return std::nullopt;
    if (index.empty() && positions->size() % 2 != 0)
        reportWarning("'vertex.position' has an odd number of vertices; the last one is ignored");
    Segments segments;
    segments.count = index.empty() ? positions->size() / 2 : index.size() / 2;
    segments.positions = std::move(*positions);
    for (size_t i = 0; i < index.size(); i += 2) segments.indices.emplace_back(index[i], index[i + 1]);
    return segments;
}

std::vector<glm::vec4> Geometry::pullSegmentColors(const Segments& segments) {
    std::vector<glm::vec4> colors = pullVectors("primitive.color", segments.count);
    const std::vector<glm::vec4> vertexColors = pullVectors("vertex.color", segments.positions.size());
    if (colors.empty() && !vertexColors.empty()) {
        for (size_t i = 0; i < segments.count; ++i) {
            const glm::uvec2 ends = segments.ends(i);
            colors.push_back(0.5f * (vertexColors[ends.x] + vertexColors[ends.y]));
        }
    }
    if (colors.empty()) colors = pullUniformColor(segments.count);
    return colors;
}

std::vector<core::CapEnds> Geometry::pullSegmentCaps(const Segments& segments) {
    const std::vector<glm::vec4> vertexCaps = pullVectors("vertex.cap", segments.positions.size());
    std::vector<core::CapEnds> caps;
    for (size_t i = 0; i < segments.count && !vertexCaps.empty(); ++i) {
        const glm::uvec2 ends = segments.ends(i);
        caps.push_back(core::CapEnds((vertexCaps[ends.x].x != 0.0f ? uint32_t(core::CapEnds::First) : 0u) |
                                     (vertexCaps[ends.y].x != 0.0f ? uint32_t(core::CapEnds::Second) : 0u)));
    }
    return caps;
}

core::CapEnds Geometry::pullCaps() {
    const std::string caps = getString("caps", "none");
    if (caps == "first") return core::CapEnds::First;
    if (caps == "second") return core::CapEnds::Second;
    if (caps == "both") return core::CapEnds::Both;
    if (caps != "none") reportWarning("parameter 'caps' has unknown value '" + caps + "'; using 'none'");
    return core::CapEnds::None;
}

Geometry::Shape Geometry::buildPolygonMesh(int corners) {
    std::optional<std::vector<glm::vec3>> positions = pullPositions();
    if (!positions) return {};
    const size_t vertexCount = positions->size();
    std::vector<uint64_t> polygons;
    if (!pullIndices("primitive.index", corners, vertexCount, polygons)) return {};
    if (polygons.empty()) {
        // Without an index array consecutive vertices form the polygons; a partial last one is dropped.
        if (vertexCount % corners != 0)
            reportWarning("'vertex.position' has " + std::to_string(vertexCount) + " vertices, not a multiple of " +
                          std::to_string(corners) + "; the last " + std::to_string(vertexCount % corners) +
                          " are ignored");
        polygons.resize(vertexCount / corners * corners);
        for (size_t i = 0; i < polygons.size(); ++i) polygons[i] = i;
    }
    const size_t polygonCount = polygons.size() / corners;

    core::TriangleMesh mesh;
    mesh.positions = std::move(*positions);
    mesh.trianglesPerPrimitive = uint32_t(corners - 2);
    mesh.indices.reserve(polygonCount * mesh.trianglesPerPrimitive);
    for (size_t p = 0; p < polygonCount; ++p) {
        const uint64_t* v = &polygons[p * corners];
        mesh.indices.emplace_back(v[0], v[1], v[2]);
        if (corners == 4) mesh.indices.emplace_back(v[0], v[2], v[3]);
    }

    for (const glm::vec4& n : pullVectors("vertex.normal", vertexCount)) mesh.normals.emplace_back(n);
    mesh.colors = pullVectors("vertex.color", vertexCount);
    // vertex.tangent: VEC3 reads w = 1 (the fill), a VEC4's w is the handedness.
    mesh.tangents = pullVectors("vertex.tangent", vertexCount);
    mesh.attributes = pullAttributes(vertexCount, polygonCount);
    // A per-vertex attribute0 is also the texture coordinate: normal maps take their tangent frame from it.
    if (mesh.attributes[0].rate == core::GeometryAttribute::Rate::Vertex)
        for (const glm::vec4& t : mesh.attributes[0].values) mesh.texcoords.emplace_back(t);
    std::vector<glm::vec4> polygonColors = pullVectors("primitive.color", polygonCount);
    if (polygonColors.empty() && mesh.colors.empty()) polygonColors = pullUniformColor(polygonCount);
    // Core stores primitive colours per triangle: each quad's colour goes to both of its halves.
    for (const glm::vec4& color : polygonColors)
        mesh.primitiveColors.insert(mesh.primitiveColors.end(), mesh.trianglesPerPrimitive, color);
    return mesh;
}

}  // namespace ripple::device
