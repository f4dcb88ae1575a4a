// ANARI objects from Python: creation, parameters (objects, strings, numbers), commit and release.
#include "python/ObjectHandle.h"

#include "python/FrameChannels.h"

namespace ripple::python {

namespace {

bool isArrayType(int type) { return type >= ANARI_ARRAY && type <= ANARI_ARRAY3D; }

// The type an object parameter is set with: the object's own, where the script names a family
// (OBJECT, or ARRAY for any array); a TypeError where the script names another type.
ANARIDataType objectParameterType(const std::string& what, int requested, const Object& object) {
    const int actual = object.type();
    if (requested == actual || requested == ANARI_OBJECT || (isArrayType(requested) && isArrayType(actual))) return actual;
    throw py::type_error(what + ": expects a " + shortTypeName(requested) + ", got a " + shortTypeName(actual) +
                         (object.subtype().empty() ? "" : " ('" + object.subtype() + "')"));
}

std::string describe(const std::string& call, const std::string& name, int type) {
    return call + "('" + name + "', " + shortTypeName(type) + ")";
}

// Sets `name` on `target` from a Python value of `type`; shared by objects and the device.
void setAnyParameter(DeviceSession& session, ANARIObject target, const std::string& name, int type, py::handle value) {
    const std::string what = describe("setParameter", name, type);
    if (type == ANARI_STRING) {
        if (!py::isinstance<py::str>(value))
            throw py::type_error(what + ": expects a str, got " + std::string(py::str(py::type::of(value).attr("__name__"))));
        const std::string text = value.cast<std::string>();
        anariSetParameter(session.handle(), target, name.c_str(), ANARI_STRING, text.c_str());
    } else if (ripple_anari::isObjectType(type)) {
        if (!py::isinstance<Object>(value))
            throw py::type_error(what + ": expects a pynari object, got " +
                                 std::string(py::str(py::type::of(value).attr("__name__"))));
        const Object& object = value.cast<const Object&>();
        if (&object.session() != &session) throw py::value_error(what + ": the object belongs to another device");
        const ANARIObject handle = object.handle();
        anariSetParameter(session.handle(), target, name.c_str(), objectParameterType(what, type, object), &handle);
    } else {
        const std::vector<std::byte> bytes = parameterBytes(what, ANARIDataType(type), value);
        anariSetParameter(session.handle(), target, name.c_str(), ANARIDataType(type), bytes.data());
    }
    session.raiseStatus(what);
}

}  // namespace

Object::Object(std::shared_ptr<DeviceSession> session, ANARIObject handle, ANARIDataType type, std::string subtype)
    : session_(std::move(session)), handle_(handle), type_(type), subtype_(std::move(subtype)) {}

Object::~Object() {
    if (handle_ != nullptr) anariRelease(session_->handle(), handle_);
}

ANARIObject Object::handle() const {
    if (handle_ == nullptr) throw py::value_error(repr() + " was released");
    return handle_;
}

void Object::release() {
    if (handle_ == nullptr) return;
    anariRelease(session_->handle(), handle_);
    handle_ = nullptr;
    session_->raiseStatus(repr() + ".release()");
}

std::string Object::repr() const {
    return "<pynari " + shortTypeName(type_) + (subtype_.empty() ? "" : " '" + subtype_ + "'") + ">";
}

void Object::setParameter(const std::string& name, int type, py::handle value) {
    setAnyParameter(*session_, handle(), name, type, value);
}

void Object::setParameterInferred(const std::string& name, py::handle value) {
    if (py::isinstance<Object>(value)) return setParameter(name, value.cast<const Object&>().type(), value);
    if (py::isinstance<py::str>(value)) return setParameter(name, ANARI_STRING, value);
    throw py::type_error("setParameter('" + name + "', value): without a type, the value must be a pynari object or "
                         "a str; pass the type for " + std::string(py::str(py::type::of(value).attr("__name__"))));
}

void Object::setParameterArray(const std::string& name, int dims, int elementType, py::handle data) {
    const std::shared_ptr<Object> array = newArray(session_, dims, elementType, data);
    const ANARIObject arrayHandle = array->handle();
    anariSetParameter(session_->handle(), handle(), name.c_str(), array->type(), &arrayHandle);
    session_->raiseStatus(describe("setParameterArray" + std::to_string(dims) + "D", name, elementType));
}  // the parameter holds the array now; the wrapper's reference goes

void Object::unsetParameter(const std::string& name) {
    anariUnsetParameter(session_->handle(), handle(), name.c_str());
    session_->raiseStatus("unsetParameter('" + name + "')");
}

void Object::commitParameters() {
    anariCommitParameters(session_->handle(), handle());
    session_->raiseStatus(repr() + ".commitParameters()");
}

std::shared_ptr<Object> Device::newObject(ANARIDataType type, const std::string& subtype) {
    const ANARIDevice d = session->handle();
    ANARIObject handle = nullptr;
    switch (type) {
        case ANARI_CAMERA: handle = anariNewCamera(d, subtype.c_str()); break;
        case ANARI_GEOMETRY: handle = anariNewGeometry(d, subtype.c_str()); break;
        case ANARI_GROUP: handle = anariNewGroup(d); break;
        case ANARI_INSTANCE: handle = anariNewInstance(d, subtype.c_str()); break;
        case ANARI_LIGHT: handle = anariNewLight(d, subtype.c_str()); break;
        case ANARI_MATERIAL: handle = anariNewMaterial(d, subtype.c_str()); break;
        case ANARI_RENDERER: handle = anariNewRenderer(d, subtype.c_str()); break;
        case ANARI_SURFACE: handle = anariNewSurface(d); break;
        case ANARI_SAMPLER: handle = anariNewSampler(d, subtype.c_str()); break;
        case ANARI_SPATIAL_FIELD: handle = anariNewSpatialField(d, subtype.c_str()); break;
        case ANARI_VOLUME: handle = anariNewVolume(d, subtype.c_str()); break;
        case ANARI_WORLD: handle = anariNewWorld(d); break;
        case ANARI_FRAME: handle = anariNewFrame(d); break;
        default: throw py::value_error("cannot create an object of type " + shortTypeName(type));
    }
    const std::string what = "new " + shortTypeName(type) + (subtype.empty() ? "" : " '" + subtype + "'");
    if (handle == nullptr) {
        session->raiseStatus(what);
        throw DeviceError(what + ": the device returned no object");
    }
    std::shared_ptr<Object> object;
    if (type == ANARI_FRAME) object = std::make_shared<Frame>(session, handle);
    else object = std::make_shared<Object>(session, handle, type, subtype);
    session->raiseStatus(what);
    return object;
}

std::shared_ptr<Object> Device::newGroup(const py::list& members) {
    // pynari's newGroup(list): surfaces and volumes of the list become the group's two arrays.
    std::shared_ptr<Object> group = newObject(ANARI_GROUP, "");
    py::list surfaces, volumes;
    for (py::handle item : members) {
        if (!py::isinstance<Object>(item))
            throw py::type_error("newGroup(list): expects surfaces and volumes, got " +
                                 std::string(py::str(py::type::of(item).attr("__name__"))));
        const int type = item.cast<const Object&>().type();
        if (type == ANARI_SURFACE) surfaces.append(item);
        else if (type == ANARI_VOLUME) volumes.append(item);
        else throw py::type_error("newGroup(list): expects surfaces and volumes, got a " + shortTypeName(type));
    }
    if (!surfaces.empty()) group->setParameterArray("surface", 1, ANARI_SURFACE, surfaces);
    if (!volumes.empty()) group->setParameterArray("volume", 1, ANARI_VOLUME, volumes);
    group->commitParameters();
    return group;
}

void Device::setParameter(const std::string& name, int type, py::handle value) {
    setAnyParameter(*session, session->handle(), name, type, value);
}

void Device::commitParameters() {
    anariCommitParameters(session->handle(), session->handle());
    session->raiseStatus("device.commitParameters()");
}

}  // namespace ripple::python
