// Base of every ANARI object of the Ripple device: reference count, the parameters an application set,
// typed access to them with defaults for commit(), and status messages that name the object.
#pragma once

#include "anari/anari.h"
#include "anari/anari_type_traits.hpp"

#include <glm/glm.hpp>

#include <cstdint>
#include <cstring>
#include <type_traits>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace ripple::device {

class DeviceState;
class Array;

// One parameter as the application set it: its type and a copy of its value. Object handles are
// retained while they are held here; strings are copied.
struct Parameter {
    ANARIDataType type = ANARI_UNKNOWN;
    std::vector<uint8_t> bytes;          // the value for plain data types (sizeOf(type) bytes)
    std::string string;                  // ANARI_STRING
    class Object* object = nullptr;      // object types (retained)
    bool readSinceSet = false;           // pulled by commit(); set-but-never-read ones are warned about once
    bool warnedUnused = false;
};

class Object {
public:
    Object(DeviceState& state, ANARIDataType type, std::string subtype);
    virtual ~Object();
    Object(const Object&) = delete;
    Object& operator=(const Object&) = delete;

    ANARIDataType type() const { return type_; }
    const std::string& subtype() const { return subtype_; }
    DeviceState& state() const { return state_; }
    // "geometry 'sphere' #12" : how messages name this object.
    std::string label() const;

    // The handle the application holds (see HandleTable.h); stable for the object's life.
    ANARIObject handle() const { return handle_; }

    // Every reference, the application's and internal ones (parameters, arrays, committed state), is in one
    // count; the object deletes itself at zero. The application's own references are also counted apart:
    // retainPublic/releasePublic are anariRetain/anariRelease. releasePublic is false (and does nothing)
    // when the application holds no reference any more: a release too many.
    void retain();
    void release();
    void retainPublic();
    bool releasePublic();
    uint32_t referenceCount() const { return references_; }
    uint32_t publicReferenceCount() const { return publicReferences_; }

    // The API calls, forwarded by the Device.
    void setParameter(std::string_view name, ANARIDataType type, const void* mem);
    void unsetParameter(std::string_view name);
    void unsetAllParameters();
    // Runs commit() with exception safety (a throw becomes an ERROR message and isValid() false), warns
    // once about parameters that were set but never read, and stamps lastCommitted().
    void commitParameters();

    // Subtype hooks. commit() pulls parameters with defaults (get/getObject/getArray below).
    virtual void commit() {}
    // Answers anariGetProperty for this object; false when it has no such property (of that type).
    virtual bool getProperty(std::string_view name, ANARIDataType type, void* mem, uint64_t size, bool wait);
    // False for objects that cannot render (unknown subtype, a required parameter missing, bad data):
    // they were reported at commit and are skipped by the scene, never rendered half-valid.
    virtual bool isValid() const { return valid_; }

    // Monotonic stamps from DeviceState::nextStamp(): when the object's committed state last changed.
    // Arrays stamp on unmap as well. Used to rebuild only what changed.
    uint64_t lastCommitted() const { return lastCommitted_; }

    // Messages through the application's status callback, naming this object.
    void reportError(const std::string& message) const;
    void reportWarning(const std::string& message) const;

    // Lets go of every object this one holds (parameters, and what subclasses keep); the device calls it on
    // every live object when it is released, so that reference cycles (an object set as its own parameter,
    // A -> B -> A) cannot outlive it.
    virtual void dropReferences() { unsetAllParameters(); }

protected:
    // Called when the application's last reference goes while internal ones remain.
    virtual void onLastPublicRelease() {}

    // Typed parameter access for commit(). A parameter set with a different type than asked for is
    // reported once (naming object, parameter, expected and given types) and the default is used.
    bool has(std::string_view name) const;
    ANARIDataType parameterType(std::string_view name) const;  // ANARI_UNKNOWN when not set
    template <class T> T get(std::string_view name, const T& fallback);
    template <class T> std::optional<T> getOptional(std::string_view name);
    std::string getString(std::string_view name, const std::string& fallback);
    // An object parameter of the given handle type (ANARI_GEOMETRY...), or nullptr when unset or of the
    // wrong type (reported). Array parameters accept ANARI_ARRAY and ANARI_ARRAY1D/2D/3D alike.
    Object* getObject(std::string_view name, ANARIDataType objectType);
    Array* getArray(std::string_view name, ANARIDataType arrayType = ANARI_ARRAY1D);
    // Marks the object invalid with an error message (a required parameter missing, bad data...); only
    // the first call of a commit reports.
    void invalidate(const std::string& message);
    // invalidate() with the problem a check of ArrayChecks.h found; true when there was one.
    bool reject(const std::optional<std::string>& problem);

    const Parameter* findParameter(std::string_view name);  // marks it read

private:
    template <class T> bool read(std::string_view name, T& out);

    DeviceState& state_;
    ANARIDataType type_;
    std::string subtype_;
    uint64_t serial_ = 0;                // creation order, for labels
    ANARIObject handle_ = nullptr;
    uint32_t references_ = 1;            // all references; the creator's is the first
    uint32_t publicReferences_ = 1;      // the application's alone
    bool valid_ = true;
    uint64_t lastCommitted_ = 0;
    std::map<std::string, Parameter, std::less<>> parameters_;
};

// The ANARI data type of the C++ types commit() asks for.
template <class T> constexpr ANARIDataType anariTypeOf();
template <> constexpr ANARIDataType anariTypeOf<float>() { return ANARI_FLOAT32; }
template <> constexpr ANARIDataType anariTypeOf<int32_t>() { return ANARI_INT32; }
template <> constexpr ANARIDataType anariTypeOf<uint32_t>() { return ANARI_UINT32; }
template <> constexpr ANARIDataType anariTypeOf<uint64_t>() { return ANARI_UINT64; }
template <> constexpr ANARIDataType anariTypeOf<bool>() { return ANARI_BOOL; }
template <> constexpr ANARIDataType anariTypeOf<glm::vec2>() { return ANARI_FLOAT32_VEC2; }
template <> constexpr ANARIDataType anariTypeOf<glm::vec3>() { return ANARI_FLOAT32_VEC3; }
template <> constexpr ANARIDataType anariTypeOf<glm::vec4>() { return ANARI_FLOAT32_VEC4; }
template <> constexpr ANARIDataType anariTypeOf<glm::uvec2>() { return ANARI_UINT32_VEC2; }
template <> constexpr ANARIDataType anariTypeOf<glm::mat4>() { return ANARI_FLOAT32_MAT4; }

template <class T> bool Object::read(std::string_view name, T& out) {
    const Parameter* p = findParameter(name);
    if (!p) return false;
    if (p->type != anariTypeOf<T>()) {
        reportWarning("parameter '" + std::string(name) + "' has type " + ripple_anari::typeName(p->type) +
                      ", expected " + ripple_anari::typeName(anariTypeOf<T>()) + "; using the default");
        return false;
    }
    if constexpr (std::is_same_v<T, bool>) {
        int32_t value = 0;
        std::memcpy(&value, p->bytes.data(), sizeof(value));
        out = value != 0;
    } else {
        std::memcpy(&out, p->bytes.data(), sizeof(T));
    }
    return true;
}

template <class T> T Object::get(std::string_view name, const T& fallback) {
    T value;
    return read(name, value) ? value : fallback;
}

template <class T> std::optional<T> Object::getOptional(std::string_view name) {
    T value;
    if (read(name, value)) return value;
    return std::nullopt;
}

}  // namespace ripple::device
