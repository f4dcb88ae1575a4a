// Python values as ANARI parameter bytes: numbers, sequences and numpy arrays checked against the
// parameter's type, so that a wrong value is a TypeError or ValueError naming the parameter, never a crash.
#include "python/ObjectHandle.h"

#include <cmath>
#include <cstring>
#include <limits>

namespace ripple::python {

std::optional<ElementFormat> elementFormat(ANARIDataType type) {
    const int t = type;
    if (t >= ANARI_INT8 && t <= ANARI_FLOAT64_VEC4) {
        const int block = (t - ANARI_INT8) / 4;  // INT8 UINT8 ... UINT64, FIXED8 ... UFIXED64, FLOAT16/32/64
        const size_t components = size_t((t - ANARI_INT8) % 4 + 1);
        if (block == 16) return std::nullopt;  // FLOAT16: numpy has it, but no device reads it
        const char kind = block >= 17 ? 'f' : (block % 2 == 0 ? 'i' : 'u');
        return ElementFormat{kind, ripple_anari::numericComponentBytes(t), components};
    }
    if (t >= ANARI_UFIXED8_R_SRGB && t <= ANARI_UFIXED8_RGBA_SRGB)
        return ElementFormat{'u', 1, size_t(t - ANARI_UFIXED8_R_SRGB + 1)};
    if (t >= ANARI_INT32_BOX1 && t <= ANARI_INT32_BOX4) return ElementFormat{'i', 4, size_t(2 * (t - ANARI_INT32_BOX1 + 1))};
    if (t >= ANARI_FLOAT32_BOX1 && t <= ANARI_FLOAT32_BOX4)
        return ElementFormat{'f', 4, size_t(2 * (t - ANARI_FLOAT32_BOX1 + 1))};
    if (t >= ANARI_FLOAT64_BOX1 && t <= ANARI_FLOAT64_BOX4)
        return ElementFormat{'f', 8, size_t(2 * (t - ANARI_FLOAT64_BOX1 + 1))};
    if (t >= ANARI_UINT64_REGION1 && t <= ANARI_UINT64_REGION4)
        return ElementFormat{'u', 8, size_t(2 * (t - ANARI_UINT64_REGION1 + 1))};
    switch (t) {
        case ANARI_BOOL:
        case ANARI_DATA_TYPE: return ElementFormat{'i', 4, 1};
        case ANARI_VOID_POINTER: return ElementFormat{'u', sizeof(void*), 1};
        case ANARI_FLOAT32_MAT2:
        case ANARI_FLOAT32_QUAT_IJKW: return ElementFormat{'f', 4, 4};
        case ANARI_FLOAT32_MAT3: return ElementFormat{'f', 4, 9};
        case ANARI_FLOAT32_MAT4: return ElementFormat{'f', 4, 16};
        case ANARI_FLOAT32_MAT2x3: return ElementFormat{'f', 4, 6};
        case ANARI_FLOAT32_MAT3x4: return ElementFormat{'f', 4, 12};
        default: return std::nullopt;
    }
}

py::dtype componentDtype(const ElementFormat& format) {
    return py::dtype(std::string(1, format.kind) + std::to_string(format.bytes));
}

std::string shortTypeName(int type) {
    const std::string name = ripple_anari::typeName(type);
    if (name == "ANARI_UNKNOWN" && type != ANARI_UNKNOWN) return "type " + std::to_string(type);
    return name.rfind("ANARI_", 0) == 0 ? name.substr(6) : name;
}

namespace {

// Writes one Python number as a component of `format`, checking that it is a number of the right kind and
// that it fits.
void writeComponent(const std::string& what, const ElementFormat& format, py::handle item, std::byte* out) {
    // numpy scalars are not int/float subclasses in general: ask them for their Python value.
    py::object value = py::reinterpret_borrow<py::object>(item);
    if (py::hasattr(value, "item") && !py::isinstance<py::int_>(value) && !py::isinstance<py::float_>(value))
        value = value.attr("item")();
    const bool isInt = py::isinstance<py::int_>(value);  // bool included
    const bool isFloat = py::isinstance<py::float_>(value);
    if (!isInt && !isFloat)
        throw py::type_error(what + ": expects numbers, got " + std::string(py::str(py::type::of(value).attr("__name__"))));
    if (format.kind == 'f') {
        const double d = value.cast<double>();
        if (format.bytes == 4) {
            const float f = float(d);
            std::memcpy(out, &f, 4);
        } else {
            std::memcpy(out, &d, 8);
        }
        return;
    }
    if (!isInt) {
        const double d = value.cast<double>();
        if (d != std::floor(d)) throw py::type_error(what + ": expects integers, got " + std::string(py::repr(value)));
        value = py::int_(value);
    }
    const std::string range = what + ": " + std::string(py::repr(value)) + " does not fit in " +
                              (format.kind == 'u' ? "an unsigned " : "a signed ") +
                              std::to_string(format.bytes * 8) + "-bit integer";
    if (format.kind == 'u') {
        if (value.cast<py::int_>() < py::int_(0)) throw py::value_error(range);
        unsigned long long u = PyLong_AsUnsignedLongLong(value.ptr());
        if (PyErr_Occurred()) {
            PyErr_Clear();
            throw py::value_error(range);
        }
        if (format.bytes < 8 && u >> (format.bytes * 8) != 0) throw py::value_error(range);
        const uint64_t v = u;
        std::memcpy(out, &v, format.bytes);  // little-endian: the low bytes
    } else {
        long long s = PyLong_AsLongLong(value.ptr());
        if (PyErr_Occurred()) {
            PyErr_Clear();
            throw py::value_error(range);
        }
        if (format.bytes < 8) {
            const long long limit = 1LL << (format.bytes * 8 - 1);
            if (s < -limit || s >= limit) throw py::value_error(range);
        }
        const int64_t v = s;
        std::memcpy(out, &v, format.bytes);
    }
}

}  // namespace

std::vector<std::byte> parameterBytes(const std::string& what, ANARIDataType type, py::handle value) {
    const std::optional<ElementFormat> format = elementFormat(type);
    if (!format) throw py::value_error(what + ": " + shortTypeName(type) + " is not a type a parameter can have here");
    if (value.is_none() || py::isinstance<py::str>(value) || py::isinstance<py::bytes>(value))
        throw py::type_error(what + ": expects " + std::to_string(format->components) + " number(s), got " +
                             std::string(py::str(py::type::of(value).attr("__name__"))));
    // A single number, or a sequence / numpy array of exactly `components` numbers (nested ones flattened).
    py::list items;
    const bool isNumber = py::isinstance<py::int_>(value) || py::isinstance<py::float_>(value) ||
                          (py::hasattr(value, "item") && py::hasattr(value, "ndim") && value.attr("ndim").cast<int>() == 0);
    if (isNumber) {
        items.append(value);
    } else {
        py::object array;
        try {
            array = py::module_::import("numpy").attr("asarray")(value);
        } catch (py::error_already_set&) {
            throw py::type_error(what + ": expects " + std::to_string(format->components) + " number(s), got " +
                                 std::string(py::str(py::type::of(value).attr("__name__"))));
        }
        const std::string kind = py::str(array.attr("dtype").attr("kind"));
        if (kind.size() != 1 || std::string("biuf").find(kind[0]) == std::string::npos)
            throw py::type_error(what + ": expects numbers, got " + std::string(py::repr(value)));
        items = array.attr("reshape")(-1).attr("tolist")();
    }
    if (items.size() != format->components)
        throw py::value_error(what + ": " + shortTypeName(type) + " takes " + std::to_string(format->components) +
                              " number(s), got " + std::to_string(items.size()));
    std::vector<std::byte> bytes(format->bytes * format->components);
    for (size_t i = 0; i < format->components; ++i) writeComponent(what, *format, items[i], bytes.data() + i * format->bytes);
    if (type == ANARI_BOOL) {  // any non-zero number is true; ANARI_BOOL is a 32-bit 0 or 1
        int32_t b = 0;
        std::memcpy(&b, bytes.data(), 4);
        b = b != 0 ? 1 : 0;
        std::memcpy(bytes.data(), &b, 4);
    }
    return bytes;
}

}  // namespace ripple::python
