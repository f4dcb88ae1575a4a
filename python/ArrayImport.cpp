// numpy arrays and lists of objects as ANARI arrays. numpy data is shared, not copied: the device reads the
// array's own memory and holds a reference to it until it calls the deleter (DeviceSession.cpp).
#include "python/ObjectHandle.h"

#include <algorithm>
#include <cstring>

namespace ripple::python {

namespace {

std::string shapeText(const py::array& array) {
    std::string text = "(";
    for (py::ssize_t i = 0; i < array.ndim(); ++i) text += (i ? ", " : "") + std::to_string(array.shape(i));
    return text + (array.ndim() == 1 ? ",)" : ")");
}

std::string expectedShapes(int dims, size_t components) {
    static const char* names[] = {"n", "h, w", "d, h, w"};
    const std::string base = names[dims - 1];
    std::string text = "(" + base + (dims == 1 ? ",)" : ")");
    if (components > 1) {
        text += " or (" + base + ", " + std::to_string(components) + ")";
        if (dims == 1) text += " or (n*" + std::to_string(components) + ",)";
    }
    return text;
}

std::shared_ptr<Object> newObjectArray(const std::shared_ptr<DeviceSession>& session, const std::string& what,
                                       int elementType, const py::sequence& items) {
    std::vector<ANARIObject> handles;
    for (py::handle item : items) {
        if (!py::isinstance<Object>(item))
            throw py::type_error(what + ": expects a list of pynari objects, got a " +
                                 std::string(py::str(py::type::of(item).attr("__name__"))) + " in it");
        const Object& object = item.cast<const Object&>();
        if (elementType != ANARI_OBJECT && object.type() != elementType)
            throw py::type_error(what + ": expects " + shortTypeName(elementType) + " objects, got a " +
                                 shortTypeName(object.type()));
        if (&object.session() != session.get()) throw py::value_error(what + ": an object belongs to another device");
        handles.push_back(object.handle());
    }
    // Handles are copied into a device-owned array, which holds references to the objects.
    const ANARIDevice d = session->handle();
    ANARIArray1D array = anariNewArray1D(d, nullptr, nullptr, nullptr, ANARIDataType(elementType), handles.size());
    if (array == nullptr) {
        session->raiseStatus(what);
        throw DeviceError(what + ": the device returned no array");
    }
    auto wrapper = std::make_shared<Object>(session, array, ANARI_ARRAY1D, "");
    if (!handles.empty()) {
        void* mapped = anariMapArray(d, array);
        if (mapped == nullptr) {
            session->raiseStatus(what);
            throw DeviceError(what + ": the device could not map the array");
        }
        std::memcpy(mapped, handles.data(), handles.size() * sizeof(ANARIObject));
        anariUnmapArray(d, array);
    }
    session->raiseStatus(what);
    return wrapper;
}

}  // namespace

std::shared_ptr<Object> newArray(const std::shared_ptr<DeviceSession>& session, int dims, int elementType,
                                 py::handle data) {
    const std::string what = "newArray" + std::to_string(dims) + "D(" + shortTypeName(elementType) + ")";
    if (dims < 1 || dims > 3) throw py::value_error(what + ": arrays have 1 to 3 dimensions");
    if (ripple_anari::isObjectType(ANARIDataType(elementType))) {
        if (dims != 1) throw py::value_error(what + ": arrays of objects have one dimension");
        if (!py::isinstance<py::list>(data) && !py::isinstance<py::tuple>(data))
            throw py::type_error(what + ": expects a list of objects, got " +
                                 std::string(py::str(py::type::of(data).attr("__name__"))));
        return newObjectArray(session, what, elementType, py::reinterpret_borrow<py::sequence>(data));
    }
    const std::optional<ElementFormat> format = elementFormat(ANARIDataType(elementType));
    if (!format || elementType == ANARI_BOOL || elementType == ANARI_DATA_TYPE || elementType == ANARI_VOID_POINTER)
        throw py::value_error(what + ": " + shortTypeName(elementType) + " is not an array element type");
    if (!py::isinstance<py::array>(data))
        throw py::type_error(what + ": expects a numpy array, got " + std::string(py::str(py::type::of(data).attr("__name__"))));
    py::array array = py::reinterpret_borrow<py::array>(data);
    const py::dtype expected = componentDtype(*format);
    if (!array.dtype().is(expected) && !array.dtype().equal(expected))
        throw py::type_error(what + ": expects dtype " + std::string(py::str(py::handle(expected))) + ", got " +
                             std::string(py::str(py::handle(array.dtype()))));
    // The element grid: the array's shape without a trailing dimension of `components`, or for a flat 1D
    // array of components (pynari's samples pass vertices so), its length divided by them.
    std::vector<uint64_t> grid;
    const size_t nd = size_t(array.ndim());
    const size_t c = format->components;
    if (c > 1 && nd >= 1 && size_t(array.shape(nd - 1)) == c && nd - 1 == size_t(dims)) {
        for (size_t i = 0; i + 1 < nd; ++i) grid.push_back(uint64_t(array.shape(i)));
    } else if (c > 1 && dims == 1 && nd == 1 && size_t(array.shape(0)) % c == 0) {
        grid.push_back(uint64_t(array.shape(0)) / c);
    } else if (c == 1 && nd == size_t(dims)) {
        for (size_t i = 0; i < nd; ++i) grid.push_back(uint64_t(array.shape(i)));
    } else {
        throw py::value_error(what + ": expects shape " + expectedShapes(dims, c) + ", got " + shapeText(array));
    }
    // The device reads the memory as packed C order; anything else is copied first (pynari copies always).
    if (!(array.flags() & py::array::c_style)) array = py::module_::import("numpy").attr("ascontiguousarray")(array);
    // numpy's order is (d, h, w); ANARI's sizes go x first.
    std::reverse(grid.begin(), grid.end());
    const ANARIDevice d = session->handle();
    PyObject* keepAlive = array.ptr();
    Py_INCREF(keepAlive);  // the device's reference, dropped by the deleter
    const void* memory = array.data();
    const auto type = ANARIDataType(elementType);
    ANARIArray handle = nullptr;
    if (dims == 1) handle = anariNewArray1D(d, memory, &DeviceSession::releaseSharedArray, keepAlive, type, grid[0]);
    if (dims == 2) handle = anariNewArray2D(d, memory, &DeviceSession::releaseSharedArray, keepAlive, type, grid[0], grid[1]);
    if (dims == 3)
        handle = anariNewArray3D(d, memory, &DeviceSession::releaseSharedArray, keepAlive, type, grid[0], grid[1], grid[2]);
    if (handle == nullptr) {
        session->raiseStatus(what);
        throw DeviceError(what + ": the device returned no array");
    }
    const ANARIDataType arrayType = dims == 1 ? ANARI_ARRAY1D : dims == 2 ? ANARI_ARRAY2D : ANARI_ARRAY3D;
    auto wrapper = std::make_shared<Object>(session, handle, arrayType, "");
    session->raiseStatus(what);
    return wrapper;
}

}  // namespace ripple::python
