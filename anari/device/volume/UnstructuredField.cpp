// Spatial field "unstructured": the arrays read, then checked and packed by core (UnstructuredField.h).
#include "anari/device/volume/UnstructuredField.h"

#include "anari/device/object/ArrayChecks.h"
#include "anari/device/scene/ArrayConversion.h"

#include <stdexcept>
#include <string>

namespace ripple::device {

namespace {

// An ARRAY1D of integers as 32-bit indices; nullopt (with `problem` set) when it is not one or a value
// does not fit.
std::optional<std::vector<uint32_t>> readIndexArray(const Array& array, const char* name, std::string& problem) {
    const std::optional<std::vector<uint64_t>> values = readIndices(array, 1);
    if (!values) {
        problem = elementTypeProblem(name, array.elementType(), "UINT32");
        return std::nullopt;
    }
    std::vector<uint32_t> out(values->size());
    for (size_t i = 0; i < out.size(); ++i) {
        if ((*values)[i] > UINT32_MAX) {
            problem = std::string("parameter '") + name + "' element " + std::to_string(i) + " is negative or past 2^32";
            return std::nullopt;
        }
        out[i] = uint32_t((*values)[i]);
    }
    return out;
}

}  // namespace

void UnstructuredField::commit() {
    forgetDependencies();
    grid_.reset();
    core::UnstructuredCells cells;

    Array* positions = getArray("vertex.position");
    if (!positions) {
        invalidate(has("vertex.position") ? "parameter 'vertex.position' must be an ARRAY1D of FLOAT32_VEC3"
                                          : "missing required parameter 'vertex.position'");
        return;
    }
    useArray(positions);
    if (positions->elementType() != ANARI_FLOAT32_VEC3) {
        invalidate(elementTypeProblem("vertex.position", positions->elementType(), "FLOAT32_VEC3"));
        return;
    }
    const std::span<const glm::vec3> p = positions->as<glm::vec3>();
    cells.positions.assign(p.begin(), p.end());

    Array* vertexData = getArray("vertex.data");
    Array* cellData = getArray("cell.data");
    for (const auto& [name, array] : {std::pair{"vertex.data", vertexData}, std::pair{"cell.data", cellData}})
        if (has(name) && !array) {
            invalidate(std::string("parameter '") + name + "' must be an ARRAY1D");
            return;
        }
    if (!vertexData && !cellData) {
        invalidate("missing parameter 'vertex.data' or 'cell.data' (the field's values)");
        return;
    }
    if (vertexData && cellData) reportWarning("both 'vertex.data' and 'cell.data' are given; using 'vertex.data'");
    Array* data = vertexData ? vertexData : cellData;
    const char* dataName = vertexData ? "vertex.data" : "cell.data";
    useArray(data);
    std::optional<std::vector<float>> values = readScalars(*data);
    if (!values) {
        invalidate(elementTypeProblem(dataName, data->elementType(), "UFIXED8, FIXED16, UFIXED16, FLOAT32 or FLOAT64"));
        return;
    }
    cells.values = std::move(*values);
    cells.cellCentered = !vertexData;

    std::string problem;
    for (const char* name : {"index", "cell.index"}) {
        Array* array = getArray(name);
        if (!array) {
            invalidate(has(name) ? std::string("parameter '") + name + "' must be an ARRAY1D of UINT32"
                                 : std::string("missing required parameter '") + name + "'");
            return;
        }
        useArray(array);
        std::optional<std::vector<uint32_t>> indices = readIndexArray(*array, name, problem);
        if (!indices) {
            invalidate(problem);
            return;
        }
        (std::string(name) == "index" ? cells.index : cells.cellIndex) = std::move(*indices);
    }
    Array* types = getArray("cell.type");
    if (!types || types->elementType() != ANARI_UINT8) {
        invalidate(!has("cell.type") ? "missing required parameter 'cell.type'"
                   : types           ? elementTypeProblem("cell.type", types->elementType(), "UINT8")
                                     : "parameter 'cell.type' must be an ARRAY1D of UINT8");
        return;
    }
    useArray(types);
    const std::span<const uint8_t> t = types->as<uint8_t>();
    cells.cellType.assign(t.begin(), t.end());

    try {
        grid_ = core::prepareUnstructuredGrid(cells);
    } catch (const std::invalid_argument& e) {
        invalidate(std::string("the mesh cannot be rendered: ") + e.what());
        return;
    }
    for (const std::string& warning : grid_->warnings) reportWarning(warning);
}

bvh::Aabb UnstructuredField::bounds() const {
    bvh::Aabb box;
    if (!isValid() || !grid_) return box;
    box.extend(grid_->lo);
    box.extend(grid_->hi);
    return box;
}

void UnstructuredField::describe(core::Volume& v) const {
    v.unstructured = grid_;
    v.voxelIdentity = {reinterpret_cast<uintptr_t>(this), lastCommitted()};
}

}  // namespace ripple::device
