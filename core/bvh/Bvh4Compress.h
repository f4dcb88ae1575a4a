// 8-bit quantization of BVH4 child boxes (shaders/shared/bvh4.h Bvh4CompressedNode). Conservative by
// construction and by check: each dequantized box holds the full-precision one.
#pragma once

#include "core/bvh/Aabb.h"
#include "core/bvh/Bvh4Collapse.h"

#include <span>
#include <vector>

namespace ripple::bvh {

// Node n of the result is node n of the input, so child indices stay valid; nodes of several BVHs
// concatenated in one array (the renderer's scene) compress in one call.
std::vector<gpu::Bvh4CompressedNode> compressBvh4(std::span<const gpu::Bvh4Node> nodes);
inline std::vector<gpu::Bvh4CompressedNode> compressBvh4(const Bvh4& tree) { return compressBvh4(tree.nodes); }

// Child `slot`'s box exactly as the kernel computes it (one float rounding per bound).
Aabb dequantizedBox(const gpu::Bvh4CompressedNode& node, int slot);

}  // namespace ripple::bvh
