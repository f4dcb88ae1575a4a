// What every ANARI app holds for one run: the library, its device and the objects made on it (released in
// reverse order), and the status callback that prints the device's messages under the program's name.
#pragma once

#include "apps/scene/AnariScene.h"

#include <anari/anari.h>

#include <glm/glm.hpp>

#include <string>
#include <utility>
#include <vector>

namespace ripple::apps {

// The device's messages: errors always, warnings unless quiet, chatter never; `program` prefixes each line.
struct StatusLog {
    const char* program = "ripple";
    bool quiet = false;
    int errors = 0;
};

// An ANARIStatusCallback whose user pointer is a StatusLog.
void printStatus(const void* user, ANARIDevice, ANARIObject, ANARIDataType, ANARIStatusSeverity severity,
                 ANARIStatusCode, const char* message);

// The library, its device and the objects of one render, released in reverse order.
struct Session {
    ANARILibrary library = nullptr;
    ANARIDevice device = nullptr;
    std::vector<ANARIObject> objects;
    Session() = default;
    Session(const Session&) = delete;
    Session& operator=(const Session&) = delete;
    ~Session() {
        for (auto it = objects.rbegin(); it != objects.rend(); ++it) anariRelease(device, *it);
        if (device) anariRelease(device, device);
        if (library) anariUnloadLibrary(library);
    }
};

// Loads libanari_library_NAME.so with `log` as its status callback and makes its "default" device. Throws
// std::runtime_error naming the library when either fails.
void openAnariDevice(const std::string& library, StatusLog& log, Session& s);

// Whether the device lists `name` (e.g. "ANARI_KHR_FRAME_ACCUMULATION") in its "extension" property.
bool deviceHasExtension(ANARIDevice device, const char* name);

// The subtypes of `type` the device lists (anariGetObjectSubtypes); empty when it lists none.
std::vector<std::string> deviceSubtypes(ANARIDevice device, ANARIDataType type);

// The world's bounds as the device computed them (its "bounds" property), or the scene source's own where
// the device does not answer.
std::pair<glm::vec3, glm::vec3> worldBounds(ANARIDevice device, const AnariWorld& scene);

}  // namespace ripple::apps
