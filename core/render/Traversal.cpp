// Parsing and resolution of the traversal back-end choice.
#include "core/render/Traversal.h"

#include <cstdlib>
#include <stdexcept>
#include <string>

namespace ripple::core {

const char* traversalName(Traversal traversal) {
    switch (traversal) {
    case Traversal::Auto: return "auto";
    case Traversal::Software: return "software";
    case Traversal::RayQuery: return "rayQuery";
    }
    return "unknown";
}

std::optional<Traversal> parseTraversal(std::string_view name) {
    for (Traversal t : {Traversal::Auto, Traversal::Software, Traversal::RayQuery})
        if (name == traversalName(t)) return t;
    return std::nullopt;
}

Traversal resolveTraversal(const vk::Context& context, Traversal requested) {
    bool fromEnvironment = false;
    if (requested == Traversal::Auto) {
        if (const char* env = std::getenv("RIPPLE_TRAVERSAL"); env && *env) {
            const auto parsed = parseTraversal(env);
            if (!parsed)
                throw std::runtime_error(std::string("RIPPLE_TRAVERSAL=") + env + " is not a traversal; use one of " +
                                         kTraversalNames);
            requested = *parsed;
            fromEnvironment = true;
        }
    }
    if (requested == Traversal::Auto)
        return context.supportsRayQuery() && !context.isCpuDevice() ? Traversal::RayQuery : Traversal::Software;
    if (requested == Traversal::RayQuery && !context.supportsRayQuery())
        throw std::runtime_error(std::string("ray-query traversal was requested") +
                                 (fromEnvironment ? " (RIPPLE_TRAVERSAL)" : "") + " but Vulkan device " +
                                 context.deviceName() + " lacks " + context.rayQueryMissing());
    return requested;
}

}  // namespace ripple::core
