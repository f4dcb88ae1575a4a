// Geometry subtype "isosurface" (KHR_GEOMETRY_ISOSURFACE): the surfaces where a field ("field") equals each
// of the isovalues ("isovalue": one FLOAT32 or an ARRAY1D of them). A structuredRegular field's are
// intersected exactly with its trilinear interpolant (shaders/intersect.glsl), an unstructured field's in
// the interpolant of each of its cells (shaders/unstructured.glsl). Colour: "primitive.color" (one per
// isovalue) or the uniform "color"; attribute0..3 likewise ("primitive.attributeN" or the uniform
// "attributeN"); the primitive id a frame reports is the isovalue's index.
#include "anari/device/geometry/Geometry.h"
#include "anari/device/object/ArrayChecks.h"
#include "anari/device/scene/ArrayConversion.h"
#include "anari/device/volume/StructuredRegularField.h"
#include "anari/device/volume/UnstructuredField.h"

#include <cmath>
#include <string>

namespace ripple::device {
namespace {

class IsosurfaceGeometry final : public Geometry {
public:
    explicit IsosurfaceGeometry(DeviceState& state) : Geometry(state, "isosurface") {}

private:
    Shape build() override {
        auto* anyField = dynamic_cast<SpatialField*>(getObject("field", ANARI_SPATIAL_FIELD));
        if (!anyField) {
            invalidate(has("field") ? "parameter 'field' is not a spatial field Ripple knows"
                                    : "missing required parameter 'field' (a spatial field)");
            return {};
        }
        useChild(anyField);
        auto* field = dynamic_cast<StructuredRegularField*>(anyField);
        auto* mesh = dynamic_cast<UnstructuredField*>(anyField);
        if (!field && !mesh) {
            invalidate("parameter 'field' is a " + anyField->subtype() +
                       " field; iso-surfaces are drawn in structuredRegular and unstructured fields");
            return {};
        }
        if (!anyField->isValid() || (field && field->values().empty()) || (mesh && !mesh->grid())) {
            invalidate("parameter 'field' is not a valid spatial field");
            return {};
        }
        if (field && !field->linearFilter())
            reportWarning("the field's filter 'nearest' is ignored: iso-surfaces use the trilinear interpolant");
        if (mesh && mesh->grid()->cellCentered) {
            invalidate("parameter 'field' is an unstructured field with cell values, constant in each cell: it has "
                       "no iso-surfaces (give it vertex.data)");
            return {};
        }

        core::IsosurfaceSet set;
        if (parameterType("isovalue") == ANARI_FLOAT32) {
            set.isovalues = {get<float>("isovalue", 0.0f)};
        } else if (Array* array = getArray("isovalue")) {
            useArray(array);
            if (array->elementType() != ANARI_FLOAT32) {
                invalidate(std::string("parameter 'isovalue' must be FLOAT32 or an ARRAY1D of FLOAT32, not an array of ") +
                           ripple_anari::typeName(array->elementType()));
                return {};
            }
            const auto* values = static_cast<const float*>(array->data());
            set.isovalues.assign(values, values + array->size());
        } else {
            invalidate(has("isovalue") ? "parameter 'isovalue' must be FLOAT32 or an ARRAY1D of FLOAT32"
                                       : "missing required parameter 'isovalue'");
            return {};
        }
        if (set.isovalues.empty()) {
            invalidate("parameter 'isovalue' is an empty array");
            return {};
        }
        for (size_t i = 0; i < set.isovalues.size(); ++i) {
            if (!std::isfinite(set.isovalues[i])) {
                invalidate("parameter 'isovalue' element " + std::to_string(i) + " is not finite");
                return {};
            }
        }
        if (mesh) {
            set.mesh = mesh->grid();
        } else {
            set.dims = field->dims();
            set.values = field->values();
            set.origin = field->origin();
            set.spacing = field->spacing();
        }
        set.colors = pullVectors("primitive.color", set.isovalues.size());
        if (set.colors.empty()) set.colors = pullUniformColor(set.isovalues.size());
        set.attributes = pullAttributes(0, set.isovalues.size());
        return set;
    }
};

}  // namespace

Geometry* newIsosurfaceGeometry(DeviceState& state) {
    return new IsosurfaceGeometry(state);
}

}  // namespace ripple::device
