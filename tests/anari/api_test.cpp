// ANARI API behaviour of the Ripple device through the public C API and Ripple's loader: reference counts
// (the device's own included), parameters of the wrong type and unknown subtypes reported, array deleters
// called exactly once, mapping, introspection answers and world bounds.
#include "anari/anari.h"
#include "tests/support/StatusLog.h"

#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

using ripple::test::StatusLog;

namespace {

struct Fixture {
    StatusLog log;
    ANARILibrary library = nullptr;
    ANARIDevice device = nullptr;

    Fixture() {
        library = anariLoadLibrary("ripple", &StatusLog::callback, &log);
        REQUIRE_MESSAGE(library, log.dump());
        device = anariNewDevice(library, "default");
        REQUIRE(device);
    }
    ~Fixture() {
        if (device) anariRelease(device, device);
        anariUnloadLibrary(library);
    }
};

bool listContains(const char** list, const char* name) {
    for (; list && *list; ++list)
        if (std::strcmp(*list, name) == 0) return true;
    return false;
}

struct DeleterRecord {
    int calls = 0;
    const void* memory = nullptr;
};

void countingDeleter(const void* userPtr, const void* appMemory) {
    auto* record = const_cast<DeleterRecord*>(static_cast<const DeleterRecord*>(userPtr));
    ++record->calls;
    record->memory = appMemory;
}

}  // namespace

TEST_CASE("device handle is reference counted; releasing NULL does nothing") {
    Fixture f;
    anariRetain(f.device, f.device);
    anariRelease(f.device, f.device);  // back to one reference: still usable
    ANARIWorld world = anariNewWorld(f.device);
    CHECK(world);
    anariRelease(f.device, world);
    anariRelease(f.device, nullptr);
    CHECK(f.log.problems() == 0);

    int32_t version = 0;
    CHECK(anariGetProperty(f.device, f.device, "version", ANARI_INT32, &version, sizeof(version), ANARI_WAIT) == 1);
    CHECK(version >= 1);
}

TEST_CASE("device parameters statusCallback and statusCallbackUserData (an ANARI_VOID_POINTER: the pointer itself)") {
    Fixture f;
    StatusLog other;
    const ANARIStatusCallback callback = &StatusLog::callback;
    anariSetParameter(f.device, f.device, "statusCallback", ANARI_STATUS_CALLBACK, &callback);
    // The SDK's C++ wrapper and helium pass a VOID_POINTER's value as `mem` itself, not its address.
    anariSetParameter(f.device, f.device, "statusCallbackUserData", ANARI_VOID_POINTER, &other);
    anariCommitParameters(f.device, f.device);
    ANARIGeometry teapot = anariNewGeometry(f.device, "teapot");
    anariCommitParameters(f.device, teapot);
    CHECK_MESSAGE(other.count({"teapot"}) >= 1, other.dump());
    CHECK(f.log.count({"teapot"}) == 0);
    anariRelease(f.device, teapot);
}

