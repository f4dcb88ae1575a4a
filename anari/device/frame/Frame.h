// ANARI frame: renders a world through a camera with a renderer into the requested channels. renderFrame()
// syncs the scene on the calling thread, then returns while a worker thread runs core::PathTracer; frames
// accumulate samples until the world, camera, renderer or size change. Whether it renders alone or
// data-parallel is its FrameDistribution's business.
#pragma once

#include "anari/device/camera/Camera.h"
#include "anari/device/frame/FrameDistribution.h"
#include "anari/device/frame/FrameMemory.h"
#include "anari/device/renderer/Renderer.h"
#include "anari/device/scene/SceneSync.h"
#include "anari/device/world/World.h"
#include "core/render/PathTracer.h"

#include <array>
#include <atomic>
#include <chrono>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

namespace ripple::device {

class Frame final : public Object {
public:
    explicit Frame(DeviceState& state);
    ~Frame() override;

    void commit() override;
    // "duration" (FLOAT32 seconds of the last frame), "numSamples" (UINT32 accumulated samples per pixel),
    // "ripple.raysPerSecond" (FLOAT32, closest-hit and shadow rays of the last frame), "ripple.traversal"
    // (STRING, the traversal back-end that traced it: "software" or "rayQuery"), and for tests of
    // what a change rebuilds: "ripple.sceneBuilds" (UINT64, scenes built so far) and "ripple.blasBuilt" /
    // "ripple.blasReused", "ripple.volumeVoxelsUploaded" / "ripple.volumeVoxelsReused" (UINT64, of the latest
    // scene build); "ripple.raysSent", "ripple.bytesSent" (UINT64,
    // rays and bytes this rank passed on in the last frame), "ripple.raysReceived" (UINT64, other ranks' rays
    // it traced), "ripple.raysTraced" (UINT64, its own closest-hit and shadow rays), "ripple.exchangeRounds"
    // (UINT64, the exchange's hops or rounds), "ripple.visitMicroseconds" (UINT64, time tracing others' rays) and "ripple.sceneBytes" (UINT64, its scene's GPU memory);
    // of the last frame on this rank: "ripple.flaggedRays" (UINT64, traversals and volume marches that ran out
    // of their step budget), "ripple.realCollisions", "ripple.nullCollisions" (UINT64, delta tracking in
    // volumes), "ripple.ratioCollisions" (UINT64, ratio tracking of shadow rays) and "ripple.parkedMarches"
    // (UINT64, volume marches that spent their step budget and were resumed by a later round); and
    // "ripple.stageMicroseconds.NAME" (UINT64, GPU time of each stage of the wavefront loop, NAME as
    // core::stageName gives it: generate, traceClosest, surface, shade, traceAny, ...).
    bool getProperty(std::string_view name, ANARIDataType type, void* mem, uint64_t size, bool wait) override;

