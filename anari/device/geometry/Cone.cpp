// Geometry subtype "cone" (KHR_GEOMETRY_CONE): cone frusta between vertex pairs (consecutive, or from
// "primitive.index"), with a radius per vertex ("vertex.radius", required) and flat caps at the ends that
// "caps" names, or at the vertices "vertex.cap" marks.
#include "anari/device/geometry/Geometry.h"

#include <cmath>
#include <string>

namespace ripple::device {
namespace {

class ConeGeometry final : public Geometry {
public:
    explicit ConeGeometry(DeviceState& state) : Geometry(state, "cone") {}

private:
    Shape build() override {
        std::optional<Segments> segments = pullSegments();
        if (!segments) return {};
        const size_t coneCount = segments->count;
        core::ConeSet cones;
        const std::vector<glm::vec4> radii = pullVectors("vertex.radius", segments->positions.size());
        if (radii.empty()) {
            invalidate(has("vertex.radius") ? "parameter 'vertex.radius' is unusable (reported above)"
                                            : "missing required parameter 'vertex.radius'");
            return {};
        }
        for (size_t i = 0; i < radii.size(); ++i) {
            if (!(std::isfinite(radii[i].x) && radii[i].x >= 0.0f)) {
                invalidate("parameter 'vertex.radius' element " + std::to_string(i) + " is negative or not finite");
                return {};
            }
            cones.radii.push_back(radii[i].x);
        }
        cones.caps = pullCaps();
        cones.segmentCaps = pullSegmentCaps(*segments);
        cones.colors = pullSegmentColors(*segments);
        cones.positions = std::move(segments->positions);
        cones.indices = std::move(segments->indices);
        if (cones.indices.empty()) {
            cones.positions.resize(coneCount * 2);
            cones.radii.resize(coneCount * 2);
        }
        cones.attributes = pullAttributes(cones.positions.size(), coneCount);
        return cones;
    }
};

}  // namespace

Geometry* newConeGeometry(DeviceState& state) {
    return new ConeGeometry(state);
}

}  // namespace ripple::device
