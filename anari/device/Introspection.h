// What the Ripple device tells applications about itself: its subtypes, their parameters (type, whether
// required, default, description) and the ANARI_KHR_* extensions it implements. Ripple's own tables;
// every returned pointer refers to static storage and stays valid.
#pragma once

#include "anari/anari.h"

namespace ripple::device {

// {"default", nullptr}
const char** deviceSubtypes();
// The ANARI_KHR_* extensions that are implemented and tested, nullptr-terminated.
const char** deviceExtensions();
// Subtypes of an object type, nullptr-terminated; nullptr for types without subtypes (surface, group,
// world, frame) or that Ripple does not have.
const char** objectSubtypes(ANARIDataType objectType);
// "description" (ANARI_STRING: const char*) and "parameter" (ANARI_PARAMETER_LIST: ANARIParameter array
// ending with {nullptr, ANARI_UNKNOWN}; a parameter accepting several types appears once per type).
// subtype may be nullptr or "" for types without subtypes. nullptr when unknown.
const void* objectInfo(ANARIDataType objectType, const char* subtype, const char* infoName, ANARIDataType infoType);
// "description" (STRING), "required" (BOOL: const int32_t*), "default" (of parameterType; for STRING the
// const char* itself), "value" (STRING_LIST of accepted strings). nullptr when unknown or not defined.
const void* parameterInfo(ANARIDataType objectType, const char* subtype, const char* parameterName,
                          ANARIDataType parameterType, const char* infoName, ANARIDataType infoType);

}  // namespace ripple::device
