// Every device and library function of libanari.so must reach the virtual method of the same name on the
// fake device library, with the same arguments, and hand back what the method returned.
#include "CallRecord.h"
#include "tests/support/StatusLog.h"

#include "anari/anari.h"

#include <doctest/doctest.h>

#include <string>
#include <vector>

using loadertest::asWord;

namespace {

// Recognisable argument values; the fake device never dereferences them.
template <class T>
T fake(uint64_t tag) {
    return reinterpret_cast<T>(uintptr_t(0xA000 + tag));
}

void fakeDeleter(const void*, const void*) {}

template <class... Args>
std::vector<uint64_t> words(Args... arguments) {
    return {asWord(arguments)...};
}

class FakeDeviceFixture {
public:
    FakeDeviceFixture() : log_(ripple::test::freshStaticStatusLog()) {
        library_ = anariLoadLibrary("loadertest", ripple::test::StatusLog::callback, &log_);
        REQUIRE(library_ != nullptr);
        device = anariNewDevice(library_, "default");
        REQUIRE(device != nullptr);
        access_ = reinterpret_cast<loadertest::CallRecordAccess>(
            anariDeviceGetProcAddress(device, loadertest::callRecordProcName));
        REQUIRE(static_cast<bool>(access_));
        callsSoFar_ = record().callCount;
    }
    ~FakeDeviceFixture() {
        if (device != nullptr) anariRelease(device, device);
        anariUnloadLibrary(library_);
    }

    const loadertest::CallRecord& record() const { return *access_(); }

    // Exactly one call reached `method`, with `arguments`, and it returned `returned`.
    void checkReached(const char* method, const std::vector<uint64_t>& arguments, uint64_t returned) {
        const loadertest::CallRecord& last = record();
        CHECK(last.callCount == callsSoFar_ + 1);
        callsSoFar_ = last.callCount;
        REQUIRE(last.method != nullptr);
        CHECK(std::string(last.method) == method);
        REQUIRE(last.argumentCount == int(arguments.size()));
        for (size_t index = 0; index < arguments.size(); ++index) {
            CAPTURE(index);
            CHECK(last.arguments[index] == arguments[index]);
        }
        CHECK(last.returned == returned);
    }
    template <class Result>
    void checkReturned(const char* method, const std::vector<uint64_t>& arguments, Result result) {
        CHECK(asWord(result) != 0);
        checkReached(method, arguments, asWord(result));
    }
    void checkNoCall() const { CHECK(record().callCount == callsSoFar_); }

    ANARILibrary library() const { return library_; }
    ANARIDevice device = nullptr;

private:
    ripple::test::StatusLog& log_;
    ANARILibrary library_ = nullptr;
    loadertest::CallRecordAccess access_ = nullptr;
    int callsSoFar_ = 0;
};

}  // namespace

TEST_CASE_FIXTURE(FakeDeviceFixture, "Array and object creation reach newArray*..newObject") {
    const void* memory = fake<const void*>(1);
    const void* user = fake<const void*>(2);
    checkReturned("newArray1D", words(memory, &fakeDeleter, user, ANARI_FLOAT32_VEC3, uint64_t(11)),
                  anariNewArray1D(device, memory, fakeDeleter, user, ANARI_FLOAT32_VEC3, 11));
    checkReturned("newArray2D", words(memory, &fakeDeleter, user, ANARI_UINT8, uint64_t(12), uint64_t(13)),
                  anariNewArray2D(device, memory, fakeDeleter, user, ANARI_UINT8, 12, 13));
    checkReturned("newArray3D",
                  words(memory, &fakeDeleter, user, ANARI_FLOAT64, uint64_t(1) << 40, uint64_t(15), uint64_t(16)),
                  anariNewArray3D(device, memory, fakeDeleter, user, ANARI_FLOAT64, uint64_t(1) << 40, 15, 16));
    const char* type = "subtypeName";
    checkReturned("newGeometry", words(type), anariNewGeometry(device, type));
    checkReturned("newMaterial", words(type), anariNewMaterial(device, type));
    checkReturned("newSampler", words(type), anariNewSampler(device, type));
    checkReturned("newSurface", words(), anariNewSurface(device));
    checkReturned("newSpatialField", words(type), anariNewSpatialField(device, type));
    checkReturned("newVolume", words(type), anariNewVolume(device, type));
    checkReturned("newLight", words(type), anariNewLight(device, type));
    checkReturned("newGroup", words(), anariNewGroup(device));
    checkReturned("newInstance", words(type), anariNewInstance(device, type));
    checkReturned("newWorld", words(), anariNewWorld(device));
    checkReturned("newCamera", words(type), anariNewCamera(device, type));
    checkReturned("newRenderer", words(type), anariNewRenderer(device, type));
    checkReturned("newFrame", words(), anariNewFrame(device));
    const char* objectType = "geometry";
    checkReturned("newObject", words(objectType, type), anariNewObject(device, objectType, type));
}

