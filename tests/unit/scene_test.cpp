// core::Scene beyond traversal: reuse of unchanged BLASes from a previous Scene, and validation of
// attributes, materials, textures and lights (bad values named in the report, then ignored, repaired or
// skipped; never a crash).
#include "core/render/TraceKernels.h"
#include "core/scene/Scene.h"
#include "tests/support/SceneGenerators.h"
#include "tests/support/TestContext.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <limits>
#include <string>

using namespace ripple;
using test::testContext;

namespace {

bool mentions(const core::SceneReport& report, const std::string& text) {
    return std::any_of(report.messages.begin(), report.messages.end(),
                       [&](const std::string& m) { return m.find(text) != std::string::npos; });
}

bool sameHits(const std::vector<gpu::Hit>& a, const std::vector<gpu::Hit>& b) {
    if (a.size() != b.size()) return false;
    for (size_t i = 0; i < a.size(); ++i)
        if (a[i].status != b[i].status || a[i].t != b[i].t || a[i].primId != b[i].primId || a[i].instanceId != b[i].instanceId)
            return false;
    return true;
}

}  // namespace

// Three geometries with identities; a second Scene built with the first as `previous` reuses the two
// whose (key, version) did not change and rebuilds the third, and traces exactly like a Scene built
// from scratch. A geometry without a key, or whose arrays no longer fit the cached build, is rebuilt.
TEST_CASE("scene: unchanged geometries reuse the previous BLAS") {
    test::ValidationGuard guard;
    core::SceneDescription d;
    d.meshes = {test::randomTriangleSoup(500, 61), test::randomTriangleSoup(300, 62)};
    d.sphereSets = {test::randomSpheres(50, 63)};
    d.meshes[0].identity = {1, 1};
    d.meshes[1].identity = {2, 1};
    d.sphereSets[0].identity = {3, 1};
    d.instances = {{{core::GeometryKind::Triangles, 0}, glm::mat4(1.0f)},
                   {{core::GeometryKind::Triangles, 1}, glm::mat4(1.0f)},
                   {{core::GeometryKind::Spheres, 0}, glm::mat4(1.0f)}};
    auto first = std::make_unique<core::Scene>(testContext(), d);
    CHECK(first->report().blasBuilt == 3);
    CHECK(first->report().blasReused == 0);

    d.meshes[1] = test::randomTriangleSoup(300, 64);
    d.meshes[1].identity = {2, 2};
    const core::Scene second(testContext(), d, {}, first.get());
    first.reset();  // `previous` is only needed while building
    CHECK(second.report().blasReused == 2);
    CHECK(second.report().blasBuilt == 1);
    CHECK(second.report().trianglesKept == 800);

    const core::Scene fresh(testContext(), d);
    core::TraceKernels kernels(testContext());
    const auto rays = test::raysTowardPoints(d, 2048, 65);
    CHECK(sameHits(kernels.traceClosest(second, rays), kernels.traceClosest(fresh, rays)));

    // Same identity but fewer triangles (an application that forgot to bump the version): not reused.
    core::SceneDescription stale = d;
    stale.meshes[0].positions.resize(300);
    const core::Scene third(testContext(), stale, {}, &second);
    CHECK(third.report().blasReused == 2);
    CHECK(third.report().trianglesKept == 100 + 300);
    // Key 0 means no identity.
    core::SceneDescription anonymous = d;
    for (auto& mesh : anonymous.meshes) mesh.identity = {};
    anonymous.sphereSets[0].identity = {};
    const core::Scene fourth(testContext(), anonymous, {}, &second);
    CHECK(fourth.report().blasReused == 0);
}

TEST_CASE("scene: attributes with a wrong length or NaN are named and ignored") {
    test::ValidationGuard guard;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    core::TriangleMesh mesh = test::randomTriangleSoup(10, 66);  // 30 positions, 10 triangles
    mesh.normals.assign(29, glm::vec3(0, 0, 1));
    mesh.colors.assign(30, glm::vec4(1.0f));
    mesh.colors[4].g = nan;
    mesh.texcoords.assign(30, glm::vec2(0.5f));
    mesh.primitiveColors.assign(11, glm::vec4(1.0f));
    core::SceneDescription d = test::sceneOf(mesh);
    core::SphereSet spheres = test::randomSpheres(5, 67);
    spheres.colors.assign(4, glm::vec4(1.0f));
    d.sphereSets.push_back(spheres);
    d.instances.push_back({{core::GeometryKind::Spheres, 0}, glm::mat4(1.0f)});
    const core::Scene scene(testContext(), d);
    const core::SceneReport& r = scene.report();
    CHECK(r.attributesIgnored == 4);
    CHECK(mentions(r, "mesh 0: normals has 29 entries, not 30; attribute ignored"));
    CHECK(mentions(r, "mesh 0: colors holds NaN or Inf; attribute ignored"));
    CHECK(mentions(r, "mesh 0: primitiveColors has 11 entries, not 10; attribute ignored"));
    CHECK(mentions(r, "sphere set 0: colors has 4 entries, not 5; attribute ignored"));
    CHECK_FALSE(mentions(r, "texcoords"));
    CHECK(r.trianglesKept == 10);
}

TEST_CASE("scene: bad materials, textures, lights and material indices are repaired or skipped, and named") {
    test::ValidationGuard guard;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    core::SceneDescription d = test::sceneOf(test::randomTriangleSoup(10, 68));
    d.instances.push_back({{core::GeometryKind::Triangles, 0}, glm::mat4(1.0f), 7});  // no material 7
    core::Material good, badColor, badRanges, badTexture;
    badColor.baseColor.y = nan;
    badColor.emissive = glm::vec3(-1.0f);
    badRanges.opacity = 2.0f;
    badRanges.roughness = std::numeric_limits<float>::infinity();
    badTexture.baseColorTexture = 5;
    d.materials = {good, badColor, badRanges, badTexture};
    core::Texture shortTexture;
    shortTexture.width = shortTexture.height = 2;
    shortTexture.texels.assign(15, 0);
    d.textures.push_back(shortTexture);
    core::Light ok, dark, noDirection, flat;
    ok.intensity = 2.0f;
    dark.color.x = nan;
    noDirection.direction = glm::vec3(0.0f);
    flat.kind = core::Light::Kind::Quad;
    flat.edge2 = flat.edge1;
    d.lights = {ok, dark, noDirection, flat};
    const core::Scene scene(testContext(), d);
    const core::SceneReport& r = scene.report();
    CHECK(r.materialsRepaired == 3);
    CHECK(mentions(r, "material 1: invalid baseColor, emissive"));
    CHECK(mentions(r, "material 2: invalid opacity, roughness"));
    CHECK(mentions(r, "material 3: invalid baseColorTexture 5 (no such texture)"));
    CHECK(r.texturesSkipped == 1);
    CHECK(mentions(r, "texture 0: 15 bytes of texels for 2x2 (need 16"));
    CHECK(r.lightsKept == 1);
    CHECK(r.lightsSkipped == 3);
    CHECK(scene.lightCount() == 1);
    CHECK(mentions(r, "light 1: color or intensity is negative, NaN or Inf; skipped"));
    CHECK(mentions(r, "light 2: direction is zero"));
    CHECK(mentions(r, "light 3: edges span no area"));
    CHECK(mentions(r, "1 instance(s) name a material index beyond the 4 material(s)"));
}
