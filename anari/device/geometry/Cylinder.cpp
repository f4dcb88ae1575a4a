// Geometry subtype "cylinder" (KHR_GEOMETRY_CYLINDER): cylinders between vertex pairs (consecutive, or
// from "primitive.index"), closed at the ends "caps" names (none, first, second, both) or at the vertices
// "vertex.cap" marks. "radius" is the radius of all when "primitive.radius" is unset.
#include "anari/device/geometry/Geometry.h"

#include <cmath>
#include <string>

namespace ripple::device {
namespace {

class CylinderGeometry final : public Geometry {
public:
    explicit CylinderGeometry(DeviceState& state) : Geometry(state, "cylinder") {}

private:
    Shape build() override {
        std::optional<Segments> segments = pullSegments();
        if (!segments) return {};
        const size_t cylinderCount = segments->count;
        core::CylinderSet cylinders;

        const std::vector<glm::vec4> radii = pullVectors("primitive.radius", cylinderCount);
        if (!radii.empty()) {
            for (const glm::vec4& r : radii) cylinders.radii.push_back(r.x);
            (void)findParameter("radius");  // the fallback, legitimately set beside it: not an unused parameter
        } else {
            cylinders.radii = {get<float>("radius", 1.0f)};
        }
        for (size_t i = 0; i < cylinders.radii.size(); ++i) {
            if (!(std::isfinite(cylinders.radii[i]) && cylinders.radii[i] > 0.0f)) {
                invalidate(radii.empty() ? "parameter 'radius' must be finite and positive"
                                         : "parameter 'primitive.radius' element " + std::to_string(i) +
                                               " is not finite and positive");
                return {};
            }
        }

        cylinders.caps = pullCaps();
        cylinders.segmentCaps = pullSegmentCaps(*segments);
        cylinders.colors = pullSegmentColors(*segments);
        cylinders.positions = std::move(segments->positions);
        cylinders.indices = std::move(segments->indices);
        if (cylinders.indices.empty()) cylinders.positions.resize(cylinderCount * 2);
        cylinders.attributes = pullAttributes(cylinders.positions.size(), cylinderCount);
        return cylinders;
    }
};

}  // namespace

Geometry* newCylinderGeometry(DeviceState& state) {
    return new CylinderGeometry(state);
}

}  // namespace ripple::device
