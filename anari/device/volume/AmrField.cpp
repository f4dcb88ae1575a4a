// Spatial field "amr": the blocks read, then checked and packed by core (AmrField.h).
#include "anari/device/volume/AmrField.h"

#include "anari/device/array/Array.h"
#include "anari/device/object/ArrayChecks.h"
#include "anari/device/scene/ArrayConversion.h"

#include <stdexcept>
#include <string>

namespace ripple::device {

namespace {

// An element of an INT32_BOX3 array: the lower corner, then the upper.
struct Box3i {
    glm::ivec3 lower, upper;
};
static_assert(sizeof(Box3i) == 24);

}  // namespace

void AmrField::commit() {
    forgetDependencies();
    grid_.reset();
    core::AmrHierarchy hierarchy;
    hierarchy.origin = get<glm::vec3>("origin", glm::vec3(0.0f));
    hierarchy.spacing = get<glm::vec3>("spacing", glm::vec3(1.0f));
    const auto required = [&](const char* name, const char* what) -> Array* {
        Array* array = getArray(name);
        if (!array) {
            invalidate(has(name) ? std::string("parameter '") + name + "' must be an ARRAY1D of " + what
                                 : std::string("missing required parameter '") + name + "' (" + what + ")");
            return nullptr;
        }
        useArray(array);
        return array;
    };
    Array* cellWidth = required("cellWidth", "FLOAT32, one per level");
    Array* bounds = required("block.bounds", "INT32_BOX3");
    Array* level = required("block.level", "INT32");
    Array* data = required("block.data", "ARRAY3D");
    if (!cellWidth || !bounds || !level || !data) return;

    if (cellWidth->elementType() != ANARI_FLOAT32) {
        invalidate(elementTypeProblem("cellWidth", cellWidth->elementType(), "FLOAT32"));
        return;
    }
    const std::span<const float> widths = cellWidth->as<float>();
    hierarchy.cellWidth.assign(widths.begin(), widths.end());
    if (bounds->elementType() != ANARI_INT32_BOX3) {
        invalidate(elementTypeProblem("block.bounds", bounds->elementType(), "INT32_BOX3"));
        return;
    }
    if (level->elementType() != ANARI_INT32 && level->elementType() != ANARI_UINT32) {
        invalidate(elementTypeProblem("block.level", level->elementType(), "INT32 or UINT32"));
        return;
    }
    if (data->elementType() != ANARI_ARRAY3D) {
        invalidate(elementTypeProblem("block.data", data->elementType(), "ARRAY3D"));
        return;
    }
    const size_t blocks = data->size();
    if (bounds->size() != blocks || level->size() != blocks) {
        invalidate("'block.bounds', 'block.level' and 'block.data' have " + std::to_string(bounds->size()) + ", " +
                   std::to_string(level->size()) + " and " + std::to_string(blocks) + " elements; they must agree");
        return;
    }
    const std::span<const Box3i> boxes = bounds->as<Box3i>();
    const std::span<const int32_t> levels = level->as<int32_t>();
    hierarchy.blocks.resize(blocks);
    for (size_t b = 0; b < blocks; ++b) {
        core::AmrBlock& block = hierarchy.blocks[b];
        if (levels[b] < 0) {
            invalidate("'block.level' element " + std::to_string(b) + " is negative");
            return;
        }
        block.level = uint32_t(levels[b]);
        block.lower = boxes[b].lower;
        block.upper = boxes[b].upper;
        auto* values = dynamic_cast<Array*>(data->objects()[b]);
        if (!values) {
            invalidate("'block.data' element " + std::to_string(b) + " is not an array");
            return;
        }
        useArray(values);
        const glm::i64vec3 extent = glm::i64vec3(block.upper) - glm::i64vec3(block.lower) + int64_t(1);
        if (int64_t(values->dim(0)) != extent.x || int64_t(values->dim(1)) != extent.y || int64_t(values->dim(2)) != extent.z) {
            invalidate("'block.data' element " + std::to_string(b) + " is " + std::to_string(values->dim(0)) + "x" +
                       std::to_string(values->dim(1)) + "x" + std::to_string(values->dim(2)) + " but its bounds hold " +
                       std::to_string(extent.x) + "x" + std::to_string(extent.y) + "x" + std::to_string(extent.z) + " cells");
            return;
        }
        std::optional<std::vector<float>> converted = readScalars(*values);
        if (!converted) {
            invalidate(elementTypeProblem(("block.data element " + std::to_string(b)).c_str(), values->elementType(),
                                          "UFIXED8, FIXED16, UFIXED16, FLOAT32 or FLOAT64"));
            return;
        }
        block.values = std::move(*converted);
    }
    try {
        grid_ = core::prepareAmrGrid(hierarchy);
    } catch (const std::invalid_argument& e) {
        invalidate(std::string("the AMR hierarchy cannot be rendered: ") + e.what());
    }
}

bvh::Aabb AmrField::bounds() const {
    bvh::Aabb box;
    if (!isValid() || !grid_) return box;
    box.extend(grid_->lo);
    box.extend(grid_->hi);
    return box;
}

void AmrField::describe(core::Volume& v) const {
    v.amr = grid_;
    v.voxelIdentity = {reinterpret_cast<uintptr_t>(this), lastCommitted()};
}

}  // namespace ripple::device