TEST_CASE_FIXTURE(FakeDeviceFixture, "Parameter and lifetime calls reach their methods") {
    const auto object = fake<ANARIObject>(3);
    const char* name = "parameterName";
    const void* value = fake<const void*>(4);
    uint64_t stride = 0;
    anariSetParameter(device, object, name, ANARI_FLOAT32_MAT4, value);
    checkReached("setParameter", words(object, name, ANARI_FLOAT32_MAT4, value), 0);
    anariUnsetParameter(device, object, name);
    checkReached("unsetParameter", words(object, name), 0);
    anariUnsetAllParameters(device, object);
    checkReached("unsetAllParameters", words(object), 0);
    checkReturned("mapParameterArray1D", words(object, name, ANARI_INT32, uint64_t(21), &stride),
                  anariMapParameterArray1D(device, object, name, ANARI_INT32, 21, &stride));
    checkReturned("mapParameterArray2D", words(object, name, ANARI_INT32, uint64_t(21), uint64_t(22), &stride),
                  anariMapParameterArray2D(device, object, name, ANARI_INT32, 21, 22, &stride));
    checkReturned("mapParameterArray3D",
                  words(object, name, ANARI_INT32, uint64_t(21), uint64_t(22), uint64_t(23), &stride),
                  anariMapParameterArray3D(device, object, name, ANARI_INT32, 21, 22, 23, &stride));
    anariUnmapParameterArray(device, object, name);
    checkReached("unmapParameterArray", words(object, name), 0);
    anariCommitParameters(device, object);
    checkReached("commitParameters", words(object), 0);
    anariRetain(device, object);
    checkReached("retain", words(object), 0);
    anariRelease(device, object);
    checkReached("release", words(object), 0);
    anariRelease(device, nullptr);  // the device decides what a NULL object means
    checkReached("release", words(ANARIObject{nullptr}), 0);
}

TEST_CASE_FIXTURE(FakeDeviceFixture, "Array, property and introspection calls reach their methods") {
    const auto array = fake<ANARIArray>(5);
    checkReturned("mapArray", words(array), anariMapArray(device, array));
    anariUnmapArray(device, array);
    checkReached("unmapArray", words(array), 0);

    const auto object = fake<ANARIObject>(6);
    const char* property = "bounds";
    float bounds[6];
    checkReturned("getProperty", words(object, property, ANARI_FLOAT32_BOX3, bounds, uint64_t(sizeof bounds), 1u),
                  anariGetProperty(device, object, property, ANARI_FLOAT32_BOX3, bounds, sizeof bounds, ANARI_WAIT));
    checkReturned("getObjectSubtypes", words(ANARI_GEOMETRY), anariGetObjectSubtypes(device, ANARI_GEOMETRY));
    const char* subtype = "sphere";
    const char* info = "description";
    checkReturned("getObjectInfo", words(ANARI_GEOMETRY, subtype, info, ANARI_STRING),
                  anariGetObjectInfo(device, ANARI_GEOMETRY, subtype, info, ANARI_STRING));
    const char* parameter = "vertex.position";
    checkReturned("getParameterInfo",
                  words(ANARI_GEOMETRY, subtype, parameter, ANARI_ARRAY1D, info, ANARI_STRING),
                  anariGetParameterInfo(device, ANARI_GEOMETRY, subtype, parameter, ANARI_ARRAY1D, info, ANARI_STRING));
}

TEST_CASE_FIXTURE(FakeDeviceFixture, "Frame calls reach their methods") {
    const auto frame = fake<ANARIFrame>(7);
    const char* channel = "channel.color";
    uint32_t width = 0;
    uint32_t height = 0;
    ANARIDataType pixelType = ANARI_UNKNOWN;
    checkReturned("mapFrame", words(frame, channel, &width, &height, &pixelType),
                  anariMapFrame(device, frame, channel, &width, &height, &pixelType));
    anariUnmapFrame(device, frame, channel);
    checkReached("unmapFrame", words(frame, channel), 0);
    anariRenderFrame(device, frame);
    checkReached("renderFrame", words(frame), 0);
    checkReturned("frameReady", words(frame, 0u), anariFrameReady(device, frame, ANARI_NO_WAIT));
    anariDiscardFrame(device, frame);
    checkReached("discardFrame", words(frame), 0);
    const char* function = "noSuchExtensionFunction";
    CHECK_FALSE(static_cast<bool>(anariDeviceGetProcAddress(device, function)));
    checkReached("getProcAddress", words(function), 0);
}

TEST_CASE_FIXTURE(FakeDeviceFixture, "Library calls reach their methods") {
    const char* subtype = "default";
    checkReturned("getDeviceSubtypes", words(), anariGetDeviceSubtypes(library()));
    checkReturned("getDeviceExtensions", words(subtype), anariGetDeviceExtensions(library(), subtype));
    const char* module = "moduleName";
    anariLoadModule(library(), module);
    checkReached("loadModule", words(module), 0);
    anariUnloadModule(library(), module);
    checkReached("unloadModule", words(module), 0);
    ANARIParameterValue initializers[] = {{nullptr, ANARI_UNKNOWN, nullptr}};
    ANARIDevice second = anariNewInitializedDevice(library(), subtype, initializers);
    checkReturned("newInitializedDevice", words(subtype, &initializers[0]), second);
    CHECK(record().liveDevices == 2);
    anariRelease(second, second);  // the fake deletes a device released through itself
    checkReached("release", words(second), 0);
    CHECK(record().liveDevices == 1);
}

