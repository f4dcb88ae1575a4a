// Loads libanari_library_ripple.so the way an external loader (the Khronos SDK's libanari) does: dlopen,
// the one exported symbol, then only virtual calls through the layout of anari/backend/*Interface.h.
// Renders a lit sphere that way and checks the pixels.
#include "anari/backend/DeviceInterface.h"
#include "anari/backend/LibraryInterface.h"
#include "tests/support/StatusLog.h"

#include <doctest/doctest.h>
#include <dlfcn.h>

#include <cmath>

using ripple::test::StatusLog;

namespace {

using NewLibrary = ANARILibrary (*)(void*, ANARIStatusCallback, const void*);

template <class T> void set(ripple::abi::DeviceInterface* d, void* object, const char* name, ANARIDataType type, const T& value) {
    d->setParameter(static_cast<ANARIObject>(object), name, type, &value);
}

}  // namespace

TEST_CASE("device library works through its one exported symbol and the virtual interface alone") {
    void* handle = dlopen(RIPPLE_DEVICE_LIBRARY_PATH, RTLD_LAZY | RTLD_LOCAL);
    REQUIRE_MESSAGE(handle, dlerror());
    auto newLibrary = reinterpret_cast<NewLibrary>(dlsym(handle, "anari_library_ripple_new_library"));
    REQUIRE(reinterpret_cast<void*>(newLibrary) != nullptr);
    // Nothing else is visible: the core's symbols stay inside the library.
    CHECK(dlsym(handle, "anariNewDevice") == static_cast<void*>(nullptr));

    StatusLog log;
    ANARILibrary libraryHandle = newLibrary(handle, &StatusLog::callback, &log);
    REQUIRE(libraryHandle);
    auto* library = ripple::abi::libraryFromHandle(libraryHandle);
    // The Khronos loader reads the dlopen handle at offset 8 when it unloads the library.
    CHECK(*reinterpret_cast<void**>(reinterpret_cast<char*>(libraryHandle) + 8) == handle);

    ANARIDevice deviceHandle = library->newDevice("default");
    REQUIRE(deviceHandle);
    auto* d = ripple::abi::deviceFromHandle(deviceHandle);

    const float center[3] = {0, 0, 0};
    ANARIArray1D centers = d->newArray1D(center, nullptr, nullptr, ANARI_FLOAT32_VEC3, 1);
    ANARIGeometry sphere = d->newGeometry("sphere");
    set(d, sphere, "vertex.position", ANARI_ARRAY1D, centers);
    set(d, sphere, "radius", ANARI_FLOAT32, 1.0f);
    d->commitParameters(sphere);
    ANARIMaterial material = d->newMaterial("matte");
    const float white[3] = {1, 1, 1};
    d->setParameter(material, "color", ANARI_FLOAT32_VEC3, white);
    d->commitParameters(material);
    ANARISurface surface = d->newSurface();
    set(d, surface, "geometry", ANARI_GEOMETRY, sphere);
    set(d, surface, "material", ANARI_MATERIAL, material);
    d->commitParameters(surface);
    ANARIArray1D surfaces = d->newArray1D(&surface, nullptr, nullptr, ANARI_SURFACE, 1);

    ANARILight light = d->newLight("directional");
    const float towardMinusZ[3] = {0, 0, -1};
    d->setParameter(light, "direction", ANARI_FLOAT32_VEC3, towardMinusZ);
    d->commitParameters(light);
    ANARIArray1D lights = d->newArray1D(&light, nullptr, nullptr, ANARI_LIGHT, 1);

    ANARIWorld world = d->newWorld();
    set(d, world, "surface", ANARI_ARRAY1D, surfaces);
    set(d, world, "light", ANARI_ARRAY1D, lights);
    d->commitParameters(world);

    ANARICamera camera = d->newCamera("perspective");
    const float eye[3] = {0, 0, 4}, forward[3] = {0, 0, -1}, up[3] = {0, 1, 0};
    d->setParameter(camera, "position", ANARI_FLOAT32_VEC3, eye);
    d->setParameter(camera, "direction", ANARI_FLOAT32_VEC3, forward);
    d->setParameter(camera, "up", ANARI_FLOAT32_VEC3, up);
    d->commitParameters(camera);
    ANARIRenderer renderer = d->newRenderer("default");
    const float background[4] = {0.25f, 0.5f, 0.75f, 1.0f};
    d->setParameter(renderer, "background", ANARI_FLOAT32_VEC4, background);
    set(d, renderer, "maxPathLength", ANARI_INT32, 1);
    d->commitParameters(renderer);

    ANARIFrame frame = d->newFrame();
    const uint32_t size[2] = {16, 16};
    d->setParameter(frame, "size", ANARI_UINT32_VEC2, size);
    set(d, frame, "channel.color", ANARI_DATA_TYPE, ANARI_FLOAT32_VEC4);
    set(d, frame, "world", ANARI_WORLD, world);
    set(d, frame, "camera", ANARI_CAMERA, camera);
    set(d, frame, "renderer", ANARI_RENDERER, renderer);
    d->commitParameters(frame);
    d->renderFrame(frame);
    CHECK(d->frameReady(frame, ANARI_WAIT) == 1);

    uint32_t width = 0, height = 0;
    ANARIDataType pixelType = ANARI_UNKNOWN;
    const auto* pixels = static_cast<const float*>(d->mapFrame(frame, "channel.color", &width, &height, &pixelType));
    REQUIRE(pixels);
    CHECK(width == 16);
    CHECK(height == 16);
    CHECK(pixelType == ANARI_FLOAT32_VEC4);
    // Corner: the background exactly. Centre: the sphere's front, lit head-on by irradiance 1:
    // radiance = albedo / pi * E * cos(0) = 1/pi (one sample per pixel still lands near the pole).
    CHECK(pixels[0] == doctest::Approx(0.25f));
    CHECK(pixels[2] == doctest::Approx(0.75f));
    const float* centerPixel = pixels + 4 * (8 * 16 + 8);
    CHECK(centerPixel[0] == doctest::Approx(1.0 / M_PI).epsilon(0.05));
    d->unmapFrame(frame, "channel.color");

    for (ANARIObject object : {static_cast<ANARIObject>(frame), static_cast<ANARIObject>(renderer),
                               static_cast<ANARIObject>(camera), static_cast<ANARIObject>(world),
                               static_cast<ANARIObject>(lights), static_cast<ANARIObject>(light),
                               static_cast<ANARIObject>(surfaces), static_cast<ANARIObject>(surface),
                               static_cast<ANARIObject>(material), static_cast<ANARIObject>(sphere),
                               static_cast<ANARIObject>(centers)})
        d->release(object);
    d->release(deviceHandle);  // the last reference: the device goes
    CHECK_MESSAGE(log.problems() == 0, log.dump());

    delete library;  // what anariUnloadLibrary does, before dlclose
    CHECK(dlclose(handle) == 0);
}
