// Geometry subtype "sphere" (KHR_GEOMETRY_SPHERE): one sphere per vertex, or per entry of
// "primitive.index"; radii per vertex ("vertex.radius") or one for all ("radius", default 1).
#include "anari/device/geometry/Geometry.h"

#include <cmath>
#include <string>

namespace ripple::device {
namespace {

class SphereGeometry final : public Geometry {
public:
    explicit SphereGeometry(DeviceState& state) : Geometry(state, "sphere") {}

private:
    Shape build() override {
        std::optional<std::vector<glm::vec3>> positions = pullPositions();
        if (!positions) return {};
        std::vector<uint64_t> index;
        if (!pullIndices("primitive.index", 1, positions->size(), index)) return {};
        // Core has no sphere index: the indexed spheres are gathered into a plain list.
        const size_t sphereCount = index.empty() ? positions->size() : index.size();
        auto vertexOf = [&](size_t sphere) { return index.empty() ? sphere : size_t(index[sphere]); };

        core::SphereSet spheres;
        spheres.centers.resize(sphereCount);
        for (size_t i = 0; i < sphereCount; ++i) spheres.centers[i] = (*positions)[vertexOf(i)];

        const std::vector<glm::vec4> vertexRadii = pullVectors("vertex.radius", positions->size());
        if (!vertexRadii.empty()) {
            spheres.radii.resize(sphereCount);
            for (size_t i = 0; i < sphereCount; ++i) spheres.radii[i] = vertexRadii[vertexOf(i)].x;
        } else {
            spheres.radii = {get<float>("radius", 1.0f)};
        }
        for (size_t i = 0; i < spheres.radii.size(); ++i) {
            if (!(std::isfinite(spheres.radii[i]) && spheres.radii[i] > 0.0f)) {
                invalidate(vertexRadii.empty() ? "parameter 'radius' must be finite and positive"
                                               : "parameter 'vertex.radius' element " + std::to_string(vertexOf(i)) +
                                                     " is not finite and positive");
                return {};
            }
        }

        spheres.colors = pullVectors("primitive.color", sphereCount);
        const std::vector<glm::vec4> vertexColors = pullVectors("vertex.color", positions->size());
        if (spheres.colors.empty() && !vertexColors.empty()) {
            for (size_t i = 0; i < sphereCount; ++i) spheres.colors.push_back(vertexColors[vertexOf(i)]);
        }
        if (spheres.colors.empty()) spheres.colors = pullUniformColor(sphereCount);
        // Core stores per-vertex attributes per sphere (a sphere's vertex is its centre).
        spheres.attributes = pullAttributes(positions->size(), sphereCount);
        for (core::GeometryAttribute& attribute : spheres.attributes) {
            if (attribute.rate != core::GeometryAttribute::Rate::Vertex || attribute.values.empty()) continue;
            std::vector<glm::vec4> perSphere(sphereCount);
            for (size_t i = 0; i < sphereCount; ++i) perSphere[i] = attribute.values[vertexOf(i)];
            attribute.values = std::move(perSphere);
        }
        return spheres;
    }
};

}  // namespace

Geometry* newSphereGeometry(DeviceState& state) {
    return new SphereGeometry(state);
}

}  // namespace ripple::device
