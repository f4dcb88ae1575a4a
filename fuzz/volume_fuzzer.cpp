// libFuzzer target: what the device checks before a kernel reads a sparse or adaptive field, on the host and
// without Vulkan: NanoVDB grid buffers (core/scene/NanoVdbGrid.h, through NanoVdbTree.h's checked walk) and AMR
// hierarchies (core/scene/AmrGrid.h). The input's first byte chooses: even, the rest is a NanoVDB grid buffer;
// odd, the rest is decoded into a hierarchy (levels, cell widths, blocks with boxes, levels and values, any of
// them wrong). Every input must be refused with std::invalid_argument, or prepared with every macrocell range
// ordered or empty; nothing else may happen.
#include "core/scene/AmrGrid.h"
#include "core/scene/NanoVdbGrid.h"

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <vector>

namespace {

// The input as a stream of bytes; past its end every read is 0.
class Input {
public:
    Input(const uint8_t* data, size_t size) : data_(data), size_(size) {}
    uint8_t byte() { return at_ < size_ ? data_[at_++] : 0; }
    int8_t small() { return int8_t(byte()); }
    float number() {
        const uint8_t kind = byte();
        if (kind == 255) {  // raw bits: NaN, infinities, denormals
            uint32_t bits = uint32_t(byte()) | uint32_t(byte()) << 8 | uint32_t(byte()) << 16 | uint32_t(byte()) << 24;
            float f;
            std::memcpy(&f, &bits, sizeof f);
            return f;
        }
        return float(kind) / 16.0f - 4.0f;
    }

private:
    const uint8_t* data_;
    size_t size_;
    size_t at_ = 0;
};

void checkRanges(const std::vector<glm::vec2>& ranges) {
    for (const glm::vec2& r : ranges)
        if (!(r.x <= r.y) && !(r.x == INFINITY && r.y == -INFINITY)) std::abort();  // neither ordered nor empty
}

void amr(Input& in) {
    ripple::core::AmrHierarchy h;
    const uint32_t levels = in.byte() % 5;
    float width = 1.0f;
    for (uint32_t l = 0; l < levels; ++l) {
        const uint8_t step = in.byte();
        width = step == 255 ? in.number() : width / float(1 + step % 4);  // mostly halving, sometimes equal or wrong
        h.cellWidth.push_back(width);
    }
    h.origin = glm::vec3(in.number(), in.number(), in.number());
    h.spacing = glm::vec3(in.number(), 0.5f, 0.5f);
    const uint32_t blocks = in.byte() % 9;
    for (uint32_t b = 0; b < blocks; ++b) {
        ripple::core::AmrBlock block;
        block.level = in.byte() % 6;
        for (int a = 0; a < 3; ++a) {
            block.lower[a] = in.small();
            block.upper[a] = block.lower[a] + in.small() % 6;  // may be below lower
        }
        if (in.byte() == 7) block.upper.x = (1 << 25);  // past the index limit
        const glm::ivec3 n = glm::max(block.upper - block.lower + 1, 0);
        const int64_t cells = int64_t(n.x) * n.y * n.z;
        const int64_t count = cells > 4096 ? 4096 : cells + (in.byte() == 3 ? 1 : 0);  // sometimes one too many
        for (int64_t i = 0; i < count; ++i) block.values.push_back(in.number());
        h.blocks.push_back(std::move(block));
    }
    try {
        const auto grid = ripple::core::prepareAmrGrid(h);
        checkRanges(grid->macrocellRanges);
    } catch (const std::invalid_argument&) {
    }
}

void nanovdb(const uint8_t* data, size_t size) {
    try {
        const auto grid = ripple::core::prepareNanoVdbGrid(std::span<const uint8_t>(data, size));
        checkRanges(grid->macrocellRanges);
    } catch (const std::invalid_argument&) {
    }
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) { return 0; }

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size == 0) return 0;
    if (data[0] % 2 == 0) {
        nanovdb(data + 1, size - 1);
    } else {
        Input in(data + 1, size - 1);
        amr(in);
    }
    return 0;
}
