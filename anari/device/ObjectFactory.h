// Creates the object behind each anariNew* call: the class of the requested subtype, or, for a subtype
// Ripple does not have, an "unknown" object of that type that reports one warning and renders nothing.
#pragma once

#include "anari/device/object/Object.h"

#include <string_view>

namespace ripple::device {

// objectType is a handle type (ANARI_GEOMETRY...); surface, group, world and frame take subtype "".
// Arrays are made by the Device itself. Returns an object with one reference, never nullptr.
Object* createObject(DeviceState& state, ANARIDataType objectType, std::string_view subtype);

}  // namespace ripple::device