TEST_CASE("unknown subtypes and wrong parameter types are reported, naming object and parameter") {
    Fixture f;
    ANARIGeometry teapot = anariNewGeometry(f.device, "teapot");
    CHECK(teapot);  // an object that renders nothing, never NULL
    anariCommitParameters(f.device, teapot);
    CHECK(f.log.count({"teapot"}) >= 1);

    ANARICamera camera = anariNewCamera(f.device, "perspective");
    const int32_t notAFloat = 3;
    anariSetParameter(f.device, camera, "fovy", ANARI_INT32, &notAFloat);
    anariCommitParameters(f.device, camera);
    CHECK_MESSAGE(f.log.count({"fovy", "ANARI_INT32", "ANARI_FLOAT32"}) == 1, f.log.dump());

    const float value = 1.0f;
    anariSetParameter(f.device, camera, "notAParameter", ANARI_FLOAT32, &value);
    anariCommitParameters(f.device, camera);
    anariCommitParameters(f.device, camera);  // warned once, not at every commit
    CHECK_MESSAGE(f.log.count({"notAParameter"}) == 1, f.log.dump());

    // A handle of one kind passed under another kind's type: the message names what the object really is.
    ANARIWorld notACamera = anariNewWorld(f.device);
    ANARIFrame frame = anariNewFrame(f.device);
    anariSetParameter(f.device, frame, "camera", ANARI_CAMERA, &notACamera);
    anariCommitParameters(f.device, frame);
    CHECK_MESSAGE(f.log.count({"parameter 'camera' was set as ANARI_CAMERA but names world", "(ANARI_WORLD)",
                               "expected ANARI_CAMERA"}) == 1,
                  f.log.dump());
    anariRelease(f.device, frame);
    anariRelease(f.device, notACamera);

    anariNewObject(f.device, "teapotType", "x");
    CHECK(f.log.count({"teapotType"}) == 1);
    anariCommitParameters(f.device, nullptr);
    CHECK(f.log.count({"NULL"}) >= 1);
    anariRelease(f.device, camera);
    anariRelease(f.device, teapot);
}

TEST_CASE("bad data is refused at commit: one error naming object, parameter, first bad element and count") {
    Fixture f;
    const float nan = std::nanf("");
    const float inf = INFINITY;
    const std::vector<float> positions = {0, 0, 0, nan, 0, 0, 1, inf, 0, 0, 1, 0};  // vertices 1 and 2 of 4 are bad
    ANARIArray1D vertices = anariNewArray1D(f.device, positions.data(), nullptr, nullptr, ANARI_FLOAT32_VEC3, 4);
    ANARIGeometry mesh = anariNewGeometry(f.device, "triangle");
    anariSetParameter(f.device, mesh, "vertex.position", ANARI_ARRAY1D, &vertices);
    anariCommitParameters(f.device, mesh);
    CHECK_MESSAGE(f.log.count({"geometry 'triangle'", "'vertex.position' is not finite: element 1 holds NaN; 2 of 4 "
                                                      "elements hold NaN or Inf"}) == 1,
                  f.log.dump());

    std::vector<uint32_t> index = {0, 1, 2, 0, 2, 4, 4, 0, 9};  // triangles 1 and 2 of 3 reach past vertex 3
    const std::vector<float> finite(12, 0.5f);
    ANARIArray1D goodVertices = anariNewArray1D(f.device, finite.data(), nullptr, nullptr, ANARI_FLOAT32_VEC3, 4);
    ANARIArray1D triangles = anariNewArray1D(f.device, index.data(), nullptr, nullptr, ANARI_UINT32_VEC3, 3);
    anariSetParameter(f.device, mesh, "vertex.position", ANARI_ARRAY1D, &goodVertices);
    anariSetParameter(f.device, mesh, "primitive.index", ANARI_ARRAY1D, &triangles);
    anariCommitParameters(f.device, mesh);
    CHECK_MESSAGE(f.log.count({"'primitive.index' element 1 refers to vertex 4, but there are 4 vertices; 2 of 3 "
                               "elements are out of range"}) == 1,
                  f.log.dump());

    // Two bad parameters, one error: the first problem found invalidates the object.
    f.log.clear();
    ANARILight light = anariNewLight(f.device, "point");
    const float position[3] = {0.0f, -inf, 0.0f};
    anariSetParameter(f.device, light, "position", ANARI_FLOAT32_VEC3, position);
    anariSetParameter(f.device, light, "intensity", ANARI_FLOAT32, &nan);
    anariCommitParameters(f.device, light);
    CHECK_MESSAGE(f.log.count({}) == 1, f.log.dump());
    CHECK(f.log.count({"light 'point'", "'intensity' is not finite: it holds NaN"}) == 1);

    anariRelease(f.device, light);
    anariRelease(f.device, mesh);
    anariRelease(f.device, triangles);
    anariRelease(f.device, goodVertices);
    anariRelease(f.device, vertices);
}

