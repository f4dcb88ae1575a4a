// Geometry subtype "cylinder" (KHR_GEOMETRY_CYLINDER): cylinders between vertex pairs (consecutive, or
// from "primitive.index"), closed at the ends "caps" names (none, first, second, both).
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
        std::optional<std::vector<glm::vec3>> positions = pullPositions();
        if (!positions) return {};
        std::vector<uint64_t> index;
        if (!pullIndices("primitive.index", 2, positions->size(), index)) return {};
        if (index.empty() && positions->size() % 2 != 0)
            reportWarning("'vertex.position' has an odd number of vertices; the last one is ignored");
        const size_t cylinderCount = index.empty() ? positions->size() / 2 : index.size() / 2;

        core::CylinderSet cylinders;
        cylinders.positions = std::move(*positions);
        for (size_t i = 0; i < index.size(); i += 2) cylinders.indices.emplace_back(index[i], index[i + 1]);
        auto endpoint = [&](size_t cylinder, int end) {
            return index.empty() ? 2 * cylinder + end : size_t(index[2 * cylinder + end]);
        };

        const std::vector<glm::vec4> radii = pullVectors("primitive.radius", cylinderCount);
        if (!radii.empty()) {
            for (const glm::vec4& r : radii) cylinders.radii.push_back(r.x);
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
        if (has("vertex.cap")) {
            (void)getArray("vertex.cap");
            reportWarning("per-vertex caps ('vertex.cap') are not supported; 'caps' applies to all cylinders");
        }

        // Core colours whole cylinders: per-vertex colours are averaged over the two ends.
        cylinders.colors = pullVectors("primitive.color", cylinderCount);
        const std::vector<glm::vec4> vertexColors = pullVectors("vertex.color", cylinders.positions.size());
        if (cylinders.colors.empty() && !vertexColors.empty()) {
            for (size_t i = 0; i < cylinderCount; ++i)
                cylinders.colors.push_back(0.5f * (vertexColors[endpoint(i, 0)] + vertexColors[endpoint(i, 1)]));
        }
        if (cylinders.colors.empty()) cylinders.colors = pullUniformColor(cylinderCount);
        if (index.empty()) cylinders.positions.resize(cylinderCount * 2);
        return cylinders;
    }
};

}  // namespace

Geometry* newCylinderGeometry(DeviceState& state) {
    return new CylinderGeometry(state);
}

}  // namespace ripple::device
