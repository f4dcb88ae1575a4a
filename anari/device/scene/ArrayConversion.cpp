// Element type conversions for array parameters (see ArrayConversion.h).
#include "anari/device/scene/ArrayConversion.h"

#include "anari/anari_type_traits.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace ripple::device {
namespace {

bool isSrgb(ANARIDataType type) {
    return type >= ANARI_UFIXED8_R_SRGB && type <= ANARI_UFIXED8_RGBA_SRGB;
}

float srgbToLinear(float encoded) {
    return encoded <= 0.04045f ? encoded / 12.92f : std::pow((encoded + 0.055f) / 1.055f, 2.4f);
}

// One component of a numeric element type starting at `at`, as float (normalized for FIXED types).
float readComponent(const uint8_t* at, int scalarType) {
    auto load = [at]<class T>(T) {
        T value;
        std::memcpy(&value, at, sizeof(T));
        return value;
    };
    switch (scalarType) {
        case ANARI_INT8: return float(load(int8_t{}));
        case ANARI_UINT8: return float(load(uint8_t{}));
        case ANARI_INT16: return float(load(int16_t{}));
        case ANARI_UINT16: return float(load(uint16_t{}));
        case ANARI_INT32: return float(load(int32_t{}));
        case ANARI_UINT32: return float(load(uint32_t{}));
        case ANARI_INT64: return float(load(int64_t{}));
        case ANARI_UINT64: return float(load(uint64_t{}));
        case ANARI_FIXED8: return std::max(float(load(int8_t{})) / 127.0f, -1.0f);
        case ANARI_UFIXED8: return float(load(uint8_t{})) / 255.0f;
        case ANARI_FIXED16: return std::max(float(load(int16_t{})) / 32767.0f, -1.0f);
        case ANARI_UFIXED16: return float(load(uint16_t{})) / 65535.0f;
        case ANARI_FIXED32: return std::max(float(double(load(int32_t{})) / 2147483647.0), -1.0f);
        case ANARI_UFIXED32: return float(double(load(uint32_t{})) / 4294967295.0);
        case ANARI_FLOAT32: return load(float{});
        case ANARI_FLOAT64: return float(load(double{}));
        default: return std::numeric_limits<float>::quiet_NaN();
    }
}

// The scalar type of a numeric element type (ANARI_FLOAT32_VEC3 -> ANARI_FLOAT32); FLOAT16 and the
// 64-bit fixed types are not read (rare, and they would need their own decoding).
int scalarTypeOf(ANARIDataType type) {
    if (type < ANARI_INT8 || type > ANARI_FLOAT64_VEC4) return ANARI_UNKNOWN;
    const int scalar = ANARI_INT8 + (type - ANARI_INT8) / 4 * 4;
    if (scalar == ANARI_FLOAT16 || scalar == ANARI_FIXED64 || scalar == ANARI_UFIXED64) return ANARI_UNKNOWN;
    return scalar;
}

// The array's elements as floats times `scale`, at least `lowest`.
template <class T>
std::vector<float> scaled(const Array& array, double scale, double lowest) {
    const std::span<const T> in = array.as<T>();
    std::vector<float> out(in.size());
    for (size_t i = 0; i < in.size(); ++i) out[i] = float(std::max(double(in[i]) * scale, lowest));
    return out;
}

}  // namespace

int componentCount(ANARIDataType elementType) {
    if (isSrgb(elementType)) return elementType - ANARI_UFIXED8_R_SRGB + 1;
    if (scalarTypeOf(elementType) == ANARI_UNKNOWN) return 0;
    return (elementType - ANARI_INT8) % 4 + 1;
}

std::optional<std::vector<glm::vec4>> readFloatVectors(const Array& array, glm::vec4 fill) {
    const ANARIDataType type = array.elementType();
    const int components = componentCount(type);
    if (components == 0) return std::nullopt;
    const int scalar = isSrgb(type) ? int(ANARI_UFIXED8) : scalarTypeOf(type);
    const size_t componentBytes = isSrgb(type) ? 1 : ripple_anari::numericComponentBytes(type);
    const auto* bytes = static_cast<const uint8_t*>(array.data());

    std::vector<glm::vec4> values(array.size(), fill);
    for (size_t i = 0; i < values.size(); ++i) {
        const uint8_t* element = bytes + i * components * componentBytes;
        for (int c = 0; c < components; ++c) values[i][c] = readComponent(element + c * componentBytes, scalar);
        // sRGB encodes colour only: the alpha of RA/RGBA stays linear.
        if (isSrgb(type)) {
            const int colorComponents = (components == 2 || components == 4) ? components - 1 : components;
            for (int c = 0; c < colorComponents; ++c) values[i][c] = srgbToLinear(values[i][c]);
        }
    }
    return values;
}

std::optional<std::vector<uint64_t>> readIndices(const Array& array, int components) {
    const ANARIDataType type = array.elementType();
    const int scalar = scalarTypeOf(type);
    if (scalar == ANARI_UNKNOWN || scalar > ANARI_UINT64 || componentCount(type) != components) return std::nullopt;
    const bool isSigned = (scalar - ANARI_INT8) % 8 == 0;
    const size_t bytesPerValue = ripple_anari::numericComponentBytes(type);
    const auto* bytes = static_cast<const uint8_t*>(array.data());

    std::vector<uint64_t> indices(array.size() * components);
    for (size_t i = 0; i < indices.size(); ++i) {
        uint64_t raw = 0;
        std::memcpy(&raw, bytes + i * bytesPerValue, bytesPerValue);  // little endian: low bytes first
        if (isSigned) {
            const uint64_t signBit = uint64_t(1) << (8 * bytesPerValue - 1);
            if (raw & signBit) raw = std::numeric_limits<uint64_t>::max();
        }
        indices[i] = raw;
    }
    return indices;
}

std::optional<std::vector<float>> readScalars(const Array& array) {
    const double none = -std::numeric_limits<double>::max();
    switch (array.elementType()) {
        case ANARI_UFIXED8: return scaled<uint8_t>(array, 1.0 / 255.0, none);
        case ANARI_UFIXED16: return scaled<uint16_t>(array, 1.0 / 65535.0, none);
        case ANARI_FIXED16: return scaled<int16_t>(array, 1.0 / 32767.0, -1.0);
        case ANARI_FLOAT32: return scaled<float>(array, 1.0, none);
        case ANARI_FLOAT64: return scaled<double>(array, 1.0, none);
        default: return std::nullopt;
    }
}

}  // namespace ripple::device
