// Geometry subtype "cone" (KHR_GEOMETRY_CONE): cone frusta between vertex pairs (consecutive, or from
// "primitive.index"), with a radius per vertex ("vertex.radius", required) and flat caps at the ends that
// "caps" names. Per-vertex caps ("vertex.cap") are not supported: "caps" applies to every cone.
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
        std::optional<std::vector<glm::vec3>> positions = pullPositions();
        if (!positions) return {};
        std::vector<uint64_t> index;
        if (!pullIndices("primitive.index", 2, positions->size(), index)) return {};
        if (index.empty() && positions->size() % 2 != 0)
            reportWarning("'vertex.position' has an odd number of vertices; the last one is ignored");
        const size_t coneCount = index.empty() ? positions->size() / 2 : index.size() / 2;

        core::ConeSet cones;
        cones.positions = std::move(*positions);
        for (size_t i = 0; i < index.size(); i += 2) cones.indices.emplace_back(index[i], index[i + 1]);
        const std::vector<glm::vec4> radii = pullVectors("vertex.radius", cones.positions.size());
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
        if (has("vertex.cap")) {
            (void)getArray("vertex.cap");
            reportWarning("per-vertex caps ('vertex.cap') are not supported; 'caps' applies to all cones");
        }
        cones.colors = pullVectors("primitive.color", coneCount);
        const std::vector<glm::vec4> vertexColors = pullVectors("vertex.color", cones.positions.size());
        if (cones.colors.empty() && !vertexColors.empty()) {
            for (size_t i = 0; i < coneCount; ++i) {
                const size_t a = index.empty() ? 2 * i : index[2 * i], b = index.empty() ? 2 * i + 1 : index[2 * i + 1];
                cones.colors.push_back(0.5f * (vertexColors[a] + vertexColors[b]));
            }
        }
        if (cones.colors.empty()) cones.colors = pullUniformColor(coneCount);
        if (index.empty()) cones.positions.resize(coneCount * 2);
        if (index.empty()) cones.radii.resize(coneCount * 2);
        return cones;
    }
};

}  // namespace

Geometry* newConeGeometry(DeviceState& state) {
    return new ConeGeometry(state);
}

}  // namespace ripple::device
