// What every spatial field reads alike (see SpatialField.h).
#include "anari/device/volume/SpatialField.h"

#include <string>

namespace ripple::device {

bool SpatialField::linearFilterParameter() {
    const std::string filter = getString("filter", "linear");
    if (filter != "linear" && filter != "nearest")
        reportWarning("parameter 'filter' has unknown value '" + filter + "'; using 'linear'");
    return filter != "nearest";
}

}  // namespace ripple::device
