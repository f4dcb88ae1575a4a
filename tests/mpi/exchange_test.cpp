// The exchanges' routing, with a scripted RankTracer instead of the GPU (exact counts): rank r owns the
// unit cube at x = 3r. Each rank sends a ray along +x from x = -1 (it enters every cube, and the first
// cube, rank 0's, stops it), one along -x from beyond the last cube (the last rank's stops it), one that
// leaves its own cube upward (enters no other), and two shadow rays: one through every cube (rank 0
// occludes, the others halve its transmittance) and one that leaves upward. Run under mpirun with 1-4 ranks.
#include "mpi/BoundsExchange.h"
#include "mpi/Communicator.h"
#include "mpi/RingExchange.h"

#include <doctest/doctest.h>

#include <cmath>

using namespace ripple;

namespace {

bvh::Aabb cubeOf(uint32_t rank) { return {{3.0f * float(rank), 0.0f, 0.0f}, {3.0f * float(rank) + 1.0f, 1.0f, 1.0f}}; }

gpu::Ray ray(glm::vec3 origin, glm::vec3 direction, float tmax) {
    return {gpu::vec4(origin, 0.0f), gpu::vec4(direction, tmax)};
}

// Hits a visiting ray where it enters this rank's cube (when the rank has one), as the contract says:
// only when closer than the hit the ray carries. baseColor.x names the rank that hit.
class ScriptedTracer final : public core::RankTracer {
public:
    ScriptedTracer(uint32_t rank, bool hasCube) : rank_(rank), hasCube_(hasCube) {}

    gpu::SurfaceRecord hitIfAny(const gpu::Ray& r, float tmax) const {
        gpu::SurfaceRecord record{};
        if (!hasCube_) return record;
        const bvh::Aabb cube = cubeOf(rank_);
        const float t = mpi::regionEntry(r, tmax, std::span(&cube, 1));
        if (!std::isfinite(t)) return record;
        record.status = gpu::HIT_FOUND;
        record.position = gpu::vec4(glm::vec3(r.origin) + t * glm::vec3(r.direction), t);
        record.baseColor = gpu::vec4(float(rank_), 0.0f, 0.0f, 0.0f);
        return record;
    }

    void traceClosest(std::span<core::WireRay> rays) override {
        visits += rays.size();
        for (core::WireRay& w : rays) {
            const float tmax = w.record.status == gpu::HIT_FOUND ? w.record.position.w : w.ray.direction.w;
            const gpu::SurfaceRecord found = hitIfAny(w.ray, tmax);
            if (found.status == gpu::HIT_FOUND) w.record = found;
        }
    }
    void traceShadow(std::span<core::WireShadowRay> rays) override {
        visits += rays.size();
        for (core::WireShadowRay& s : rays) {
            if (s.occlusion == gpu::HIT_FOUND || hitIfAny(s.ray, s.ray.direction.w).status != gpu::HIT_FOUND) continue;
            if (rank_ == 0) s.occlusion = gpu::HIT_FOUND;
            else s.transmittance *= 0.5f;
        }
    }

