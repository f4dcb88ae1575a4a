// The status callback, device opening and bounds query the ANARI apps share (see AnariSession.h).
#include "apps/scene/AnariSession.h"

#include <cstdio>
#include <stdexcept>
#include <string>

namespace ripple::apps {

void printStatus(const void* user, ANARIDevice, ANARIObject, ANARIDataType, ANARIStatusSeverity severity,
                 ANARIStatusCode, const char* message) {
    auto* log = static_cast<StatusLog*>(const_cast<void*>(user));
    if (severity <= ANARI_SEVERITY_ERROR) {
        ++log->errors;
        std::fprintf(stderr, "[%s] ERROR: %s\n", log->program, message ? message : "(no message)");
    } else if (severity <= ANARI_SEVERITY_PERFORMANCE_WARNING && !log->quiet) {
        std::fprintf(stderr, "[%s] WARNING: %s\n", log->program, message ? message : "(no message)");
    }
}

void openAnariDevice(const std::string& library, StatusLog& log, Session& s) {
    s.library = anariLoadLibrary(library.c_str(), printStatus, &log);
    if (!s.library)
        throw std::runtime_error("cannot load the ANARI library '" + library + "' (the loader's reason is above)");
    s.device = anariNewDevice(s.library, "default");
    if (!s.device) throw std::runtime_error("the ANARI library '" + library + "' created no device");
}

std::pair<glm::vec3, glm::vec3> worldBounds(ANARIDevice device, const AnariWorld& scene) {
    float box[6];
    if (anariGetProperty(device, scene.world, "bounds", ANARI_FLOAT32_BOX3, box, sizeof box, ANARI_WAIT))
        return {glm::vec3(box[0], box[1], box[2]), glm::vec3(box[3], box[4], box[5])};
    return {scene.boundsMin, scene.boundsMax};
}

bool deviceHasExtension(ANARIDevice device, const char* name) {
    const char** extensions = nullptr;
    if (!anariGetProperty(device, device, "extension", ANARI_STRING_LIST, &extensions, sizeof extensions, ANARI_WAIT))
        return false;
    for (const char** e = extensions; e && *e; ++e)
        if (std::string(*e) == name) return true;
    return false;
}

std::vector<std::string> deviceSubtypes(ANARIDevice device, ANARIDataType type) {
    std::vector<std::string> names;
    for (const char** t = anariGetObjectSubtypes(device, type); t && *t; ++t) names.emplace_back(*t);
    return names;
}

}  // namespace ripple::apps