TEST_CASE("array deleters run exactly once, when the last reference goes") {
    Fixture f;
    static const float positions[] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    DeleterRecord record;
    ANARIArray1D array = anariNewArray1D(f.device, positions, &countingDeleter, &record, ANARI_FLOAT32_VEC3, 3);
    ANARIGeometry geometry = anariNewGeometry(f.device, "triangle");
    anariSetParameter(f.device, geometry, "vertex.position", ANARI_ARRAY1D, &array);
    anariRelease(f.device, array);  // the geometry still holds it
    CHECK(record.calls == 0);
    anariRelease(f.device, geometry);
    CHECK(record.calls == 1);
    CHECK(record.memory == positions);
}

TEST_CASE("arrays: managed memory, mapping, parameter arrays and object elements") {
    Fixture f;
    ANARIArray1D managed = anariNewArray1D(f.device, nullptr, nullptr, nullptr, ANARI_FLOAT32, 4);
    auto* values = static_cast<float*>(anariMapArray(f.device, managed));
    REQUIRE(values);
    for (int i = 0; i < 4; ++i) values[i] = float(i);
    anariUnmapArray(f.device, managed);
    anariRelease(f.device, managed);

    ANARIGeometry spheres = anariNewGeometry(f.device, "sphere");
    uint64_t stride = 0;
    auto* centers = static_cast<float*>(
        anariMapParameterArray1D(f.device, spheres, "vertex.position", ANARI_FLOAT32_VEC3, 2, &stride));
    REQUIRE(centers);
    CHECK(stride == 12);
    const float data[] = {0, 0, 0, 2, 0, 0};
    std::memcpy(centers, data, sizeof(data));
    anariUnmapParameterArray(f.device, spheres, "vertex.position");
    const float radius = 0.5f;
    anariSetParameter(f.device, spheres, "radius", ANARI_FLOAT32, &radius);
    anariCommitParameters(f.device, spheres);

    // An array of surfaces keeps its elements alive after the application lets go of them.
    ANARISurface surface = anariNewSurface(f.device);
    anariSetParameter(f.device, surface, "geometry", ANARI_GEOMETRY, &spheres);
    ANARIMaterial material = anariNewMaterial(f.device, "matte");
    anariCommitParameters(f.device, material);
    anariSetParameter(f.device, surface, "material", ANARI_MATERIAL, &material);
    anariCommitParameters(f.device, surface);
    ANARIArray1D surfaces = anariNewArray1D(f.device, &surface, nullptr, nullptr, ANARI_SURFACE, 1);
    anariRelease(f.device, surface);
    anariRelease(f.device, material);
    anariRelease(f.device, spheres);

    ANARIWorld world = anariNewWorld(f.device);
    anariSetParameter(f.device, world, "surface", ANARI_ARRAY1D, &surfaces);
    anariRelease(f.device, surfaces);
    anariCommitParameters(f.device, world);

    float bounds[6] = {};
    REQUIRE(anariGetProperty(f.device, world, "bounds", ANARI_FLOAT32_BOX3, bounds, sizeof(bounds), ANARI_WAIT) == 1);
    const float expected[6] = {-0.5f, -0.5f, -0.5f, 2.5f, 0.5f, 0.5f};
    for (int i = 0; i < 6; ++i) CHECK(bounds[i] == doctest::Approx(expected[i]).epsilon(1e-6));
    anariRelease(f.device, world);
    CHECK_MESSAGE(f.log.problems() == 0, f.log.dump());
}