    uint64_t visits = 0;

private:
    uint32_t rank_;
    bool hasCube_;
};

struct Outcome {
    std::vector<core::WireRay> rays;
    std::vector<core::WireShadowRay> shadows;
    uint64_t raysSentEverywhere = 0;
    uint64_t visitsHere = 0;
};

// The queues every rank starts with, traced at home (its own cube) first as the path tracer does, then
// exchanged. `cubes`: which ranks tell the others they own their cube (the others share no box);
// `solid`: which of those really hold something there (a rank may share a box it has no hit in).
Outcome route(core::RayExchange& exchange, const mpi::Communicator& world, const std::vector<bool>& cubes,
              const std::vector<bool>& solid) {
    const auto rank = uint32_t(world.rank()), ranks = uint32_t(world.size());
    const float far = 3.0f * float(ranks) + 5.0f;
    const glm::vec3 mid(3.0f * float(rank) + 0.5f, 0.5f, 0.5f);
    ScriptedTracer tracer(rank, cubes[rank] && solid[rank]);
    Outcome o;
    const gpu::Ray closest[] = {ray({-1.0f, 0.5f, 0.5f}, {1, 0, 0}, INFINITY), ray({far, 0.5f, 0.5f}, {-1, 0, 0}, INFINITY),
                                ray(mid, {0, 1, 0}, INFINITY)};
    for (uint32_t i = 0; i < 3; ++i) {
        core::WireRay w{closest[i], rank, i, 0, 0, {}};
        w.record = tracer.hitIfAny(w.ray, w.ray.direction.w);  // the home rank's local trace
        o.rays.push_back(w);
    }
    const gpu::Ray shadow[] = {ray({-1.0f, 0.5f, 0.5f}, {1, 0, 0}, far + 1.0f), ray(mid, {0, 1, 0}, 10.0f)};
    for (uint32_t i = 0; i < 2; ++i) o.shadows.push_back({shadow[i], rank, i, gpu::HIT_MISS, 1.0f});
    std::vector<bvh::Aabb> mine;
    if (cubes[rank]) mine.push_back(cubeOf(rank));
    exchange.shareRegions(mine);
    exchange.resetStats();
    tracer.visits = 0;
    exchange.exchangeClosest(o.rays, tracer);
    exchange.exchangeShadow(o.shadows, tracer);
    o.raysSentEverywhere = world.sum(exchange.stats().raysSent);
    o.visitsHere = tracer.visits;
    return o;
}

}  // namespace

TEST_CASE("bounds exchange: a ray goes only to ranks whose boxes it enters, nearest first, exact counts") {
    const mpi::Communicator world = mpi::Communicator::world();
    const auto rank = uint32_t(world.rank()), n = uint32_t(world.size());
    mpi::BoundsExchange bounds(world);
    const Outcome o = route(bounds, world, std::vector<bool>(n, true), std::vector<bool>(n, true));
    // +x: sent once (to rank 0) unless home is rank 0; -x: once (to the last rank) unless home is it; the
    // upward ray never; the through shadow ray to every other rank; the upward one never.
    CHECK(o.raysSentEverywhere == uint64_t(n - 1) * (n + 2));
    CHECK(o.rays[0].record.status == gpu::HIT_FOUND);
    CHECK(o.rays[0].record.baseColor.x == 0.0f);                 // rank 0's cube is nearest along +x
    CHECK(o.rays[0].record.position.w == doctest::Approx(1.0));
    CHECK(o.rays[1].record.baseColor.x == float(n - 1));         // the last rank's along -x
    CHECK(o.rays[1].record.position.w == doctest::Approx(7.0));  // from x = 3n + 5 to x = 3(n - 1) + 1
    CHECK(o.rays[2].record.baseColor.x == float(rank));          // inside its own cube
    CHECK(o.shadows[0].occlusion == (rank == 0 ? gpu::HIT_MISS : gpu::HIT_FOUND));
    if (rank == 0) CHECK(o.shadows[0].transmittance == doctest::Approx(std::pow(0.5, double(n - 1))));
    CHECK(o.shadows[1].occlusion == gpu::HIT_MISS);
    CHECK(o.shadows[1].transmittance == 1.0f);

    // The ring gives the same answers, sending every ray through every rank.
    mpi::RingExchange ring(world);
    const Outcome r = route(ring, world, std::vector<bool>(n, true), std::vector<bool>(n, true));
    for (size_t i = 0; i < 3; ++i) {
        CHECK(r.rays[i].record.status == o.rays[i].record.status);
        CHECK(r.rays[i].record.baseColor.x == o.rays[i].record.baseColor.x);
        CHECK(r.rays[i].record.position.w == o.rays[i].record.position.w);
    }
    for (size_t i = 0; i < 2; ++i) {
        CHECK(r.shadows[i].occlusion == o.shadows[i].occlusion);
        // An unoccluded shadow ray carries home the other ranks' transmittance (0.5 each for rank 0's).
        if (o.shadows[i].occlusion == gpu::HIT_MISS) CHECK(r.shadows[i].transmittance == o.shadows[i].transmittance);
    }
    if (n > 1) CHECK(r.raysSentEverywhere == uint64_t(n) * n * (3 + 2));  // n hops of 3 + 2 rays on every rank
}