TEST_CASE_FIXTURE(FakeDeviceFixture, "NULL device handles are ignored: no call, NULL or 0 returned") {
    const auto object = fake<ANARIObject>(8);
    const auto frame = fake<ANARIFrame>(9);
    uint64_t stride = 0;
    uint32_t size = 0;
    ANARIDataType type = ANARI_UNKNOWN;
    CHECK(anariNewArray1D(nullptr, nullptr, nullptr, nullptr, ANARI_FLOAT32, 1) == nullptr);
    CHECK(anariNewArray2D(nullptr, nullptr, nullptr, nullptr, ANARI_FLOAT32, 1, 1) == nullptr);
    CHECK(anariNewArray3D(nullptr, nullptr, nullptr, nullptr, ANARI_FLOAT32, 1, 1, 1) == nullptr);
    CHECK(anariNewGeometry(nullptr, "sphere") == nullptr);
    CHECK(anariNewMaterial(nullptr, "matte") == nullptr);
    CHECK(anariNewSampler(nullptr, "image2D") == nullptr);
    CHECK(anariNewSurface(nullptr) == nullptr);
    CHECK(anariNewSpatialField(nullptr, "structuredRegular") == nullptr);
    CHECK(anariNewVolume(nullptr, "transferFunction1D") == nullptr);
    CHECK(anariNewLight(nullptr, "directional") == nullptr);
    CHECK(anariNewGroup(nullptr) == nullptr);
    CHECK(anariNewInstance(nullptr, "transform") == nullptr);
    CHECK(anariNewWorld(nullptr) == nullptr);
    CHECK(anariNewCamera(nullptr, "perspective") == nullptr);
    CHECK(anariNewRenderer(nullptr, "default") == nullptr);
    CHECK(anariNewFrame(nullptr) == nullptr);
    CHECK(anariNewObject(nullptr, "geometry", "sphere") == nullptr);
    anariSetParameter(nullptr, object, "name", ANARI_FLOAT32, &stride);
    anariUnsetParameter(nullptr, object, "name");
    anariUnsetAllParameters(nullptr, object);
    CHECK(anariMapParameterArray1D(nullptr, object, "name", ANARI_FLOAT32, 1, &stride) == nullptr);
    CHECK(anariMapParameterArray2D(nullptr, object, "name", ANARI_FLOAT32, 1, 1, &stride) == nullptr);
    CHECK(anariMapParameterArray3D(nullptr, object, "name", ANARI_FLOAT32, 1, 1, 1, &stride) == nullptr);
    anariUnmapParameterArray(nullptr, object, "name");
    anariCommitParameters(nullptr, object);
    anariRelease(nullptr, object);
    anariRetain(nullptr, object);
    CHECK(anariMapArray(nullptr, fake<ANARIArray>(10)) == nullptr);
    anariUnmapArray(nullptr, fake<ANARIArray>(10));
    CHECK(anariGetProperty(nullptr, object, "bounds", ANARI_FLOAT32_BOX3, &stride, 8, ANARI_WAIT) == 0);
    CHECK(anariGetObjectSubtypes(nullptr, ANARI_GEOMETRY) == nullptr);
    CHECK(anariGetObjectInfo(nullptr, ANARI_GEOMETRY, "sphere", "description", ANARI_STRING) == nullptr);
    CHECK(anariGetParameterInfo(nullptr, ANARI_GEOMETRY, "sphere", "radius", ANARI_FLOAT32, "default",
                                ANARI_FLOAT32) == nullptr);
    CHECK(anariMapFrame(nullptr, frame, "channel.color", &size, &size, &type) == nullptr);
    anariUnmapFrame(nullptr, frame, "channel.color");
    anariRenderFrame(nullptr, frame);
    CHECK(anariFrameReady(nullptr, frame, ANARI_WAIT) == 0);
    anariDiscardFrame(nullptr, frame);
    CHECK_FALSE(static_cast<bool>(anariDeviceGetProcAddress(nullptr, loadertest::callRecordProcName)));
    checkNoCall();
}

TEST_CASE_FIXTURE(FakeDeviceFixture, "An exception thrown by the device stays inside the loader") {
    const auto frame = fake<ANARIFrame>(11);
    CHECK(anariFrameReady(device, frame, loadertest::throwingWaitMask) == 0);
    checkNoCall();  // it threw before recording
    anariRenderFrame(device, frame);  // the device is still usable
    checkReached("renderFrame", words(frame), 0);
}

TEST_CASE_FIXTURE(FakeDeviceFixture, "Releasing the device through itself deletes it") {
    CHECK(record().liveDevices == 1);
    anariRelease(device, device);
    checkReached("release", words(device), 0);
    CHECK(record().liveDevices == 0);
    device = nullptr;
}
