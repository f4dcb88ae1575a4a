// Surface parameters: "geometry" and "material" (both required), "visible", "id".
#include "anari/device/surface/Surface.h"

namespace ripple::device {

void Surface::commit() {
    forgetDependencies();
    geometry_ = dynamic_cast<Geometry*>(getObject("geometry", ANARI_GEOMETRY));
    material_ = dynamic_cast<Material*>(getObject("material", ANARI_MATERIAL));
    visible_ = get<bool>("visible", true);
    id_ = getOptional<uint32_t>("id");
    if (!geometry_)
        invalidate(has("geometry") ? "parameter 'geometry' is not a usable geometry"
                                   : "missing required parameter 'geometry'");
    if (!material_)
        invalidate(has("material") ? "parameter 'material' is not a usable material"
                                   : "missing required parameter 'material'");
    useChild(geometry_);
    useChild(material_);
}

bool Surface::renderable() const {
    return isValid() && visible_ && geometry_ && geometry_->isValid() && material_ && material_->isValid();
}

}  // namespace ripple::device