TEST_CASE("bounds exchange: ranks with empty bounds are never sent a ray, and still answer collectives") {
    const mpi::Communicator world = mpi::Communicator::world();
    const auto rank = uint32_t(world.rank()), n = uint32_t(world.size());
    std::vector<bool> cubes(n, false);
    cubes[0] = true;  // only rank 0 holds anything
    mpi::BoundsExchange bounds(world);
    const Outcome o = route(bounds, world, cubes, cubes);
    CHECK(o.raysSentEverywhere == 3ull * (n - 1));  // +x, -x and the through shadow ray, from each other rank
    if (rank != 0) CHECK(o.visitsHere == 0);
    CHECK(o.rays[0].record.baseColor.x == 0.0f);
    CHECK(o.rays[1].record.status == gpu::HIT_FOUND);
    CHECK(o.rays[1].record.baseColor.x == 0.0f);
    CHECK(o.rays[2].record.status == (rank == 0 ? gpu::HIT_FOUND : gpu::HIT_MISS));
    CHECK(o.shadows[0].occlusion == (rank == 0 ? gpu::HIT_MISS : gpu::HIT_FOUND));
}

// Round 2: rank 0 shares its cube but has nothing in it, so a +x ray from rank h >= 2 (its own hit at
// x = 3h) first goes to rank 0 (nearest, no hit) and then at once to ranks 1..h-1, which it enters before
// that hit; rank 1's is the closest. From ranks 0 and 1 it goes once (to rank 1, resp. rank 0).
TEST_CASE("bounds exchange: a ray the nearest rank does not stop goes on to every rank it enters before its hit") {
    const mpi::Communicator world = mpi::Communicator::world();
    const auto rank = uint32_t(world.rank()), n = uint32_t(world.size());
    std::vector<bool> solid(n, true);
    solid[0] = false;
    mpi::BoundsExchange bounds(world);
    const Outcome o = route(bounds, world, std::vector<bool>(n, true), solid);
    uint64_t plusX = 0;  // rays sent for the +x ray, over all home ranks
    for (uint32_t h = 0; h < n && n > 1; ++h) plusX += h <= 1 ? 1 : h;
    // -x: once from every rank but the last; the through shadow ray to every other rank.
    CHECK(o.raysSentEverywhere == plusX + (n - 1) + uint64_t(n) * (n - 1));
    if (n > 1) {
        CHECK(o.rays[0].record.status == gpu::HIT_FOUND);
        CHECK(o.rays[0].record.baseColor.x == 1.0f);  // rank 1's cube: the nearest with something in it
        CHECK(o.rays[0].record.position.w == doctest::Approx(4.0));
    } else {
        CHECK(o.rays[0].record.status == gpu::HIT_MISS);
    }
    CHECK(o.rays[2].record.status == (rank == 0 ? gpu::HIT_MISS : gpu::HIT_FOUND));
}

TEST_CASE("bounds exchange: the entry distance of a segment into boxes") {
    const bvh::Aabb box{{0, 0, 0}, {1, 1, 1}};
    const auto entry = [&](glm::vec3 o, glm::vec3 d, float tmin, float tmax) {
        return mpi::regionEntry({gpu::vec4(o, tmin), gpu::vec4(d, tmax)}, tmax, std::span(&box, 1));
    };
    // Entries are widened by a few ulps of the distance (never later than the exact one).
    const auto near = [](float t) { return doctest::Approx(t).epsilon(1e-5); };
    CHECK(entry({-1, 0.5f, 0.5f}, {1, 0, 0}, 0, INFINITY) == near(1.0f));
    CHECK(entry({-1, 0.5f, 0.5f}, {1, 0, 0}, 0, INFINITY) <= 1.0f);
    CHECK(entry({-1, 0.5f, 0.5f}, {2, 0, 0}, 0, INFINITY) == near(0.5f));  // t in units of the direction
    CHECK(entry({0.5f, 0.5f, 0.5f}, {1, 0, 0}, 0, 5) == 0.0f);       // starts inside
    CHECK(entry({0.5f, 0.5f, 0.5f}, {1, 0, 0}, 0.25f, 5) == 0.25f);  // from tmin
    CHECK(std::isinf(entry({-1, 0.5f, 0.5f}, {1, 0, 0}, 0, 0.5f)));  // ends before the box
    CHECK(std::isinf(entry({-1, 2, 0.5f}, {1, 0, 0}, 0, INFINITY))); // parallel, outside the slab
    CHECK(entry({-1, 1, 0.5f}, {1, 0, 0}, 0, INFINITY) == near(1.0f));  // parallel, on the slab's face
    CHECK_FALSE(std::isinf(entry({-1, 0.5f, 0.5f}, {1, 0, 0}, 0, 0.9999995f)));  // ends a hair before: kept
    CHECK(std::isinf(entry({2, 0.5f, 0.5f}, {1, 0, 0}, 0, INFINITY))); // moving away
}

