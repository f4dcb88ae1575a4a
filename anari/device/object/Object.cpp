// Parameter storage, typed access and status reporting shared by every object of the Ripple device.
#include "anari/device/object/Object.h"

#include "anari/device/array/Array.h"
#include "anari/device/object/DeviceState.h"

#include <exception>

namespace ripple::device {

namespace {

const char* objectTypeName(ANARIDataType type) {
    switch (type) {
    case ANARI_ARRAY: case ANARI_ARRAY1D: case ANARI_ARRAY2D: case ANARI_ARRAY3D: return "array";
    case ANARI_CAMERA: return "camera";
    case ANARI_FRAME: return "frame";
    case ANARI_GEOMETRY: return "geometry";
    case ANARI_GROUP: return "group";
    case ANARI_INSTANCE: return "instance";
    case ANARI_LIGHT: return "light";
    case ANARI_MATERIAL: return "material";
    case ANARI_RENDERER: return "renderer";
    case ANARI_SURFACE: return "surface";
    case ANARI_SAMPLER: return "sampler";
    case ANARI_SPATIAL_FIELD: return "spatial field";
    case ANARI_VOLUME: return "volume";
    case ANARI_WORLD: return "world";
    default: return "object";
    }
}

bool isArrayType(ANARIDataType type) {
    return type == ANARI_ARRAY || type == ANARI_ARRAY1D || type == ANARI_ARRAY2D || type == ANARI_ARRAY3D;
}

}  // namespace

Object::Object(DeviceState& state, ANARIDataType type, std::string subtype)
    : state_(state), type_(type), subtype_(std::move(subtype)), serial_(state.nextSerial()) {
    handle_ = state_.handles.add(this);
    lastCommitted_ = state_.nextStamp();
}

Object::~Object() {
    unsetAllParameters();
    state_.handles.remove(handle_);
}

std::string Object::label() const {
    std::string text = objectTypeName(type_);
    if (!subtype_.empty()) text += " '" + subtype_ + "'";
    return text + " #" + std::to_string(serial_);
}

void Object::retain() { ++references_; }

void Object::release() {
    if (references_ == 0) return;  // already dying: a parameter cycle releasing back into us
    if (--references_ == 0) delete this;
}

void Object::retainPublic() {
    ++publicReferences_;
    retain();
}

bool Object::releasePublic() {
    if (publicReferences_ == 0) return false;
    // The application lets go of its last reference: whatever still holds the object internally must
    // stop depending on application memory now (arrays copy shared memory), before we return.
    if (--publicReferences_ == 0 && references_ > 1) onLastPublicRelease();
    release();
    return true;
}

void Object::setParameter(std::string_view name, ANARIDataType type, const void* mem) {
    if (name.empty()) {
        reportWarning("anariSetParameter with an empty name; ignored");
        return;
    }
    if (!mem && type != ANARI_VOID_POINTER) {
        reportWarning("parameter '" + std::string(name) + "' set with a NULL value; ignored");
        return;
    }
    Parameter value;
    value.type = type;
    if (type == ANARI_VOID_POINTER) {
        // As in the SDK's C++ wrapper and helium: an ANARI_VOID_POINTER's value is `mem` itself, not what
        // it points to (like ANARI_STRING). Stored as the pointer's bytes.
        const auto* bytes = reinterpret_cast<const uint8_t*>(&mem);
        value.bytes.assign(bytes, bytes + sizeof(mem));
    } else if (type == ANARI_STRING) {
        value.string = static_cast<const char*>(mem);
    } else if (ripple_anari::isObjectType(type)) {
        const auto handle = *static_cast<const ANARIObject*>(mem);
        value.object = state_.handles.find(handle);
        if (handle && (!value.object || value.object->publicReferenceCount() == 0)) {
            reportError("parameter '" + std::string(name) +
                        "' names an object the application has released (or one that is not of this device); ignored");
            return;
        }
        if (value.object) value.object->retain();
    } else {
        const size_t size = ripple_anari::sizeOf(type);
        if (size == 0) {
            reportWarning("parameter '" + std::string(name) + "' has unknown data type " + std::to_string(type) +
                          "; ignored");
            return;
        }
        const auto* bytes = static_cast<const uint8_t*>(mem);
        value.bytes.assign(bytes, bytes + size);
    }
    unsetParameter(name);
    parameters_.emplace(std::string(name), std::move(value));
}

void Object::unsetParameter(std::string_view name) {
    auto it = parameters_.find(name);
    if (it == parameters_.end()) return;
    Object* held = it->second.object;
    parameters_.erase(it);
    if (held) held->release();  // after erasing: releasing may delete objects that refer back to us
}

void Object::unsetAllParameters() {
    std::vector<Object*> held;
    for (auto& [name, value] : parameters_)
        if (value.object) held.push_back(value.object);
    parameters_.clear();
    for (Object* object : held) object->release();
}

void Object::commitParameters() {
    valid_ = true;
    for (auto& [name, value] : parameters_) value.readSinceSet = false;
    try {
        commit();
    } catch (const std::exception& error) {
        invalidate(std::string("commit failed: ") + error.what());
    }
    for (auto& [name, value] : parameters_) {
        if (value.readSinceSet || value.warnedUnused) continue;
        value.warnedUnused = true;
        reportWarning("parameter '" + name + "' is not used by Ripple (unknown or unsupported); ignored");
    }
    lastCommitted_ = state_.nextStamp();
}

bool Object::getProperty(std::string_view, ANARIDataType, void*, uint64_t, bool) { return false; }

void Object::reportError(const std::string& message) const {
    state_.report(this, ANARI_SEVERITY_ERROR, ANARI_STATUS_INVALID_ARGUMENT, label() + ": " + message);
}

void Object::reportWarning(const std::string& message) const {
    state_.report(this, ANARI_SEVERITY_WARNING, ANARI_STATUS_INVALID_ARGUMENT, label() + ": " + message);
}

void Object::invalidate(const std::string& message) {
    // One error per commit: the first problem found; later ones may be consequences of it.
    if (!valid_) return;
    valid_ = false;
    reportError(message + "; the object renders nothing");
}

bool Object::reject(const std::optional<std::string>& problem) {
    if (problem) invalidate(*problem);
    return problem.has_value();
}

const Parameter* Object::findParameter(std::string_view name) {
    auto it = parameters_.find(name);
    if (it == parameters_.end()) return nullptr;
    it->second.readSinceSet = true;
    return &it->second;
}

bool Object::has(std::string_view name) const { return parameters_.find(name) != parameters_.end(); }

ANARIDataType Object::parameterType(std::string_view name) const {
    auto it = parameters_.find(name);
    return it == parameters_.end() ? ANARI_UNKNOWN : it->second.type;
}

std::string Object::getString(std::string_view name, const std::string& fallback) {
    const Parameter* p = findParameter(name);
    if (!p) return fallback;
    if (p->type != ANARI_STRING) {
        reportWarning("parameter '" + std::string(name) + "' has type " + ripple_anari::typeName(p->type) +
                      ", expected ANARI_STRING; using the default");
        return fallback;
    }
    return p->string;
}

Object* Object::getObject(std::string_view name, ANARIDataType objectType) {
    const Parameter* p = findParameter(name);
    if (!p || !p->object) return nullptr;
    const bool typeMatches = p->type == objectType || (isArrayType(objectType) && isArrayType(p->type));
    if (!typeMatches) {
        reportWarning("parameter '" + std::string(name) + "' has type " + ripple_anari::typeName(p->type) +
                      ", expected " + ripple_anari::typeName(objectType) + "; ignored");
        return nullptr;
    }
    // Set with the right type but naming an object of another kind: name what it really is.
    if (isArrayType(objectType) ? !isArrayType(p->object->type()) : p->object->type() != objectType) {
        reportWarning("parameter '" + std::string(name) + "' was set as " + ripple_anari::typeName(p->type) +
                      " but names " + p->object->label() + " (" + ripple_anari::typeName(p->object->type()) +
                      "), expected " + ripple_anari::typeName(objectType) + "; ignored");
        return nullptr;
    }
    return p->object;
}

Array* Object::getArray(std::string_view name, ANARIDataType arrayType) {
    Object* object = getObject(name, arrayType);
    if (!object) return nullptr;
    auto* array = static_cast<Array*>(object);
    if (arrayType != ANARI_ARRAY && array->type() != arrayType) {
        reportWarning("parameter '" + std::string(name) + "' is an " + ripple_anari::typeName(array->type()) +
                      ", expected " + ripple_anari::typeName(arrayType) + "; ignored");
        return nullptr;
    }
    return array;
}

}  // namespace ripple::device
