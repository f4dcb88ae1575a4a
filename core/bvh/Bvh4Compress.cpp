// Quantization of BVH4 nodes into their own frame (see Bvh4Compress.h and Bvh4CompressedNode).
#include "core/bvh/Bvh4Compress.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <stdexcept>

namespace ripple::bvh {

namespace {

// Smallest power of two whose 255 steps cover `extent`, as a biased float exponent in [1, 254].
uint32_t biasedExponent(float extent) {
    if (!(extent > 0.0f)) return 1;  // a flat axis: any scale works, the smallest normal one is exact
    if (!std::isfinite(extent)) return 254;
    int exponent = static_cast<int>(std::ceil(std::log2(double(extent) / 255.0)));
    while (std::ldexp(255.0, exponent) < double(extent)) ++exponent;  // log2 may round down
    return static_cast<uint32_t>(std::clamp(exponent + 127, 1, 254));
}

float scaleOf(uint32_t biased) { return std::bit_cast<float>(biased << 23); }

// The kernel's dequantization: q * scale is exact (8-bit times a power of two), the sum rounds once.
float dequantize(float origin, uint32_t q, float scale) { return origin + float(q) * scale; }

uint32_t quantizeLo(float value, float origin, float scale) {
    auto q = static_cast<uint32_t>(std::clamp(std::floor((double(value) - origin) / scale), 0.0, 255.0));
    while (q > 0 && dequantize(origin, q, scale) > value) --q;
    return q;
}

uint32_t quantizeHi(float value, float origin, float scale) {
    auto q = static_cast<uint32_t>(std::clamp(std::ceil((double(value) - origin) / scale), 0.0, 255.0));
    while (q < 255 && dequantize(origin, q, scale) < value) ++q;
    if (dequantize(origin, q, scale) < value) throw std::logic_error("compressBvh4: box beyond its node's frame");
    return q;
}

}  // namespace

Aabb dequantizedBox(const gpu::Bvh4CompressedNode& node, int slot) {
    const uint32_t exponents = std::bit_cast<uint32_t>(node.frame.w);
    const uint32_t words[2][3] = {{node.quantX.x, node.quantX.z, node.quantZ.x},
                                  {node.quantX.y, node.quantX.w, node.quantZ.y}};
    Aabb box;
    for (int axis = 0; axis < 3; ++axis) {
        const float scale = scaleOf((exponents >> (8 * axis)) & 0xFFu);
        box.lo[axis] = dequantize(node.frame[axis], (words[0][axis] >> (8 * slot)) & 0xFFu, scale);
        box.hi[axis] = dequantize(node.frame[axis], (words[1][axis] >> (8 * slot)) & 0xFFu, scale);
    }
    return box;
}

// Each node is quantized on its own, so the nodes are spread over the cores.
std::vector<gpu::Bvh4CompressedNode> compressBvh4(std::span<const gpu::Bvh4Node> nodes) {
    std::vector<gpu::Bvh4CompressedNode> out(nodes.size());
    tbb::parallel_for(size_t(0), nodes.size(), [&](size_t n) {
        const gpu::Bvh4Node& full = nodes[n];
        Aabb boxes[4], frame;
        for (int i = 0; i < 4; ++i) {
            if (full.children[i] == gpu::BVH4_EMPTY_CHILD) continue;
            boxes[i] = Aabb{{full.minX[i], full.minY[i], full.minZ[i]}, {full.maxX[i], full.maxY[i], full.maxZ[i]}};
            frame.extend(boxes[i]);
        }
        gpu::Bvh4CompressedNode& c = out[n];
        c = {};
        c.children = full.children;
        if (frame.empty()) return;
        uint32_t exponents = 0;
        float scale[3];
        for (int axis = 0; axis < 3; ++axis) {
            const uint32_t biased = biasedExponent(frame.hi[axis] - frame.lo[axis]);
            exponents |= biased << (8 * axis);
            scale[axis] = scaleOf(biased);
        }
        c.frame = gpu::vec4(frame.lo, std::bit_cast<float>(exponents));
        uint32_t* lo[3] = {&c.quantX.x, &c.quantX.z, &c.quantZ.x};
        uint32_t* hi[3] = {&c.quantX.y, &c.quantX.w, &c.quantZ.y};
        for (int i = 0; i < 4; ++i) {
            if (full.children[i] == gpu::BVH4_EMPTY_CHILD) continue;
            for (int axis = 0; axis < 3; ++axis) {
                *lo[axis] |= quantizeLo(boxes[i].lo[axis], frame.lo[axis], scale[axis]) << (8 * i);
                *hi[axis] |= quantizeHi(boxes[i].hi[axis], frame.lo[axis], scale[axis]) << (8 * i);
            }
        }
    });
    return out;
}

}  // namespace ripple::bvh