// The entry test runs across boxes in SIMD lanes, chunks of 16: against a per-box scalar test in double
// precision (the slab method with divisions and zero directions tested against the slab), on boxes that
// straddle the chunks, rays with zero direction components and origins on faces.
TEST_CASE("bounds exchange: the SIMD entry test agrees with a scalar one on every box count") {
    uint32_t state = 12345u;
    const auto uniform = [&](float lo, float hi) {
        state = state * 1664525u + 1013904223u;
        return lo + (hi - lo) * float(state >> 8) / float(1u << 24);
    };
    const auto scalarEntry = [](const gpu::Ray& r, float tmax, const std::vector<bvh::Aabb>& boxes) {
        double nearest = INFINITY;
        for (const bvh::Aabb& box : boxes) {
            double t0 = r.origin.w, t1 = tmax;
            bool inside = true;
            for (int a = 0; a < 3; ++a) {
                const double o = r.origin[a], d = r.direction[a];
                if (d == 0.0) {
                    inside = inside && o >= box.lo[a] && o <= box.hi[a];
                    continue;
                }
                const double n = (box.lo[a] - o) / d, f = (box.hi[a] - o) / d;
                t0 = std::max(t0, std::min(n, f));
                t1 = std::min(t1, std::max(n, f));
            }
            if (inside && t0 <= t1) nearest = std::min(nearest, t0);
        }
        return nearest;
    };
    uint64_t entered = 0, missed = 0;
    for (uint32_t count : {1u, 15u, 16u, 17u, 40u, 64u}) {
        std::vector<bvh::Aabb> boxes;
        for (uint32_t i = 0; i < count; ++i) {
            const glm::vec3 lo(uniform(-10, 8), uniform(-10, 8), uniform(-10, 8));
            boxes.push_back({lo, lo + glm::vec3(uniform(0.1f, 2), uniform(0.1f, 2), uniform(0.1f, 2))});
        }
        const mpi::RegionBoxes soa(boxes);
        for (int i = 0; i < 4000; ++i) {
            glm::vec3 o(uniform(-12, 12), uniform(-12, 12), uniform(-12, 12));
            glm::vec3 d(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1));
            if (i % 2 == 0) d += boxes[(i / 2) % count].lo - o;  // towards a box
            if (i % 5 == 0) d[i % 3] = 0.0f;                             // parallel to a slab
            if (i % 7 == 0) o[(i / 7) % 3] = boxes[i % count].lo[(i / 7) % 3];  // on a face's plane
            const float tmax = i % 3 == 0 ? INFINITY : uniform(0, 30);
            const gpu::Ray r{gpu::vec4(o, 0.0f), gpu::vec4(d, tmax)};
            const double expected = scalarEntry(r, tmax, boxes);
            const float got = soa.entry(r, tmax);
            if (std::isinf(expected)) {
                ++missed;
                // Only a ray within the widening of a box may be kept.
                if (!std::isinf(got)) CHECK(scalarEntry(r, tmax * 1.00001f + 1e-5f, boxes) <= double(tmax) * 1.00001 + 1e-5);
            } else {
                ++entered;
                REQUIRE(std::isfinite(got));
                CHECK(double(got) <= expected + 1e-9);  // never later than the exact entry
                CHECK(double(got) >= expected - 1e-5 * std::max(1.0, std::abs(expected)));
            }
        }
    }
    CHECK(entered > 2000);  // both outcomes well covered
    CHECK(missed > 2000);
}
