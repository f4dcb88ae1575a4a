// How a frame renders over ranks: alone, or data-parallel (every rank holds part of the scene and renders
// the same frame with the others). Frame calls the same steps either way; only the data-parallel
// distribution (DataParallelFrame.h) makes collective calls, and it alone knows about MPI.
#pragma once

#include "core/render/PathTracer.h"
#include "core/render/RayExchange.h"
#include "mpi/Communicator.h"

#include <glm/glm.hpp>

#include <array>
#include <cstdint>
#include <memory>
#include <string>

namespace ripple::vk {
class Context;
}

namespace ripple::device {

class SceneSync;
class World;

// What every rank must agree on before rendering a frame together (ANARI.md section 5: frame, renderer and
// camera have the same subtype and parameters on every rank). Fields that have no small exact value
// (camera, renderer) are hashes; the others are the values themselves, so that a message can name them.
struct FrameFingerprint {
    enum Field : size_t {
        Renderable,     // 1 when this rank can render the frame, 0 when not (the other fields are then 0)
        FrameIndex,     // creation order of the frame on its rank
        WorldIndex,     // creation order of its world
        Size,           // width << 32 | height
        Channels,       // color type << 32 | channelFeatures bits
        PixelSamples,
        MaxPathLength,
        Renderer,       // hash of subtype and settings
        Camera,         // hash of subtype and the camera as rendered
        RayExchange,    // the device parameter rayExchange (core::ExchangeKind)
        kFieldCount
    };
    std::array<uint64_t, kFieldCount> fields{};
};

// 64-bit FNV-1a over `bytes`, continuing from `hash`: the same bytes give the same hash on every rank.
uint64_t fingerprintHash(const void* bytes, size_t size, uint64_t hash = 0xcbf29ce484222325ull);

class FrameDistribution {
public:
    virtual ~FrameDistribution() = default;

    // Collective. Empty when every rank can render the frame `mine` describes and all describe the same
    // one; otherwise one message, the same on every rank, naming what differs (and the first rank that
    // differs from rank 0).
    virtual std::string disagreement(const FrameFingerprint& mine) = 0;
    // Collective, on the API thread after the scene sync: every rank's lights for `sync` and the world's
    // extent over ranks. Returns whether the accumulation restarts: on every rank when it does on one.
    virtual bool shareLights(SceneSync& sync, World& world, bool restart) = 0;
    // Collective: whether `value` is true on any rank.
    virtual bool anyRank(bool value) = 0;
    // Whether the frame may render on a worker thread (data-parallel: MPI is called from one thread).
    virtual bool rendersOnWorker() const = 0;
    // The ray exchange of `kind` the path tracer uses (null: this rank holds the whole scene). Owned here.
    virtual core::RayExchange* exchange(core::ExchangeKind kind) = 0;
    // Collective, on the rendering thread: the scene to render, with every rank's emitters where shared.
    virtual const core::Scene& scene(SceneSync& sync, const vk::Context& context, bool& rebuilt) = 0;
    // Collective: rank 0 assembles every rank's pixels; the others keep theirs (undefined by ANARI's rule).
    virtual void gather(glm::uvec2 size, size_t bytesPerPixel, void* pixels) = 0;
    // Why a frame of `size` with `bytesPerPixel` bytes of color and depth cannot be assembled, or empty.
    virtual std::string whyCannotGather(glm::uvec2 /*size*/, uint64_t /*bytesPerPixel*/) const { return {}; }
    // Rendering failed on this rank. Data-parallel: the other ranks wait for it in the exchange, so every
    // rank is ended with the message (this does not return); alone: nothing more to do.
    virtual void failed(const std::string& message) = 0;
};

// Alone for a communicator of one rank, data-parallel otherwise.
std::unique_ptr<FrameDistribution> makeFrameDistribution(const mpi::Communicator& ranks);

}  // namespace ripple::device
