// Typed helpers over the ANARI C API for the apps: parameters by C++ type, arrays filled from vectors, and a
// list of handles released together once their parents hold them.
#pragma once

#include <anari/anari.h>

#include <glm/glm.hpp>

#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

namespace ripple::apps::anari {

inline void set(ANARIDevice d, ANARIObject o, const char* name, float v) { anariSetParameter(d, o, name, ANARI_FLOAT32, &v); }
inline void set(ANARIDevice d, ANARIObject o, const char* name, uint32_t v) { anariSetParameter(d, o, name, ANARI_UINT32, &v); }
inline void set(ANARIDevice d, ANARIObject o, const char* name, int32_t v) { anariSetParameter(d, o, name, ANARI_INT32, &v); }
inline void set(ANARIDevice d, ANARIObject o, const char* name, bool v) {
    const int32_t asBool = v ? 1 : 0;  // ANARI_BOOL is a 32-bit integer
    anariSetParameter(d, o, name, ANARI_BOOL, &asBool);
}
inline void set(ANARIDevice d, ANARIObject o, const char* name, const glm::vec3& v) { anariSetParameter(d, o, name, ANARI_FLOAT32_VEC3, &v); }
inline void set(ANARIDevice d, ANARIObject o, const char* name, const glm::vec4& v) { anariSetParameter(d, o, name, ANARI_FLOAT32_VEC4, &v); }
inline void set(ANARIDevice d, ANARIObject o, const char* name, const glm::uvec2& v) { anariSetParameter(d, o, name, ANARI_UINT32_VEC2, &v); }
inline void set(ANARIDevice d, ANARIObject o, const char* name, const glm::mat4& v) { anariSetParameter(d, o, name, ANARI_FLOAT32_MAT4, &v); }
inline void set(ANARIDevice d, ANARIObject o, const char* name, const char* v) { anariSetParameter(d, o, name, ANARI_STRING, v); }
inline void setObject(ANARIDevice d, ANARIObject o, const char* name, ANARIDataType type, ANARIObject v) {
    anariSetParameter(d, o, name, type, &v);
}

// The element type of a std::vector's entries, as ANARI names it.
template <typename T> constexpr ANARIDataType elementType();
template <> constexpr ANARIDataType elementType<float>() { return ANARI_FLOAT32; }
template <> constexpr ANARIDataType elementType<glm::vec2>() { return ANARI_FLOAT32_VEC2; }
template <> constexpr ANARIDataType elementType<glm::vec3>() { return ANARI_FLOAT32_VEC3; }
template <> constexpr ANARIDataType elementType<glm::vec4>() { return ANARI_FLOAT32_VEC4; }
template <> constexpr ANARIDataType elementType<glm::uvec2>() { return ANARI_UINT32_VEC2; }
template <> constexpr ANARIDataType elementType<glm::uvec3>() { return ANARI_UINT32_VEC3; }
template <> constexpr ANARIDataType elementType<uint32_t>() { return ANARI_UINT32; }
template <> constexpr ANARIDataType elementType<uint8_t>() { return ANARI_UINT8; }

// A device-owned 1D array holding a copy of `values` (of `type`, one element per entry).
template <typename T>
ANARIArray1D newArray1D(ANARIDevice d, const std::vector<T>& values, ANARIDataType type = elementType<T>()) {
    ANARIArray1D array = anariNewArray1D(d, nullptr, nullptr, nullptr, type, values.size());
    if (!array) throw std::runtime_error("the ANARI device returned no array (" + std::to_string(values.size()) + " elements)");
    void* mapped = anariMapArray(d, array);
    if (!mapped) {
        anariRelease(d, array);
        throw std::runtime_error("the ANARI device could not map a new array");
    }
    if (!values.empty()) std::memcpy(mapped, values.data(), values.size() * sizeof(T));
    anariUnmapArray(d, array);
    return array;
}

// Handles created while building a scene, released together once their parents reference them (ANARI
// objects count references, so a parent keeps what it uses alive).
class HandleList {
public:
    explicit HandleList(ANARIDevice d) : device_(d) {}
    HandleList(const HandleList&) = delete;
    HandleList& operator=(const HandleList&) = delete;
    ~HandleList() {
        for (ANARIObject o : handles_) anariRelease(device_, o);
    }
    // Keeps `o` for release; throws when the device returned no object.
    template <typename Handle>
    Handle keep(Handle o, const char* what) {
        if (!o) throw std::runtime_error(std::string("the ANARI device returned no ") + what);
        handles_.push_back(o);
        return o;
    }

private:
    ANARIDevice device_;
    std::vector<ANARIObject> handles_;
};

}  // namespace ripple::apps::anari
