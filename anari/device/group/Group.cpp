// Group parameters: "surface", "volume" and "light" arrays.
#include "anari/device/group/Group.h"

namespace ripple::device {

void Group::commit() {
    forgetDependencies();
    surfaces_ = pullObjects<Surface>("surface", ANARI_SURFACE);
    lights_ = pullObjects<Light>("light", ANARI_LIGHT);
    volumes_ = pullObjects<Volume>("volume", ANARI_VOLUME);
}

}  // namespace ripple::device
