// Reading ANARI arrays of the element types applications actually pass (float, normalized fixed point,
// sRGB bytes, signed and unsigned integers) as the float vectors and indices core::SceneDescription holds.
#pragma once

#include "anari/device/array/Array.h"

#include <glm/glm.hpp>

#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

namespace ripple::device {

// Components per element (1..4) of a numeric or sRGB element type; 0 for anything else.
int componentCount(ANARIDataType elementType);

// Elements as linear float RGBA-style vectors: missing components come from `fill`; UFIXED types map to
// [0,1], FIXED to [-1,1], sRGB bytes are decoded to linear. nullopt when the type is not numeric.
std::optional<std::vector<glm::vec4>> readFloatVectors(const Array& array, glm::vec4 fill = {0, 0, 0, 1});

// The samples of a spatial field: UFIXED8 and UFIXED16 normalised to [0, 1], FIXED16 to [-1, 1], FLOAT32
// and FLOAT64 as they are; nullopt for any other element type.
std::optional<std::vector<float>> readScalars(const Array& array);

// Elements as unsigned integers (indices), flattened: an array of UINT32_VEC3 of n elements gives 3n
// values. Accepts 8- to 64-bit signed and unsigned integers with exactly `components` components; a
// negative value becomes UINT64_MAX so the caller's range check rejects it. nullopt for other types.
std::optional<std::vector<uint64_t>> readIndices(const Array& array, int components);

// True when every component is finite (neither NaN nor infinite).
template <glm::length_t N>
bool allFinite(const glm::vec<N, float>& v) {
    for (glm::length_t i = 0; i < N; ++i)
        if (!std::isfinite(v[i])) return false;
    return true;
}

}  // namespace ripple::device
