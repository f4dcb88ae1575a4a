// The pynari module: pynari's Python API (ingowald/pynari: names, constants, call signatures) over the ANARI
// C API, so that pynari scripts run on any ANARI library the loader finds, Ripple by default.
#include "python/FrameChannels.h"

namespace ripple::python {
namespace {

py::list objectSubtypes(const Device& device, int type) {
    py::list names;
    const char** subtypes = anariGetObjectSubtypes(device.session->handle(), ANARIDataType(type));
    for (; subtypes != nullptr && *subtypes != nullptr; ++subtypes) names.append(*subtypes);
    device.session->raiseStatus("getObjectSubtypes(" + shortTypeName(type) + ")");
    return names;
}

py::dict objectInfo(const Device& device, int type, const std::string& subtype) {
    const ANARIDevice d = device.session->handle();
    py::dict info;
    const auto* description = static_cast<const char*>(
        anariGetObjectInfo(d, ANARIDataType(type), subtype.c_str(), "description", ANARI_STRING));
    info["description"] = description != nullptr ? description : "";
    py::list parameters;
    const auto* p = static_cast<const ANARIParameter*>(
        anariGetObjectInfo(d, ANARIDataType(type), subtype.c_str(), "parameter", ANARI_PARAMETER_LIST));
    for (; p != nullptr && p->name != nullptr; ++p) {
        py::dict entry;
        entry["name"] = p->name;
        entry["type"] = int(p->type);
        entry["type_name"] = ripple_anari::typeName(p->type);
        parameters.append(entry);
    }
    info["parameters"] = parameters;
    device.session->raiseStatus("getObjectInfo(" + shortTypeName(type) + ", '" + subtype + "')");
    return info;
}

py::dict parameterInfo(const Device& device, int type, const std::string& subtype, const std::string& name,
                       int parameterType) {
    const ANARIDevice d = device.session->handle();
    py::dict info;
    const auto* description = static_cast<const char*>(anariGetParameterInfo(
        d, ANARIDataType(type), subtype.c_str(), name.c_str(), ANARIDataType(parameterType), "description", ANARI_STRING));
    info["description"] = description != nullptr ? description : "";
    const auto* required = static_cast<const int32_t*>(anariGetParameterInfo(
        d, ANARIDataType(type), subtype.c_str(), name.c_str(), ANARIDataType(parameterType), "required", ANARI_BOOL));
    info["required"] = required != nullptr && *required != 0;
    device.session->raiseStatus("getParameterInfo(" + shortTypeName(type) + ", '" + subtype + "', '" + name + "')");
    return info;
}

void defineConstants(py::module_& m) {
    // Every ANARI data type under its name without "ANARI_" (pynari's subset and the rest, e.g. INSTANCE).
    for (int type = 0; type <= ANARI_FLOAT64_BOX4; ++type) {
        const std::string name = shortTypeName(type);
        if (name.rfind("type ", 0) != 0 && !(type != ANARI_UNKNOWN && name == "UNKNOWN")) m.attr(name.c_str()) = type;
    }
    // pynari's own spellings.
    m.attr("FLOAT32_MAT4X4") = int(ANARI_FLOAT32_MAT4);
    for (int i = 1; i <= 4; ++i) m.attr(("FLOAT32_RANGE" + std::to_string(i)).c_str()) = int(ANARI_FLOAT32_BOX1) + i - 1;
    m.attr("FLOAT") = int(ANARI_FLOAT32);
    m.attr("float") = int(ANARI_FLOAT32);
    m.attr("float2") = int(ANARI_FLOAT32_VEC2);
    m.attr("float3") = int(ANARI_FLOAT32_VEC3);
    m.attr("float4") = int(ANARI_FLOAT32_VEC4);
    m.attr("UINT") = int(ANARI_UINT32);
    m.attr("uint") = int(ANARI_UINT32);
    m.attr("uint2") = int(ANARI_UINT32_VEC2);
    m.attr("uint3") = int(ANARI_UINT32_VEC3);
    m.attr("uint4") = int(ANARI_UINT32_VEC4);
}

}  // namespace
}  // namespace ripple::python

