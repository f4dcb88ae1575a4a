// Group parameters: "surface" and "light" arrays; "volume" is accepted and ignored (no volumes yet).
#include "anari/device/group/Group.h"

namespace ripple::device {

void Group::commit() {
    forgetDependencies();
    surfaces_ = pullObjects<Surface>("surface", ANARI_SURFACE);
    lights_ = pullObjects<Light>("light", ANARI_LIGHT);
    if (has("volume")) {
        (void)getArray("volume");
        reportWarning("volumes are not supported yet; parameter 'volume' is ignored");
    }
}

}  // namespace ripple::device
