// ANARI geometry: the subtypes (triangle, quad, sphere, cylinder, cone, curve, isosurface) pull their arrays at commit, validate
// them and keep the core geometry they describe, ready to be copied into a core::SceneDescription.
#pragma once

#include "anari/device/scene/SceneObject.h"
#include "core/bvh/Aabb.h"
#include "core/scene/SceneDescription.h"

#include <optional>
#include <variant>

namespace ripple::device {

class Geometry : public SceneObject {
public:
    // monostate: nothing valid was committed.
    using Shape = std::variant<std::monostate, core::TriangleMesh, core::SphereSet, core::CylinderSet, core::ConeSet,
                               core::IsosurfaceSet>;

    Geometry(DeviceState& state, std::string subtype);

    void commit() final;
    bool isValid() const override;
    const Shape& shape() const { return shape_; }
    // Object-space bounds of the committed primitives (spheres and cylinders include their radii).
    const bvh::Aabb& bounds() const { return bounds_; }

protected:
    // The subtype's part of commit(): pulls its parameters and returns the shape, or monostate after
    // invalidate() named the parameter at fault.
    virtual Shape build() = 0;

    // "vertex.position": required, three components, all finite (else invalidate() names the problem).
    std::optional<std::vector<glm::vec3>> pullPositions();
    // An optional index array of `components` integers per primitive, each below vertexCount. Fills
    // `indices` (empty when unset); false after invalidate() for a wrong type or an index out of range.
    bool pullIndices(std::string_view name, int components, size_t vertexCount, std::vector<uint64_t>& indices);
    // An optional per-vertex or per-primitive array of float vectors, its first `count` elements; empty when
    // unset. A wrong type, fewer elements, or a NaN/Inf element invalidates the geometry (reported once).
    std::vector<glm::vec4> pullVectors(std::string_view name, size_t count, glm::vec4 fill = {0, 0, 0, 1});
    // The uniform "color" repeated `count` times; empty when unset. It applies when neither
    // "primitive.color" nor "vertex.color" is given.
    std::vector<glm::vec4> pullUniformColor(size_t count);
    // attribute0..3: "vertex.attributeN" (its first vertexCount elements), else "primitive.attributeN" (first
    // primitiveCount), else the uniform "attributeN"; unset ones stay empty. A vertexCount of 0 (a geometry
    // without vertices: isosurface) reads no "vertex.attributeN".
    core::GeometryAttributes pullAttributes(size_t vertexCount, size_t primitiveCount);
    // Cylinders and cones: two vertices per primitive, consecutive or from "primitive.index".
    struct Segments {
        std::vector<glm::vec3> positions;
        std::vector<glm::uvec2> indices;  // empty: consecutive pairs (an odd last vertex is ignored)
        size_t count = 0;
        glm::uvec2 ends(size_t i) const { return indices.empty() ? glm::uvec2(2 * i, 2 * i + 1) : indices[i]; }
    };
    std::optional<Segments> pullSegments();
    // "primitive.color"; else "vertex.color" averaged over each segment's two ends (core colours whole
    // segments); else the uniform "color".
    std::vector<glm::vec4> pullSegmentColors(const Segments& segments);
    // "caps" of cylinders and cones: none, first, second or both (unknown values are reported: none).
    core::CapEnds pullCaps();
    // "vertex.cap" (nonzero: a flat disk closes the segments at that vertex) as the ends of each segment;
    // empty when unset (or unusable, reported).
    std::vector<core::CapEnds> pullSegmentCaps(const Segments& segments);
    // Triangle and quad meshes: polygons of `corners` vertices (3 or 4), quads split into two triangles.
    Shape buildPolygonMesh(int corners);

private:
    Shape shape_;
    bvh::Aabb bounds_;
};

Geometry* newTriangleGeometry(DeviceState& state);
Geometry* newQuadGeometry(DeviceState& state);
Geometry* newSphereGeometry(DeviceState& state);
Geometry* newCylinderGeometry(DeviceState& state);
Geometry* newConeGeometry(DeviceState& state);
Geometry* newCurveGeometry(DeviceState& state);
Geometry* newIsosurfaceGeometry(DeviceState& state);

}  // namespace ripple::device
