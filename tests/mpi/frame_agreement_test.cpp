// Data-parallel ANARI through the public API under mpirun: ranks whose frame, renderer or camera differ
// (ANARI.md section 5) are told so on every rank, naming what differs, and none renders; ranks that agree
// again render together afterwards (nobody was left waiting in a collective); and the device parameter
// rayExchange picks the exchange the ranks render with.
#include "mpi/Communicator.h"
#include "tests/anari/RenderSession.h"

#include <doctest/doctest.h>

#include <string>
#include <vector>

using ripple::test::RenderSession;

namespace {

struct Scene {
    ANARIWorld world;
    ANARICamera camera;
    ANARIRenderer renderer;
};

Scene floorScene(RenderSession& s) {
    Scene scene;
    scene.world = s.world({s.surface(s.floor(), s.matte({0.8f, 0.8f, 0.8f}))}, {s.directional({0, -1, 0}, 2.0f)});
    scene.camera = s.perspective({0, 3, 6}, {0, 0, 0});
    scene.renderer = s.renderer(1, 2);
    return scene;
}

// Renders `frame` once; true when the device rendered it (it holds samples).
bool rendered(RenderSession& s, ANARIFrame frame) {
    anariRenderFrame(s.device, frame);
    REQUIRE(anariFrameReady(s.device, frame, ANARI_WAIT) == 1);
    uint32_t samples = 0;
    anariGetProperty(s.device, frame, "numSamples", ANARI_UINT32, &samples, sizeof samples, ANARI_WAIT);
    return samples > 0;
}

}  // namespace

TEST_CASE("ranks that disagree on frame, renderer or camera are told what differs, and none renders") {
    const ripple::mpi::Communicator ranks = ripple::mpi::Communicator::world();
    REQUIRE(ranks.size() == 2);  // rank 1 is the one that differs
    const bool odd = ranks.rank() == 1;
    RenderSession s;
    const Scene scene = floorScene(s);
    ANARIFrame frame = s.frame(scene.world, scene.camera, scene.renderer, {16, 16}, ANARI_FLOAT32_VEC4);
    std::string expected;
    bool exchangeDiffers = false;
    SUBCASE("channels") {
        if (odd) {
            const ANARIDataType depth = ANARI_FLOAT32;
            s.setRaw(frame, "channel.depth", ANARI_DATA_TYPE, &depth);
            s.commit(frame);
        }
        expected = "rank 1's frame has color ANARI_FLOAT32_VEC4, depth, rank 0's color ANARI_FLOAT32_VEC4: every rank must enable "
                   "the same channels";
    }
    SUBCASE("size") {
        if (odd) {
            s.set(frame, "size", glm::uvec2(16, 8));
            s.commit(frame);
        }
        expected = "rank 1's frame is 16x8, rank 0's 16x16";
    }
    SUBCASE("pixelSamples") {
        if (odd) {
            s.setInt(scene.renderer, "pixelSamples", 3);
            s.commit(scene.renderer);
        }
        expected = "rank 1's renderer has pixelSamples 3, rank 0's 1";
    }
    SUBCASE("another renderer parameter") {
        if (odd) {
            s.set(scene.renderer, "ambientRadiance", 0.5f);
            s.commit(scene.renderer);
        }
        expected = "rank 1's renderer differs from rank 0's (subtype or parameters)";
    }
    SUBCASE("camera") {
        if (odd) {
            s.set(scene.camera, "fovy", 0.5f);
            s.commit(scene.camera);
        }
        expected = "rank 1's camera differs from rank 0's";
    }
    SUBCASE("the ray exchange (a device parameter)") {
        if (odd) {
            s.set(s.device, "rayExchange", "ring");
            s.commit(s.device);
            exchangeDiffers = true;
        }
        expected = "rank 1 uses rayExchange 'ring', rank 0 'bounds': every rank must set the same device parameter "
                   "rayExchange";
    }
    SUBCASE("whether a rank can render at all") {
        if (odd) {
            s.setObject(frame, "camera", ANARI_CAMERA, nullptr);
            s.commit(frame);
        }
        expected = "rank 1 cannot render this frame";
    }
    CHECK_FALSE(rendered(s, frame));
    CHECK_MESSAGE(s.log.count({"cannot render (data-parallel): ", expected.c_str()}) == 1, s.log.dump());
    if (exchangeDiffers) {
        s.set(s.device, "rayExchange", "bounds");
        s.commit(s.device);
    }

    // Agreeing again, the ranks render together.
    s.log.clear();
    ANARIFrame agreed = s.frame(scene.world, s.perspective({0, 3, 6}, {0, 0, 0}), s.renderer(1, 2), {16, 16},
                                ANARI_FLOAT32_VEC4);
    CHECK(rendered(s, agreed));
    CHECK_MESSAGE(s.log.problems() == 0, s.log.dump());
}