PYBIND11_MODULE(pynari, m) {
    using namespace ripple::python;
    m.doc() = "pynari's API over the ANARI C API (Ripple's loader; Ripple's device by default)";
    py::register_exception<DeviceError>(m, "DeviceError", PyExc_RuntimeError);
    m.attr("DeviceWarning") = py::reinterpret_steal<py::object>(
        PyErr_NewExceptionWithDoc("pynari.DeviceWarning", "A warning the ANARI device reported.", PyExc_UserWarning, nullptr));
    defineConstants(m);

    m.def("newDevice", [](const std::string& libName, const std::string& devName) {
        return Device(std::make_shared<DeviceSession>(libName, devName));
    }, "Loads the ANARI library libName ('default': $ANARI_LIBRARY, else ripple) and creates its device devName",
          py::arg("libName") = "default", py::arg("devName") = "default");
    // pynari asks this to choose sample counts; Ripple runs on Vulkan, and this module has no CUDA.
    m.def("has_cuda_capable_gpu", [] { return false; });

    py::class_<Object, std::shared_ptr<Object>> object(m, "Object");
    object.def("setParameter", &Object::setParameter, py::arg("name"), py::arg("type"), py::arg("value"))
        .def("setParameter", &Object::setParameterInferred, py::arg("name"), py::arg("value"))
        .def("setParameterArray", [](Object& o, const std::string& name, int type, py::handle data) {
            o.setParameterArray(name, 1, type, data);
        })
        .def("setParameterArray1D", [](Object& o, const std::string& name, int type, py::handle data) {
            o.setParameterArray(name, 1, type, data);
        })
        .def("setParameterArray2D", [](Object& o, const std::string& name, int type, py::handle data) {
            o.setParameterArray(name, 2, type, data);
        })
        .def("setParameterArray3D", [](Object& o, const std::string& name, int type, py::handle data) {
            o.setParameterArray(name, 3, type, data);
        })
        .def("unsetParameter", &Object::unsetParameter)
        .def("commitParameters", &Object::commitParameters)
        .def("release", &Object::release)
        .def_property_readonly("type", [](const Object& o) { return int(o.type()); })
        .def_property_readonly("subtype", &Object::subtype)
        .def("__repr__", &Object::repr);

    py::class_<Frame, Object, std::shared_ptr<Frame>>(m, "Frame")
        .def("render", &Frame::render)
        .def("get", &Frame::get, py::arg("channel"))
        .def("map", &Frame::map)
        .def("unmap", &Frame::unmap)
        .def("readGPU", [](Frame&, uint64_t, const std::string&) {
            throw py::value_error("frame.readGPU(): this module has no CUDA; use frame.get(channel)");
        });

    py::class_<Device> device(m, "Device");
    auto subtyped = [&device](const char* name, ANARIDataType type) {
        device.def(name, [type](Device& d, const std::string& subtype) { return d.newObject(type, subtype); },
                   py::arg("subtype"));
    };
    auto plain = [&device](const char* name, ANARIDataType type) {
        device.def(name, [type](Device& d) { return d.newObject(type, ""); });
    };
    subtyped("newCamera", ANARI_CAMERA);
    subtyped("newGeometry", ANARI_GEOMETRY);
    subtyped("newInstance", ANARI_INSTANCE);
    subtyped("newLight", ANARI_LIGHT);
    subtyped("newMaterial", ANARI_MATERIAL);
    subtyped("newRenderer", ANARI_RENDERER);
    subtyped("newSampler", ANARI_SAMPLER);
    subtyped("newSpatialField", ANARI_SPATIAL_FIELD);
    subtyped("newVolume", ANARI_VOLUME);
    plain("newSurface", ANARI_SURFACE);
    plain("newWorld", ANARI_WORLD);
    plain("newFrame", ANARI_FRAME);
    device.def("newGroup", &Device::newGroup, py::arg("members") = py::list())
        .def("newArray", [](Device& d, int type, py::handle data) { return newArray(d.session, 1, type, data); })
        .def("newArray1D", [](Device& d, int type, py::handle data) { return newArray(d.session, 1, type, data); })
        .def("newArray2D", [](Device& d, int type, py::handle data) { return newArray(d.session, 2, type, data); })
        .def("newArray3D", [](Device& d, int type, py::handle data) { return newArray(d.session, 3, type, data); })
        .def("setParameter", &Device::setParameter, py::arg("name"), py::arg("type"), py::arg("value"))
        .def("commitParameters", &Device::commitParameters)
        .def("getObjectSubtypes", &objectSubtypes, py::arg("type"))
        .def("getObjectInfo", &objectInfo, py::arg("type"), py::arg("subtype") = "default")
        .def("getParameterInfo", &parameterInfo, py::arg("type"), py::arg("subtype"), py::arg("paramName"),
             py::arg("paramType"));
}