    // The calls the Device forwards. map() waits for a frame in progress; rows start at the bottom.
    void renderFrame();
    bool ready(bool wait);
    void discard();
    const void* map(std::string_view channel, uint32_t* width, uint32_t* height, ANARIDataType* pixelType);
    void unmap(std::string_view channel);

private:
    // What one renderFrame() call hands to the worker: copies only, so the application may change its
    // objects while the frame renders.
    struct Job {
        glm::uvec2 size{0, 0};
        ANARIDataType colorType = ANARI_UNKNOWN;
        bool depth = false;
        core::FrameChannels channels;  // depth and the surface channels asked for
        bool restartAccumulation = false;
        core::Camera camera;
        core::RenderSettings settings;
        ANARIFrameCompletionCallback completion = nullptr;  // KHR_FRAME_COMPLETION_CALLBACK
        const void* completionUserData = nullptr;
    };
    // What the worker hands back (guarded by resultsMutex_).
    struct Results {
        glm::uvec2 size{0, 0};
        ANARIDataType colorType = ANARI_UNKNOWN;
        std::vector<uint8_t> color;
        std::vector<float> depth;
        std::vector<float> albedo;             // three floats per pixel
        std::vector<float> normal;             // three floats per pixel
        std::vector<uint32_t> ids[3];          // primitiveId, objectId, instanceId
        float duration = 0.0f;
        uint32_t numSamples = 0;
        float raysPerSecond = 0.0f;
        const char* traversal = "";          // core::traversalName of the back-end that traced it
        uint64_t sceneBuilds = 0;
        uint64_t blasBuilt = 0;
        uint64_t blasReused = 0;
        uint64_t volumeVoxelsUploaded = 0;
        uint64_t volumeVoxelsReused = 0;
        uint64_t raysSent = 0;                 // data-parallel traffic of this rank in the last frame
        uint64_t bytesSent = 0;                // rays, answers and world boxes
        uint64_t raysReceived = 0;             // other ranks' rays traced here
        uint64_t raysTraced = 0;               // this rank's own closest-hit and shadow rays
        uint64_t exchangeRounds = 0;           // ring hops or bounds rounds (core::ExchangeStats::hops)
        uint64_t visitMicroseconds = 0;        // spent tracing other ranks' rays
        uint64_t sceneBytes = 0;               // GPU memory of this rank's part of the scene
        uint64_t flaggedRays = 0;              // core::FrameStats of the last frame
        uint64_t realCollisions = 0;
        uint64_t nullCollisions = 0;
        uint64_t ratioCollisions = 0;
        uint64_t parkedMarches = 0;
        std::array<uint64_t, core::kStageCount> stageMicroseconds{};
    };

    // Why this frame cannot render now, or empty when it can; includes the memory check of a new size.
    std::string whyNotRenderable();
    std::string whyNotInMemory();  // for a new size or channels; remembers what fitted
    FrameFingerprint fingerprint(bool renderable) const;
    Job makeJob() const;
    void run(const Job& job);
    void renderJob(const Job& job, const std::chrono::steady_clock::time_point& start);
    // Worker: copies the albedo, normal and id channels the job asked for out of the tracer.
    void readSurfaceChannels(const Job& job, size_t pixels, Results& results);
    void waitForWorker();

    // Committed parameters.
    glm::uvec2 size_{0, 0};
    ANARIDataType colorType_ = ANARI_UNKNOWN;
    bool depth_ = false;
    bool accumulation_ = true;
    bool implicitAmbientReported_ = false;
    core::FrameChannels channels_;              // channel.depth and the surface channels enabled
    ObjectRef<World> world_;
    ObjectRef<Camera> camera_;
    ObjectRef<Renderer> renderer_;
    ANARIFrameCompletionCallback completion_ = nullptr;
    const void* completionUserData_ = nullptr;

    // What the accumulation so far was rendered with: a change to any of them starts it over.
    const Object* renderedCamera_ = nullptr;
    uint64_t renderedCameraStamp_ = 0;
    const Object* renderedRenderer_ = nullptr;
    uint64_t renderedRendererStamp_ = 0;

    // The memory of the last size and channels that fitted, released when the frame resizes.
    std::optional<FrameMemory> acceptedMemory_;
    glm::uvec2 acceptedSize_{0, 0};
    ANARIDataType acceptedColorType_ = ANARI_UNKNOWN;
    uint32_t acceptedChannels_ = 0;

    // Data-parallel ANARI: the N-th frame created on each rank is the same frame.
    uint64_t globalIndex_ = 0;
    std::unique_ptr<FrameDistribution> distribution_;  // made at the first render (the communicator is known then)
    SceneSync sync_;                            // used by the API thread, then the worker, never both at once
    std::unique_ptr<core::PathTracer> tracer_;  // worker only
    core::Traversal tracerTraversal_ = core::Traversal::Auto;  // what tracer_ was made with
    core::RayExchange* tracerExchange_ = nullptr;              // and with which exchange
    core::FrameChannels tracerChannels_;        // worker only: what the tracer's buffers were sized for
    std::thread worker_;
    std::atomic<bool> finished_{true};
    std::atomic<bool> discarded_{false};
    mutable std::mutex resultsMutex_;
    Results results_;
};

}  // namespace ripple::device