TEST_CASE("ranks that set an unknown ray exchange are told its name and the allowed ones") {
    RenderSession s;
    s.set(s.device, "rayExchange", "broadcast");
    s.commit(s.device);
    CHECK_MESSAGE(s.log.count({"rayExchange", "'broadcast'", "bounds", "ring"}) == 1, s.log.dump());
}

// The device parameter rayExchange picks the exchange a data-parallel frame renders with: rank 0 holds a
// floor and the light, the other ranks a sphere each beside it. Both exchanges bring every ray its closest
// hit, so the images are the same; the ring passes every ray to every other rank, bounds only the rays that
// enter another rank's boxes (most of the floor's rays enter none), so the ring sends more.
TEST_CASE("data-parallel frames render with the ray exchange the device parameter names") {
    const ripple::mpi::Communicator ranks = ripple::mpi::Communicator::world();
    struct Run {
        ripple::test::Image image;
        uint64_t raysSent = 0;  // over all ranks
    };
    const auto run = [&](const char* exchange) {
        RenderSession s;
        s.set(s.device, "rayExchange", exchange);
        s.commit(s.device);
        std::vector<ANARISurface> surfaces;
        std::vector<ANARILight> lights;
        if (ranks.rank() == 0) {
            surfaces.push_back(s.surface(s.floor(), s.matte({0.8f, 0.8f, 0.8f})));
            lights.push_back(s.directional(glm::normalize(glm::vec3(-0.5f, -1.0f, -0.3f)), 2.0f));
        } else {
            ANARIGeometry sphere = s.keep(anariNewGeometry(s.device, "sphere"));
            const glm::vec3 center(-1.5f + float(ranks.rank()), 0.4f, 0.0f);
            s.setObject(sphere, "vertex.position", ANARI_ARRAY1D, s.array(ANARI_FLOAT32_VEC3, std::vector<glm::vec3>{center}));
            s.set(sphere, "radius", 0.4f);
            s.commit(sphere);
            surfaces.push_back(s.surface(sphere, s.matte({0.2f, 0.5f, 0.8f})));
        }
        ANARIFrame frame = s.frame(s.world(surfaces, lights), s.perspective({0, 3, 6}, {0, 0, 0}), s.renderer(4, 3),
                                   {32, 32}, ANARI_FLOAT32_VEC4);
        Run r;
        r.image = s.render(frame);
        uint64_t sent = 0;
        CHECK(anariGetProperty(s.device, frame, "ripple.raysSent", ANARI_UINT64, &sent, sizeof sent, ANARI_WAIT) == 1);
        r.raysSent = ranks.sum(sent);
        CHECK_MESSAGE(s.log.problems() == 0, s.log.dump());
        return r;
    };
    const Run ring = run("ring");
    const Run bounds = run("bounds");
    MESSAGE("rays sent over all ranks: ring " << ring.raysSent << ", bounds " << bounds.raysSent);
    if (ranks.size() > 1) {
        CHECK(bounds.raysSent > 0);
        CHECK(ring.raysSent > 2 * bounds.raysSent);
    }
    if (ranks.rank() == 0) CHECK(ripple::test::rmseRgb(ring.image, bounds.image) < 1e-6);
}
