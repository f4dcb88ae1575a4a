// Object and array lifetime as real applications use it (the Khronos SDK's tools and CTS do exactly this):
// arrays filled from temporary buffers that are released and freed before the objects using them are
// committed; objects released while still inside arrays; handles released twice or used after release;
// array sizes that overflow. Everything goes through the public C API.
#include "tests/anari/RenderSession.h"

#include <doctest/doctest.h>

#include <cstring>
#include <memory>
#include <vector>

using ripple::test::Image;
using ripple::test::RenderSession;

namespace {

// Fills a buffer the way freed-and-reused memory looks to a device that kept the pointer: the bytes of
// "vert" everywhere (as an index, 1953654134; as a float, 7.7e31).
template <class T>
void scribble(std::vector<T>& values) {
    auto* bytes = reinterpret_cast<uint8_t*>(values.data());
    for (size_t i = 0; i < values.size() * sizeof(T); ++i) bytes[i] = uint8_t("vert"[i % 4]);
}

// A shared array on application memory, as applications make them from a std::vector.
template <class T>
ANARIArray1D sharedArray(ANARIDevice device, ANARIDataType type, const std::vector<T>& values) {
    return anariNewArray1D(device, values.data(), nullptr, nullptr, type, values.size());
}

// Builds a small scene (a floor, a sphere, an instanced triangle, a light) from shared arrays on
// temporary buffers, and returns only the frame. With `freeEarly`, every array is released right after it
// is set and its memory scribbled over and freed before anything is committed, and every object but the
// frame is released before rendering; otherwise all stay alive until the end of the test.
struct TemporaryScene {
    std::vector<std::unique_ptr<std::vector<uint8_t>>> keptBuffers;
    std::vector<ANARIObject> keptObjects;
};

ANARIFrame buildScene(RenderSession& s, bool freeEarly, TemporaryScene& kept) {
    ANARIDevice d = s.device;
    auto own = [&](auto handle) {
        if (!freeEarly) kept.keptObjects.push_back(handle);
        return handle;
    };
    // Sets a shared array from a temporary vector; with freeEarly the array is released and the memory
    // scribbled over and freed at once, otherwise the data lives in a buffer kept to the end.
    auto setArray = [&](ANARIObject object, const char* name, ANARIDataType type, auto values) {
        const void* memory = values.data();
        if (!freeEarly) {
            auto bytes = std::make_unique<std::vector<uint8_t>>(values.size() * sizeof(values[0]));
            std::memcpy(bytes->data(), values.data(), bytes->size());
            memory = bytes->data();
            kept.keptBuffers.push_back(std::move(bytes));
        }
        ANARIArray1D array = anariNewArray1D(d, memory, nullptr, nullptr, type, values.size());
        anariSetParameter(d, object, name, ANARI_ARRAY1D, &array);
        if (freeEarly) {
            anariRelease(d, array);
            scribble(values);
        } else {
            kept.keptObjects.push_back(array);
        }
    };

    ANARIGeometry floor = own(anariNewGeometry(d, "triangle"));
    setArray(floor, "vertex.position", ANARI_FLOAT32_VEC3,
             std::vector<glm::vec3>{{-3, 0, -3}, {3, 0, -3}, {3, 0, 3}, {-3, 0, 3}});
    setArray(floor, "primitive.index", ANARI_UINT32_VEC3, std::vector<glm::uvec3>{{0, 2, 1}, {0, 3, 2}});
    anariCommitParameters(d, floor);

    ANARIGeometry ball = own(anariNewGeometry(d, "sphere"));
    setArray(ball, "vertex.position", ANARI_FLOAT32_VEC3, std::vector<glm::vec3>{{0, 1, 0}});
    setArray(ball, "vertex.radius", ANARI_FLOAT32, std::vector<float>{1.0f});
    anariCommitParameters(d, ball);

    ANARIGeometry triangle = own(anariNewGeometry(d, "triangle"));
    setArray(triangle, "vertex.position", ANARI_FLOAT32_VEC3,
             std::vector<glm::vec3>{{-1, 0, 0}, {1, 0, 0}, {0, 1.5f, 0}});
    anariCommitParameters(d, triangle);

    auto surfaceOf = [&](ANARIGeometry geometry, glm::vec3 color) {
        ANARIMaterial material = own(anariNewMaterial(d, "matte"));
        anariSetParameter(d, material, "color", ANARI_FLOAT32_VEC3, &color);
        anariCommitParameters(d, material);
        ANARISurface surface = own(anariNewSurface(d));
        anariSetParameter(d, surface, "geometry", ANARI_GEOMETRY, &geometry);
        anariSetParameter(d, surface, "material", ANARI_MATERIAL, &material);
        anariCommitParameters(d, surface);
        return surface;
    };
    ANARISurface floorSurface = surfaceOf(floor, {0.8f, 0.8f, 0.8f});
    ANARISurface ballSurface = surfaceOf(ball, {0.8f, 0.2f, 0.1f});
    ANARISurface triangleSurface = surfaceOf(triangle, {0.1f, 0.3f, 0.9f});

    // The triangle sits in a group placed by an instance: object arrays on temporary handle buffers too.
    ANARIGroup group = own(anariNewGroup(d));
    setArray(group, "surface", ANARI_SURFACE, std::vector<ANARISurface>{triangleSurface});
    anariCommitParameters(d, group);
    ANARIInstance instance = own(anariNewInstance(d, "transform"));
    const glm::mat4 transform{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, -2, 0, -1.5f, 1};
    anariSetParameter(d, instance, "group", ANARI_GROUP, &group);
    anariSetParameter(d, instance, "transform", ANARI_FLOAT32_MAT4, &transform);
    anariCommitParameters(d, instance);

    ANARILight light = own(anariNewLight(d, "directional"));
    const glm::vec3 direction{-0.3f, -1.0f, -0.5f};
    const float irradiance = 2.5f;
    anariSetParameter(d, light, "direction", ANARI_FLOAT32_VEC3, &direction);
    anariSetParameter(d, light, "irradiance", ANARI_FLOAT32, &irradiance);
    anariCommitParameters(d, light);

    ANARIWorld world = own(anariNewWorld(d));
    setArray(world, "surface", ANARI_SURFACE, std::vector<ANARISurface>{floorSurface, ballSurface});
    setArray(world, "instance", ANARI_INSTANCE, std::vector<ANARIInstance>{instance});
    setArray(world, "light", ANARI_LIGHT, std::vector<ANARILight>{light});
    if (freeEarly) {
        // The application lets go of everything the world holds before the world is even committed.
        for (ANARIObject object : {ANARIObject(floor), ANARIObject(ball), ANARIObject(triangle),
                                   ANARIObject(floorSurface), ANARIObject(ballSurface), ANARIObject(triangleSurface),
                                   ANARIObject(group), ANARIObject(instance), ANARIObject(light)})
            anariRelease(d, object);
    }
    anariCommitParameters(d, world);

    ANARICamera camera = own(anariNewCamera(d, "perspective"));
    const glm::vec3 position{0, 3, 7}, view = glm::normalize(glm::vec3{0, -2.2f, -7}), up{0, 1, 0};
    const float aspect = 1.0f;
    anariSetParameter(d, camera, "position", ANARI_FLOAT32_VEC3, &position);
    anariSetParameter(d, camera, "direction", ANARI_FLOAT32_VEC3, &view);
    anariSetParameter(d, camera, "up", ANARI_FLOAT32_VEC3, &up);
    anariSetParameter(d, camera, "aspect", ANARI_FLOAT32, &aspect);
    anariCommitParameters(d, camera);

    ANARIRenderer renderer = own(anariNewRenderer(d, "default"));
    const int32_t samples = 4, pathLength = 3;
    anariSetParameter(d, renderer, "pixelSamples", ANARI_INT32, &samples);
    anariSetParameter(d, renderer, "maxPathLength", ANARI_INT32, &pathLength);
    anariCommitParameters(d, renderer);

    ANARIFrame frame = anariNewFrame(d);
    const glm::uvec2 size{48, 48};
    const ANARIDataType colorType = ANARI_FLOAT32_VEC4;
    anariSetParameter(d, frame, "size", ANARI_UINT32_VEC2, &size);
    anariSetParameter(d, frame, "channel.color", ANARI_DATA_TYPE, &colorType);
    anariSetParameter(d, frame, "world", ANARI_WORLD, &world);
    anariSetParameter(d, frame, "camera", ANARI_CAMERA, &camera);
    anariSetParameter(d, frame, "renderer", ANARI_RENDERER, &renderer);
    anariCommitParameters(d, frame);
    if (freeEarly)
        for (ANARIObject object : {ANARIObject(world), ANARIObject(camera), ANARIObject(renderer)})
            anariRelease(d, object);
    return frame;
}

Image renderOnce(RenderSession& s, ANARIFrame frame) {
    anariRenderFrame(s.device, frame);
    anariFrameReady(s.device, frame, ANARI_WAIT);
    return s.mapped(frame);
}

}  // namespace

