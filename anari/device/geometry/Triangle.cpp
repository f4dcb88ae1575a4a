// Geometry subtype "triangle" (KHR_GEOMETRY_TRIANGLE): an indexed or unindexed triangle mesh.
#include "anari/device/geometry/Geometry.h"

namespace ripple::device {
namespace {

class TriangleGeometry final : public Geometry {
public:
    explicit TriangleGeometry(DeviceState& state) : Geometry(state, "triangle") {}

private:
    Shape build() override { return buildPolygonMesh(3); }
};

}  // namespace

Geometry* newTriangleGeometry(DeviceState& state) {
    return new TriangleGeometry(state);
}

}  // namespace ripple::device
