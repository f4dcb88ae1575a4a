// Shared between GLSL and C++: the few definitions both sides need to agree on the layout of GPU data.
// Every struct that lives in a GPU buffer is built from vec4 and 32-bit scalars only (no bare vec3), and
// the C++ side static_asserts its size and offsets in core/scene/GpuLayout.cpp.
#ifndef RIPPLE_SHARED_COMMON_H
#define RIPPLE_SHARED_COMMON_H

#ifdef __cplusplus
#include <cstdint>
#include <glm/vec4.hpp>
#define RIPPLE_GPU_BEGIN namespace ripple::gpu { using vec4 = glm::vec4; using uint = std::uint32_t; using std::uint64_t;
#define RIPPLE_GPU_END }
#define RIPPLE_CONST inline constexpr
#else
#define RIPPLE_GPU_BEGIN
#define RIPPLE_GPU_END
#define RIPPLE_CONST const
#endif

#endif
