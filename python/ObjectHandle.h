// The Python side of an ANARI object: its handle, its type and the device it belongs to. Python's garbage
// collector releases the handle; the device keeps what other objects still use (ANARI counts references).
#pragma once

#include "python/DeviceSession.h"

#include <anari/anari_type_traits.hpp>

#include <pybind11/numpy.h>

#include <cstddef>
#include <optional>

namespace ripple::python {

class Object {
public:
    Object(std::shared_ptr<DeviceSession> session, ANARIObject handle, ANARIDataType type, std::string subtype);
    virtual ~Object();
    Object(const Object&) = delete;
    Object& operator=(const Object&) = delete;

    ANARIObject handle() const;  // throws ValueError once released
    ANARIDataType type() const { return type_; }
    const std::string& subtype() const { return subtype_; }
    DeviceSession& session() const { return *session_; }
    const std::shared_ptr<DeviceSession>& sessionPointer() const { return session_; }
    void release();
    std::string repr() const;

    // setParameter(name, type, value): value converted to `type`, or TypeError/ValueError naming name.
    void setParameter(const std::string& name, int type, py::handle value);
    // setParameter(name, value) for an object (its own type) or a string.
    void setParameterInferred(const std::string& name, py::handle value);
    // setParameterArrayND(name, elementType, data): a new array of data set as the parameter.
    void setParameterArray(const std::string& name, int dims, int elementType, py::handle data);
    void unsetParameter(const std::string& name);
    void commitParameters();

protected:
    std::shared_ptr<DeviceSession> session_;
    ANARIObject handle_;
    ANARIDataType type_;
    std::string subtype_;
};

// The Python side of the device: creates objects and arrays, takes device parameters.
class Device {
public:
    explicit Device(std::shared_ptr<DeviceSession> s) : session(std::move(s)) {}
    std::shared_ptr<Object> newObject(ANARIDataType type, const std::string& subtype);
    std::shared_ptr<Object> newGroup(const py::list& members);
    void setParameter(const std::string& name, int type, py::handle value);
    void commitParameters();

    std::shared_ptr<DeviceSession> session;
};

// How one element of an ANARI data type is stored: `components` numbers of `kind` ('i' signed, 'u' unsigned,
// 'f' float) and `bytes` each; empty for strings, handles and types without a fixed numeric layout.
struct ElementFormat {
    char kind;
    size_t bytes;
    size_t components;
};
std::optional<ElementFormat> elementFormat(ANARIDataType type);
// The numpy dtype of one component of `format` ("f4", "u1", ...).
py::dtype componentDtype(const ElementFormat& format);
// "FLOAT32_VEC3": the constant's name as pynari spells it.
std::string shortTypeName(int type);

// The bytes of `value` as a parameter of `type`; `what` names it in errors ("setParameter('position', ...)").
std::vector<std::byte> parameterBytes(const std::string& what, ANARIDataType type, py::handle value);

// A new ANARI array of `dims` (1..3) dimensions: numpy data shared with the device (kept alive until the
// device lets go of it; copied only when it is not C-contiguous), or a list of objects (copied handles).
std::shared_ptr<Object> newArray(const std::shared_ptr<DeviceSession>& session, int dims, int elementType,
                                 py::handle data);

}  // namespace ripple::python