TEST_CASE("shared arrays released and freed early render exactly like arrays kept alive (privatization)") {
    Image kept, freed;
    {
        RenderSession s;
        TemporaryScene alive;
        ANARIFrame frame = buildScene(s, false, alive);
        kept = renderOnce(s, frame);
        anariRelease(s.device, frame);
        for (ANARIObject object : alive.keptObjects) anariRelease(s.device, object);
        CHECK_MESSAGE(s.log.problems() == 0, s.log.dump());
    }
    {
        RenderSession s;
        TemporaryScene nothing;
        ANARIFrame frame = buildScene(s, true, nothing);
        freed = renderOnce(s, frame);
        // A second frame after everything else is long gone: the frame alone keeps the scene alive.
        Image again = renderOnce(s, frame);
        CHECK(again.width == freed.width);
        anariRelease(s.device, frame);
        CHECK_MESSAGE(s.log.problems() == 0, s.log.dump());
    }
    REQUIRE(kept.width == 48);
    REQUIRE(freed.width == 48);
    // Same scene, same random numbers: every pixel equal, and the scene is not empty.
    size_t differing = 0, lit = 0;
    for (size_t i = 0; i < kept.linear.size(); ++i) {
        differing += kept.linear[i] != freed.linear[i] ? 1 : 0;
        lit += kept.linear[i].r > 0.2f ? 1 : 0;
    }
    CHECK(differing == 0);
    CHECK(lit > 200);
}

