// The wavefront path tracer: per sample pass, generate camera rays -> repeat { trace closest, shade (emission,
// next-event estimation, BSDF sample, Russian roulette), occlude shadow rays } -> accumulate; resolve turns
// the accumulation into the requested channels. One .comp per stage (shaders/pt_*.comp). Synchronous: the
// ANARI layer runs it on a worker thread to make frames asynchronous. Knows nothing of ANARI or MPI.
//
// What the images contain: area lights (quad, ring, hdri, and the triangles of emissive materials without
// an emission texture) are found both by next-event estimation and by BSDF-sampled rays, combined by
// multiple importance sampling (power heuristic); lights are picked in proportion to their power. Camera
// rays do not see quad and ring lights. Emissive surfaces emit from both sides. Shadow rays treat every
// surface as opaque (light through partly transparent surfaces reaches a point only by BSDF rays). Random numbers
// are keyed by (pixel, sample index, bounce, dimension, seed), so the same inputs give the same image bit
// for bit, however the frame is split into waves and however many of a pixel's samples a pass traces
// together (a frame of few pixels packs several: PathTracerOptions::packedWavePaths); the pixel jitter and the first BSDF direction are
// stratified over the accumulation's frames (shaders/rng.glsl), so the image also depends on how many
// samples each render() call adds.
#pragma once

#include "core/render/RayExchange.h"
#include "core/render/FeatureSet.h"
#include "core/render/StageProfile.h"
#include "core/render/SurfaceChannels.h"
#include "core/render/TraceKernels.h"
#include "core/render/VolumeParking.h"
#include "core/scene/Scene.h"
#include "core/vk/Buffer.h"
#include "core/vk/Context.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

namespace ripple::core {

struct Camera {
    enum class Kind : uint32_t { Perspective = 0, Orthographic = 1, Omnidirectional = 2 };
    Kind kind = Kind::Perspective;
    glm::vec3 position{0.0f};
    glm::vec3 direction{0.0f, 0.0f, -1.0f};
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    float fovy = 1.0471976f;              // perspective: vertical field of view, radians (ANARI default pi/3)
    float aspect = 1.0f;                  // width / height of the image region
    float height = 1.0f;                  // orthographic: height of the view in world units
    float apertureRadius = 0.0f;          // perspective: lens radius for depth of field (0: pinhole)
    float focusDistance = 1.0f;           // perspective: distance of the plane in focus along `direction`
    glm::vec4 imageRegion{0.0f, 0.0f, 1.0f, 1.0f}; // (minX, minY, maxX, maxY) of the screen in [0,1]^2
    // Perspective and orthographic: camera rays see only what lies between these distances along
    // `direction` (planes, not spheres).
    float nearClip = 0.0f;
    float farClip = std::numeric_limits<float>::infinity();
};

struct RenderSettings {
    glm::vec4 background{0.0f, 0.0f, 0.0f, 1.0f}; // what camera rays that miss see (linear RGBA)
    glm::vec3 ambientColor{1.0f};
    float ambientRadiance = 0.0f;         // radiance of a uniform environment seen by secondary rays
    uint32_t maxPathLength = 5;           // surface interactions per path (1: direct lighting only)
    uint32_t pixelSamples = 1;            // samples per pixel added by one render() call
    uint32_t seed = 0;                    // varies the random numbers; the same seed gives the same image
    // Largest component any one contribution (emission or light sample times throughput) may have; larger
    // ones are scaled down to it, trading bias for less noise from rare bright paths. 0: no clamp.
    float maxRadiance = 0.0f;
    // How area lights are found. Mis is the renderer; the others exist to test that each strategy alone
    // converges to the same image.
    enum class LightSampling : uint32_t { Mis = 0, LightsOnly = 1, BsdfOnly = 2 };
    LightSampling lightSampling = LightSampling::Mis;
    // Henyey-Greenstein mean cosine of scattering in volumes: > 0 forward, < 0 backward, 0 isotropic.
    // Clamped to [-0.99, 0.99] (the phase function is a delta at +-1).
    float phaseAnisotropy = 0.0f;
    // PathTraced: the path tracer. EyeLight: a quick look, no lights or bounces: the first surface (or
    // volume collision) in its colour times ambientColor * ambientRadiance * (1 - r + r |cos|), with
    // r = eyeLightBlendRatio in [0, 1] and the angle between the normal and the view ray, plus its emission.
    enum class Shading : uint32_t { PathTraced = 0, EyeLight = 1 };
    Shading shading = Shading::PathTraced;
    float eyeLightBlendRatio = 0.5f;
};

struct PathTracerOptions {
    // Paths in flight at once: a frame with more pixels is rendered in waves of this many, so queue memory
    // (about 220 bytes per path) does not grow with the image.
    uint32_t queueCapacity = 1u << 20;
    // A frame of fewer pixels (on the busiest rank) traces several of each pixel's samples in one pass, up to
    // this many paths (and queueCapacity): small dispatches cost lavapipe more per path (default scene, GPU
    // time per path of a frame: 3.6 us at 1,024 paths, 1.8 at 4,096, 0.75-0.87 from 16,384 up), and with
    // several ranks each pass costs exchange rounds. The image is the same bit for bit (PixelSample in
    // shaders/pt_common.glsl). 1: one sample of each pixel per pass.
    uint32_t packedWavePaths = 1u << 16;
    uint32_t workgroupSize = 64;
    // Build the kernels for the FeatureSet of each frame (see FeatureSet.h). false: every kernel keeps
    // every feature, the baseline the specialisation benchmark compares against.
    bool specialize = true;
    // The other ranks of a data-parallel render (not owned; must outlive the tracer). Null: this rank
    // holds the whole scene. With N ranks, this rank generates and shades only its pixels (PixelTiles.h).
    RayExchange* exchange = nullptr;
    // Tracking steps per invocation of the volume stages and the resume rounds of marches that spend them.
    VolumeParkingOptions volumeParking;
};

// Pixel formats the resolve stage writes. Row 0 of every channel is the bottom row of the image.
enum class ColorFormat : uint32_t { Rgba8Unorm = 0, Rgba8Srgb = 1, Rgba32Float = 2 };

struct FrameStats {
    uint64_t waves = 0;                   // waves traced, over all passes (the busiest rank's count)
    uint64_t raysTraced = 0;              // closest-hit rays over all bounces
    uint64_t shadowRays = 0;
    uint64_t nonFiniteSamples = 0;        // dropped, never accumulated
    uint64_t flaggedRays = 0;             // traversals that ran out of budget (HIT_FLAG_*), treated as misses
    // Volume tracking (docs/volumes.md): real and null collisions of the path rays' free-flight sampling
    // (their ratio is the cost of the majorants' looseness), and the tentative collisions of shadow rays'
    // ratio tracking.
    uint64_t realCollisions = 0;
    uint64_t nullCollisions = 0;
    uint64_t ratioCollisions = 0;
    uint64_t parkedMarches = 0;           // volume marches that spent their step budget and were resumed later
    StageSeconds stageSeconds{};          // GPU time per stage of the wavefront loop (StageProfile.h)
    double seconds = 0.0;
};

class PathTracer {
public:
    explicit PathTracer(const vk::Context& context, const TraceOptions& traceOptions = {},
                        const PathTracerOptions& options = {});
    ~PathTracer();

