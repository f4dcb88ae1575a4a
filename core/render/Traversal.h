// Which ray traversal back-end traces: Ripple's own BVH4 kernels (software, any Vulkan 1.2 device) or
// the device's ray queries over Vulkan acceleration structures (VK_KHR_ray_query). Scenes and trace
// kernels resolve the choice the same way, so a Scene built for a tracer has what that tracer reads.
#pragma once

#include "core/vk/Context.h"

#include <optional>
#include <string_view>

namespace ripple::core {

enum class Traversal {
    Auto,      // RIPPLE_TRAVERSAL when set, else RayQuery on a GPU that supports it, else Software
    Software,  // shaders/traverse.glsl
    RayQuery,  // shaders/traverse_rq.glsl; needs Context::supportsRayQuery()
};

// "auto", "software", "rayQuery": the ANARI parameter `traversal`, RIPPLE_TRAVERSAL and --traversal.
const char* traversalName(Traversal traversal);
std::optional<Traversal> parseTraversal(std::string_view name);
inline constexpr const char* kTraversalNames = "auto, software, rayQuery";

// Software or RayQuery, never Auto. Throws std::runtime_error when RayQuery is asked for (directly or by
// RIPPLE_TRAVERSAL) on a device without it, naming what the device lacks, and when RIPPLE_TRAVERSAL holds
// an unknown value. Auto on a device without ray queries, or on a CPU device, is Software: lavapipe's ray
// queries are a software traversal of their own that traces at about half the rate of Ripple's BVH4
// kernels (docs/traversal.md).
Traversal resolveTraversal(const vk::Context& context, Traversal requested);

}  // namespace ripple::core
