// Robustness group "API misuse": calls a careless or hostile application makes — array sizes that overflow,
// a release too many, handles used after release or never made by this device, objects of the wrong kind in
// object arrays, shared memory freed and scribbled over while the device still uses the array. Each case must
// be reported by a message naming what was wrong, and the frame must equal the frame without the misuse.
#include "apps/ripple-robustness/Robustness.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace ripple::robustness {
namespace {

constexpr float kSameImage = 1e-5f;  // deterministic renders: the same scene gives the same bits

struct MisuseCase {
    std::string name;
    std::string fragment;  // the message that must appear
    // Does the misuse; returns the surfaces to add to the good scene (those that must still render).
    std::function<std::vector<ANARISurface>(Harness&)> misuse;
    bool addsSphere = false;  // the frame must equal the good scene plus the second sphere
    bool quick = true;
};

// A second sphere whose centers come from application memory that is scribbled over and freed right after
// the array's release, before the geometry is committed: a device that read it later renders garbage.
ANARISurface sphereFromFreedMemory(Harness& h) {
    ANARIDevice d = h.device();
    auto centers = std::make_unique<std::vector<glm::vec3>>(std::vector<glm::vec3>{{1.0f, 0.0f, 0.0f}});
    ANARIArray1D array = anariNewArray1D(d, centers->data(), nullptr, nullptr, ANARI_FLOAT32_VEC3, 1);
    ANARIGeometry geometry = h.keep(anariNewGeometry(d, "sphere"));
    anariSetParameter(d, geometry, "vertex.position", ANARI_ARRAY1D, &array);
    const float radius = 0.5f;
    anariSetParameter(d, geometry, "radius", ANARI_FLOAT32, &radius);
    anariRelease(d, array);
    std::fill(centers->begin(), centers->end(), glm::vec3(7.7e31f));
    centers.reset();
    anariCommitParameters(d, geometry);
    return h.surface(geometry, h.matte({0.9f, 0.4f, 0.1f}));
}

ANARISurface secondSphere(Harness& h) {
    return h.surface(h.spheres({{1.0f, 0.0f, 0.0f}}, 0.5f), h.matte({0.9f, 0.4f, 0.1f}));
}

std::vector<MisuseCase> allCases() {
    std::vector<MisuseCase> cases;
    cases.push_back({"array of 2^22 x 2^22 x 2^22 FLOAT32_VEC4 (byte size overflows 64 bits)", "overflows 64 bits",
                     [](Harness& h) {
                         const uint64_t n = uint64_t(1) << 22;
                         h.keep(anariNewArray3D(h.device(), nullptr, nullptr, nullptr, ANARI_FLOAT32_VEC4, n, n, n));
                         return std::vector<ANARISurface>{};
                     }});
    cases.push_back({"managed array of 2^40 FLOAT32 (more than the machine's memory)", "more than this machine's memory",
                     [](Harness& h) {
                         h.keep(anariNewArray1D(h.device(), nullptr, nullptr, nullptr, ANARI_FLOAT32, uint64_t(1) << 40));
                         return std::vector<ANARISurface>{};
                     }});
    cases.push_back({"a material released twice (already destroyed)", "not a live object of this device",
                     [](Harness& h) {
                         ANARIMaterial material = anariNewMaterial(h.device(), "matte");
                         anariRelease(h.device(), material);
                         anariRelease(h.device(), material);
                         return std::vector<ANARISurface>{};
                     }});
    cases.push_back({"an array released twice while a geometry holds it", "released more often than created",
                     [](Harness& h) {
                         ANARIDevice d = h.device();
                         const std::vector<glm::vec3> centers{{1.0f, 0.0f, 0.0f}};
                         ANARIArray1D array = anariNewArray1D(d, nullptr, nullptr, nullptr, ANARI_FLOAT32_VEC3, 1);
                         *static_cast<glm::vec3*>(anariMapArray(d, array)) = centers[0];
                         anariUnmapArray(d, array);
                         ANARIGeometry geometry = h.keep(anariNewGeometry(d, "sphere"));
                         anariSetParameter(d, geometry, "vertex.position", ANARI_ARRAY1D, &array);
                         const float radius = 0.5f;
                         anariSetParameter(d, geometry, "radius", ANARI_FLOAT32, &radius);
                         anariRelease(d, array);
                         anariRelease(d, array);  // one too many: the geometry's reference must survive
                         anariCommitParameters(d, geometry);
                         return std::vector<ANARISurface>{h.surface(geometry, h.matte({0.9f, 0.4f, 0.1f}))};
                     },
                     true});
    cases.push_back({"a handle that never came from this device", "not a live object of this device",
                     [](Harness& h) {
                         int notAnObject = 0;
                         anariCommitParameters(h.device(), reinterpret_cast<ANARIObject>(&notAnObject));
                         return std::vector<ANARISurface>{};
                     }});
    cases.push_back({"a released geometry set on a surface", "names an object the application has released",
                     [](Harness& h) {
                         ANARIGeometry geometry = anariNewGeometry(h.device(), "sphere");
                         anariRelease(h.device(), geometry);
                         ANARISurface surface = h.keep(anariNewSurface(h.device()));
                         anariSetParameter(h.device(), surface, "geometry", ANARI_GEOMETRY, &geometry);
                         return std::vector<ANARISurface>{};
                     }});
    cases.push_back({"a camera in an array of surfaces", "not of the array's type ANARI_SURFACE",
                     [](Harness& h) {
                         ANARICamera camera = h.perspective({0, 0, 1}, {0, 0, -1}, {0, 1, 0}, 0.5f);
                         ANARISurface sphere = secondSphere(h);
                         const std::vector<ANARIObject> handles{sphere, camera};
                         // The harness's world takes surfaces one by one; the mixed array is checked on its own.
                         h.keep(anariNewArray1D(h.device(), handles.data(), nullptr, nullptr, ANARI_SURFACE, 2));
                         return std::vector<ANARISurface>{sphere};
                     },
                     true});
    cases.push_back({"shared array released, its memory scribbled over and freed before the commit",
                     "", [](Harness& h) { return std::vector<ANARISurface>{sphereFromFreedMemory(h)}; }, true});
    return cases;
}

}  // namespace