    // Resizes the frame (and clears the accumulation). Only the channels asked for get buffers.
    void resize(glm::uvec2 size, bool wantDepth);
    void resize(glm::uvec2 size, const FrameChannels& channels);
    // Starts accumulation over: call when scene, camera or settings changed.
    void resetAccumulation();

    // Adds settings.pixelSamples samples per pixel to the accumulation and resolves the channels.
    // Blocks until the GPU is done. Throws std::invalid_argument for a camera that is not finite or has
    // no direction, or when resize() was never called. A maxPathLength of 0 is taken as 1.
    FrameStats render(const Scene& scene, const Camera& camera, const RenderSettings& settings);

    glm::uvec2 size() const { return size_; }
    uint32_t accumulatedSamples() const { return accumulatedSamples_; }

    // Read back the resolved channels (size().x * size().y pixels, row 0 at the bottom).
    // Color: 4 bytes per pixel for the 8-bit formats, 16 for Rgba32Float. Depth: the distance along the
    // camera ray to the first hit of the latest sample (+inf where nothing was hit).
    // readDepth throws std::logic_error when resize() did not ask for depth.
    void readColor(ColorFormat format, void* destination) const;
    void readDepth(float* destination) const;
    // Albedo and normal: three floats per pixel; the ids: one uint32 per pixel (~0u where the camera ray
    // missed). Of the latest sample's first hit. Throws std::logic_error when resize() did not ask for it.
    void readChannel(SurfaceChannel channel, void* destination) const;

    // What the latest render() was specialised for, and every pipeline variant built so far.
    FeatureSet features() const;
    // The traversal back-end the tracer uses: Software or RayQuery (TraceOptions::traversal resolved).
    Traversal traversal() const;
    std::vector<PipelineCache::Entry> pipelines() const;
    // Bytes of the optional per-pixel channels (depth, albedo, normal, ids): 0 when none was asked for.
    uint64_t channelBytes() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
    glm::uvec2 size_{0, 0};
    uint32_t accumulatedSamples_ = 0;
    // The pixel jitter and the first BSDF direction come from two independent stratified sequences per
    // pixel, one for the accumulation's even frames and one for its odd frames (stratified2D in
    // shaders/rng.glsl): frames taken in turns into two halves, as the error estimate does
    // (metrics/ErrorEstimate.h), stay independent estimates of the image. Points used so far of each.
    uint32_t accumulatedFrames_ = 0;
    uint32_t stratifiedSamples_[2] = {0, 0};
};

}  // namespace ripple::core