TEST_CASE("a shared array's application memory is no longer read once the application released it") {
    RenderSession s;
    std::vector<glm::vec3> centers{{0, 0, 0}, {2, 0, 0}};
    ANARIArray1D array = sharedArray(s.device, ANARI_FLOAT32_VEC3, centers);
    ANARIGeometry spheres = s.keep(anariNewGeometry(s.device, "sphere"));
    anariSetParameter(s.device, spheres, "vertex.position", ANARI_ARRAY1D, &array);
    const float radius = 0.5f;
    anariSetParameter(s.device, spheres, "radius", ANARI_FLOAT32, &radius);
    anariRelease(s.device, array);
    centers[1] = {1e30f, 1e30f, 1e30f};  // the application reuses its memory
    anariCommitParameters(s.device, spheres);
    ANARISurface surface = s.surface(spheres, s.matte({1, 1, 1}));
    ANARIWorld world = s.world({surface}, {});
    float bounds[6] = {};
    REQUIRE(anariGetProperty(s.device, world, "bounds", ANARI_FLOAT32_BOX3, bounds, sizeof(bounds), ANARI_WAIT) == 1);
    CHECK(bounds[3] == doctest::Approx(2.5f));
    CHECK_MESSAGE(s.log.problems() == 0, s.log.dump());
}

TEST_CASE("releasing an object twice, or using a released handle, is reported and touches nothing") {
    RenderSession s;
    SUBCASE("an object the device has already destroyed") {
        ANARIMaterial material = anariNewMaterial(s.device, "matte");
        anariRelease(s.device, material);
        anariRelease(s.device, material);
        CHECK_MESSAGE(s.log.count({"anariRelease", "not a live object of this device"}) == 1, s.log.dump());
        const float value = 1.0f;
        anariSetParameter(s.device, material, "opacity", ANARI_FLOAT32, &value);
        anariCommitParameters(s.device, material);
        CHECK_MESSAGE(s.log.count({"not a live object of this device"}) == 3, s.log.dump());
    }
    SUBCASE("an object still held inside the device (an array set on a geometry)") {
        const std::vector<float> radii{1.0f};
        ANARIArray1D array = sharedArray(s.device, ANARI_FLOAT32, radii);
        ANARIGeometry spheres = s.keep(anariNewGeometry(s.device, "sphere"));
        anariSetParameter(s.device, spheres, "vertex.radius", ANARI_ARRAY1D, &array);
        anariRelease(s.device, array);
        anariRelease(s.device, array);  // one too many: the geometry's reference must survive it
        CHECK_MESSAGE(s.log.count({"anariRelease", "released more often than created and retained"}) == 1,
                      s.log.dump());
        anariRetain(s.device, array);
        CHECK_MESSAGE(s.log.count({"anariRetain", "released by the application"}) == 1, s.log.dump());
    }
    SUBCASE("a handle that never came from this device") {
        int notAnObject = 0;
        anariRelease(s.device, reinterpret_cast<ANARIObject>(&notAnObject));
        anariCommitParameters(s.device, reinterpret_cast<ANARIObject>(0x1235));
        CHECK_MESSAGE(s.log.count({"not a live object of this device"}) == 2, s.log.dump());
    }
    SUBCASE("a released handle set as a parameter or placed in an array") {
        ANARIGeometry geometry = anariNewGeometry(s.device, "sphere");
        anariRelease(s.device, geometry);
        ANARISurface surface = s.keep(anariNewSurface(s.device));
        anariSetParameter(s.device, surface, "geometry", ANARI_GEOMETRY, &geometry);
        CHECK_MESSAGE(s.log.count({"parameter 'geometry'", "released"}) == 1, s.log.dump());
        ANARIArray1D surfaces = s.keep(anariNewArray1D(s.device, &geometry, nullptr, nullptr, ANARI_SURFACE, 1));
        CHECK(surfaces);
        CHECK_MESSAGE(s.log.count({"1 element(s) are not live objects", "element 0"}) == 1, s.log.dump());
    }
}