TEST_CASE("introspection answers from Ripple's own tables") {
    Fixture f;
    const char** deviceSubtypes = anariGetDeviceSubtypes(f.library);
    CHECK(listContains(deviceSubtypes, "default"));

    const char** geometries = anariGetObjectSubtypes(f.device, ANARI_GEOMETRY);
    for (const char* name : {"triangle", "quad", "sphere", "cylinder"}) CHECK_MESSAGE(listContains(geometries, name), name);
    CHECK(listContains(anariGetObjectSubtypes(f.device, ANARI_MATERIAL), "physicallyBased"));
    CHECK(listContains(anariGetObjectSubtypes(f.device, ANARI_LIGHT), "quad"));
    CHECK(listContains(anariGetObjectSubtypes(f.device, ANARI_CAMERA), "orthographic"));
    CHECK(listContains(anariGetObjectSubtypes(f.device, ANARI_RENDERER), "default"));

    const char** extensions = nullptr;
    REQUIRE(anariGetProperty(f.device, f.device, "extension", ANARI_STRING_LIST, &extensions, sizeof(extensions),
                             ANARI_WAIT) == 1);
    CHECK(listContains(extensions, "ANARI_KHR_GEOMETRY_SPHERE"));
    CHECK(listContains(extensions, "ANARI_KHR_CAMERA_PERSPECTIVE"));
    for (const char* implemented : {"ANARI_KHR_DATA_PARALLEL_MPI", "ANARI_KHR_FRAME_ACCUMULATION",
                                    "ANARI_KHR_DEVICE_SYNCHRONIZATION", "ANARI_KHR_FRAME_COMPLETION_CALLBACK"})
        CHECK_MESSAGE(listContains(extensions, implemented), implemented);
    int32_t idle = 0;  // KHR_DEVICE_SYNCHRONIZATION: nothing in flight, so idle at once
    CHECK(anariGetProperty(f.device, f.device, "waitIdle", ANARI_BOOL, &idle, sizeof(idle), ANARI_WAIT) == 1);
    CHECK(idle == 1);
    CHECK(listContains(extensions, "ANARI_KHR_SPATIAL_FIELD_STRUCTURED_REGULAR"));
    CHECK(listContains(extensions, "ANARI_KHR_VOLUME_TRANSFER_FUNCTION1D"));
    CHECK(listContains(anariGetDeviceExtensions(f.library, "default"), "ANARI_KHR_GEOMETRY_TRIANGLE"));

    const auto* parameters = static_cast<const ANARIParameter*>(
        anariGetObjectInfo(f.device, ANARI_GEOMETRY, "sphere", "parameter", ANARI_PARAMETER_LIST));
    REQUIRE(parameters);
    bool hasPosition = false;
    for (const ANARIParameter* p = parameters; p->name; ++p)
        hasPosition = hasPosition || (std::strcmp(p->name, "vertex.position") == 0 && p->type == ANARI_ARRAY1D);
    CHECK(hasPosition);

    const auto* fovy = static_cast<const float*>(
        anariGetParameterInfo(f.device, ANARI_CAMERA, "perspective", "fovy", ANARI_FLOAT32, "default", ANARI_FLOAT32));
    REQUIRE(fovy);
    CHECK(*fovy == doctest::Approx(M_PI / 3.0));
    CHECK(anariGetObjectInfo(f.device, ANARI_GEOMETRY, "teapot", "parameter", ANARI_PARAMETER_LIST) == nullptr);

    // The device's own parameters, with the values an application (ripple-view's renderer panel) may offer.
    const auto* traversals = static_cast<const char* const*>(anariGetParameterInfo(
        f.device, ANARI_DEVICE, "default", "traversal", ANARI_STRING, "value", ANARI_STRING_LIST));
    REQUIRE(traversals);
    std::vector<std::string> names;
    for (const char* const* t = traversals; *t; ++t) names.emplace_back(*t);
    CHECK(names == std::vector<std::string>{"auto", "software", "rayQuery"});
    CHECK(listContains(const_cast<const char**>(static_cast<const char* const*>(anariGetParameterInfo(
                           f.device, ANARI_DEVICE, "default", "rayExchange", ANARI_STRING, "value", ANARI_STRING_LIST))),
                       "ring"));
}

TEST_CASE("the loader reports a library that does not exist, naming it") {
    StatusLog log;
    ANARILibrary missing = anariLoadLibrary("no_such_ripple_library", &StatusLog::callback, &log);
    CHECK(missing == nullptr);
    CHECK(log.count({"no_such_ripple_library"}) >= 1);
}
