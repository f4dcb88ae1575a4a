// 8-bit quantization of BVH4 child boxes (shaders/shared/bvh4.h Bvh4CompressedNode): ripple-bench's
// --nodes compressed lever. Conservative by construction and by check: each dequantized box holds the
// full-precision one.
#pragma once

#include "core/bvh/Aabb.h"
#include "core/bvh/Bvh4Collapse.h"

#include <vector>

namespace ripple::bvh {

std::vector<gpu::Bvh4CompressedNode> compressBvh4(const Bvh4& tree);

// Child `slot`'s box exactly as the kernel computes it (one float rounding per bound).
Aabb dequantizedBox(const gpu::Bvh4CompressedNode& node, int slot);

}  // namespace ripple::bvh