TEST_CASE("an object of the wrong type inside an object array is reported, not dropped silently") {
    RenderSession s;
    ANARICamera camera = s.keep(anariNewCamera(s.device, "perspective"));
    ANARISurface surface = s.surface(s.floor(), s.matte({1, 1, 1}));
    const std::vector<ANARIObject> handles{surface, camera};
    ANARIArray1D mixed = s.keep(anariNewArray1D(s.device, handles.data(), nullptr, nullptr, ANARI_SURFACE, 2));
    ANARIWorld world = s.keep(anariNewWorld(s.device));
    anariSetParameter(s.device, world, "surface", ANARI_ARRAY1D, &mixed);
    anariCommitParameters(s.device, world);
    CHECK_MESSAGE(s.log.count({"not of the array's type ANARI_SURFACE", "element 1", "camera 'perspective'"}) == 1,
                  s.log.dump());
    float bounds[6] = {};  // the surface that is one still renders
    CHECK(anariGetProperty(s.device, world, "bounds", ANARI_FLOAT32_BOX3, bounds, sizeof(bounds), ANARI_WAIT) == 1);
}

TEST_CASE("array sizes are 64-bit and overflow-checked; impossible managed arrays are refused") {
    RenderSession s;
    const uint64_t huge = uint64_t(1) << 22;  // 2^66 elements in three dimensions
    CHECK(anariNewArray3D(s.device, nullptr, nullptr, nullptr, ANARI_FLOAT32_VEC4, huge, huge, huge) == nullptr);
    CHECK_MESSAGE(s.log.count({"anariNewArray", "overflows 64 bits"}) == 1, s.log.dump());
    // 2^61 elements of 16 bytes: the element count fits, the byte size does not.
    CHECK(anariNewArray1D(s.device, nullptr, nullptr, nullptr, ANARI_FLOAT32_VEC4, uint64_t(1) << 61) == nullptr);
    CHECK_MESSAGE(s.log.count({"anariNewArray", "overflows 64 bits"}) == 2, s.log.dump());
    // 2^40 floats (4 TiB) fit in 64 bits but in no machine this runs on.
    CHECK(anariNewArray2D(s.device, nullptr, nullptr, nullptr, ANARI_FLOAT32, uint64_t(1) << 20, uint64_t(1) << 20) ==
          nullptr);
    CHECK_MESSAGE(s.log.count({"anariNewArray", "more than this machine's memory"}) == 1, s.log.dump());
    // Parameter arrays go the same way.
    ANARIGeometry geometry = s.keep(anariNewGeometry(s.device, "sphere"));
    uint64_t stride = 0;
    CHECK(anariMapParameterArray2D(s.device, geometry, "vertex.position", ANARI_FLOAT32_VEC3, uint64_t(1) << 40,
                                   uint64_t(1) << 40, &stride) == nullptr);
    CHECK_MESSAGE(s.log.count({"anariNewArray", "overflows 64 bits"}) == 3, s.log.dump());
}

TEST_CASE("KHR_DEVICE_SYNCHRONIZATION: waitIdle returns once the frame in flight has finished") {
    RenderSession s;
    ANARISurface floor = s.surface(s.floor(), s.matte({0.8f, 0.8f, 0.8f}));
    ANARIWorld world = s.world({floor}, {s.directional({0, -1, 0}, 1.0f)});
    ANARIFrame frame = s.frame(world, s.perspective({0, 4, 6}, {0, 0, 0}), s.renderer(16, 3), {64, 64},
                               ANARI_FLOAT32_VEC4);
    anariRenderFrame(s.device, frame);
    int32_t idle = 0;
    REQUIRE(anariGetProperty(s.device, s.device, "waitIdle", ANARI_BOOL, &idle, sizeof(idle), ANARI_WAIT) == 1);
    CHECK(idle == 1);
    CHECK(anariFrameReady(s.device, frame, ANARI_NO_WAIT) == 1);
}
