// Geometry subtype "curve" (KHR_GEOMETRY_CURVE): round linear segments. Segment i joins vertex
// primitive.index[i] to the next vertex; without "primitive.index" the vertices form one polyline. Radii
// per vertex ("vertex.radius") or one for all ("radius", default 1). Each segment is a sphere at both ends
// joined by the cone tangent to both, so a polyline is smooth at its joints.
#include "anari/device/geometry/Geometry.h"

#include <cmath>
#include <string>

namespace ripple::device {
namespace {

class CurveGeometry final : public Geometry {
public:
    explicit CurveGeometry(DeviceState& state) : Geometry(state, "curve") {}

private:
    Shape build() override {
        std::optional<std::vector<glm::vec3>> positions = pullPositions();
        if (!positions) return {};
        const size_t vertexCount = positions->size();
        std::vector<uint64_t> starts;
        if (!pullIndices("primitive.index", 1, vertexCount, starts)) return {};
        if (starts.empty())
            for (size_t i = 0; i + 1 < vertexCount; ++i) starts.push_back(i);
        core::ConeSet curve;
        curve.round = true;
        for (size_t i = 0; i < starts.size(); ++i) {
            if (starts[i] + 1 >= vertexCount) {
                invalidate("parameter 'primitive.index' element " + std::to_string(i) + " starts a segment at vertex " +
                           std::to_string(starts[i]) + ", which has no next vertex (" + std::to_string(vertexCount) +
                           " vertices)");
                return {};
            }
            curve.indices.emplace_back(starts[i], starts[i] + 1);
        }
        curve.positions = std::move(*positions);

        const std::vector<glm::vec4> radii = pullVectors("vertex.radius", vertexCount);
        if (!radii.empty()) {
            for (const glm::vec4& r : radii) curve.radii.push_back(r.x);
        } else {
            curve.radii = {get<float>("radius", 1.0f)};
        }
        for (size_t i = 0; i < curve.radii.size(); ++i) {
            if (!(std::isfinite(curve.radii[i]) && curve.radii[i] > 0.0f)) {
                invalidate(radii.empty() ? "parameter 'radius' must be finite and positive"
                                         : "parameter 'vertex.radius' element " + std::to_string(i) +
                                               " is not finite and positive");
                return {};
            }
        }
        const size_t segments = curve.indices.size();
        curve.colors = pullVectors("primitive.color", segments);
        const std::vector<glm::vec4> vertexColors = pullVectors("vertex.color", vertexCount);
        if (curve.colors.empty() && !vertexColors.empty())
            for (const glm::uvec2& s : curve.indices) curve.colors.push_back(0.5f * (vertexColors[s.x] + vertexColors[s.y]));
        if (curve.colors.empty()) curve.colors = pullUniformColor(segments);
        curve.attributes = pullAttributes(vertexCount, segments);
        return curve;
    }
};

}  // namespace

Geometry* newCurveGeometry(DeviceState& state) {
    return new CurveGeometry(state);
}

}  // namespace ripple::device