std::vector<Row> misuseCases(Harness& h, bool quick) {
    ANARICamera camera = h.perspective({0.0f, 0.0f, 5.0f}, {0.0f, 0.0f, -1.0f}, {0.0f, 1.0f, 0.0f}, 0.7f);
    ANARISurface sphere = h.surface(h.spheres({{-1.0f, 0.0f, 0.0f}}, 0.7f), h.matte({0.7f, 0.7f, 0.7f}));
    ANARILight light = h.directional({-0.3f, -0.4f, -1.0f}, 2.0f);
    RenderSettings settings;
    settings.size = {32, 16};
    settings.pixelSamples = 4;
    settings.maxPathLength = 3;
    settings.ambientRadiance = 0.3f;
    const Image good = h.render(h.world({sphere}, {}, {light}), camera, settings);
    const Image withSecond = h.render(h.world({sphere, secondSphere(h)}, {}, {light}), camera, settings);

    std::vector<Row> rows;
    for (const MisuseCase& misuse : allCases()) {
        if (quick && !misuse.quick) continue;
        h.clearMessages();
        std::vector<ANARISurface> surfaces = misuse.misuse(h);
        const bool reported = misuse.fragment.empty() ? h.errorCount() == 0 : h.messagesContain(misuse.fragment);
        surfaces.insert(surfaces.begin(), sphere);
        const Image image = h.render(h.world(surfaces, {}, {light}), camera, settings);
        const float difference = maxRgbDifference(image, misuse.addsSphere ? withSecond : good);
        Row row;
        row.group = "API misuse";
        row.name = misuse.name;
        row.expected = true;  // exact bookkeeping, deterministic renders: nothing to lose precision to
        row.finite = image.rendered && image.nonFinite == 0;
        row.holds = reported && difference <= kSameImage;
        row.measured = std::string(misuse.fragment.empty() ? "no error: " : "reported: ") + (reported ? "yes" : "no") +
                       ", largest pixel difference from the intended frame " + formatNumber(difference) + " (want <= " +
                       formatNumber(kSameImage) + ")";
        const std::vector<std::string> messages = h.messages();
        row.why = misuse.fragment.empty() ? "the device copied the data when the application released the array"
                                          : (messages.empty() ? std::string("no message") : messages.front());
        rows.push_back(row);
    }
    return rows;
}

}  // namespace ripple::robustness
