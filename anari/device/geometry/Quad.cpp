// Geometry subtype "quad" (KHR_GEOMETRY_QUAD): quads (v0 v1 v2 v3) rendered as triangles (v0 v1 v2) and
// (v0 v2 v3); core reports triangle / 2 as the primitive id, so ids still count quads.
#include "anari/device/geometry/Geometry.h"

namespace ripple::device {
namespace {

class QuadGeometry final : public Geometry {
public:
    explicit QuadGeometry(DeviceState& state) : Geometry(state, "quad") {}

private:
    Shape build() override { return buildPolygonMesh(4); }
};

}  // namespace

Geometry* newQuadGeometry(DeviceState& state) {
    return new QuadGeometry(state);
}

}  // namespace ripple::device
