// The path tracer's GPU state: per-path data that stays at home, shadow requests, per-frame constants and
// the one parameter block every pt_*.comp stage receives as push constants.
#ifndef RIPPLE_SHARED_PATH_H
#define RIPPLE_SHARED_PATH_H
#include "common.h"

RIPPLE_GPU_BEGIN

RIPPLE_CONST uint PATH_FLAG_CAMERA = 1u;  // no scattering yet: a miss shows the background, not the ambient light
RIPPLE_CONST uint PATH_PASS_THROUGH_SHIFT = 8u;   // (flags >> this) & 0xFF = pass-throughs of transparent
                                                  // surfaces so far
RIPPLE_CONST uint PATH_MAX_PASS_THROUGHS = 16u;   // more than this and the path ends (bounds the bounce loop)
RIPPLE_CONST uint PATH_DEPTH_SHIFT = 16u;         // flags >> this = surface interactions so far (scattering
                                                  // events; pass-throughs do not count), at most 1024

// The home part of a path, parallel to its ray in the same queue slot (the ray is gpu::Ray).
struct PathState {
    vec4 throughput;  // rgb; w: distance from the last scattering point to this ray's origin (pass-throughs)
    uint slot;        // the pixel sample's slot in the pass: k * width * height + y * width + x for the pass's
                      // k-th sample of pixel (x, y), row 0 at the bottom (pixelSample in pt_common.glsl)
    uint flags;       // PATH_FLAG_* | pass-throughs << PATH_PASS_THROUGH_SHIFT | depth << PATH_DEPTH_SHIFT
    float bsdfPdf;    // solid-angle pdf of the BSDF sample that made this ray (for MIS at what it finds); 0: none
    float ambientPdf; // solid-angle pdf with which next-event estimation at the same vertex would have picked the
                      // ambient light in this ray's direction (its chance included): MIS if the ray escapes
};

// What an unoccluded shadow ray adds to its pixel sample (the ray itself sits in a gpu::Ray queue beside it).
struct ShadowRequest {
    vec4 contribution;  // rgb; w unused
    uint slot;          // the PathState::slot it adds to
    uint pad0;
    uint pad1;
    uint pad2;
};

// What the rank that owns a closest hit learns about the surface there (pt_surface), so that the path's
// home rank can shade it (pt_shade) without any of the scene's geometry, attributes or textures: this is
// the "packed material" a data-parallel ray carries home. Directions are world space.
struct SurfaceRecord {
    vec4 position;         // xyz: hit point; w: hit t along the ray
    vec4 geometricNormal;  // xyz: unit, facing the incoming ray; w: opacity
    vec4 shadingNormal;    // xyz: unit, on the side of geometricNormal; w: this point's light density (see
                           // surfaceLightPdf in lights.glsl), 0 when it is not part of a light
    vec4 baseColor;        // rgb: base color with vertex color and texture applied; w: metallic
    vec4 emission;         // rgb: emitted radiance; w: GGX alpha (roughness^2, floored)
    vec4 layers;           // x: transmission, y: clearcoat, z: clearcoat GGX alpha, w: ior
    uint status;           // the hit's status (HIT_MISS, HIT_FOUND, HIT_FLAG_*): shade treats all but HIT_FOUND as a miss
    uint materialKind;     // MATERIAL_*
    float f0;              // dielectric reflectance at normal incidence, from the ior
    uint pad0;
    // The id channels (pt_channels): the application's primitive index (quads count once), the surface's
    // and the instance's "id" (~0u when unset). Written by pt_surface via writeSurfaceIds (ids.glsl).
    uint primitiveId;
    uint objectId;
    uint instanceId;
    uint pad1;
};

// Workgroup counts of one vkCmdDispatchIndirect (VkDispatchIndirectCommand).
struct DispatchSize {
    uint x;
    uint y;
    uint z;
};

// Counters the kernels bump with atomics. With one rank the queue lengths stay on the device: between
// bounces pt_queue_advance turns the appends into the lengths the next bounce consumes and the dispatch
// sizes that launch it. With several ranks the host reads the appends after each bounce instead (the
// exchange needs them) and passes the lengths as StageParams.count.
struct PathCounters {
    uint nextPaths;     // rays appended to the next path queue
    uint shadowRays;    // shadow rays appended
    uint nonFinite;     // samples dropped by pt_accumulate
    uint flagged;       // traversals flagged HIT_FLAG_* (treated as misses)
    uint pathCount;     // length of the path queue the current bounce consumes
    uint shadowCount;   // length of the shadow queue it consumes
    uint pathsTraced;   // sums of the two over the bounces since the host last cleared them
    uint shadowsTraced;
    DispatchSize pathGroups;        // pathCount in workgroups of the path stages
    DispatchSize shadowGroups;      // shadowCount in workgroups of the path stages
    DispatchSize pathTraceGroups;   // the same in workgroups of the trace kernels
    DispatchSize shadowTraceGroups;
    // Volume tracking over the frame, each a 64-bit sum in two words (low, high; countVolumeSteps in
    // volume.glsl carries): real and null collisions of delta tracking (free flight of path rays), the
    // tentative collisions of ratio tracking (shadow rays), and the marches parked for a resume round.
    uint realCollisions[2];
    uint nullCollisions[2];
    uint ratioCollisions[2];
    uint parkedMarches[2];
};

// Parameters of pt_queue_advance.
struct QueueAdvanceParams {
    uint64_t counters;     // PathCounters
    uint capacity;         // queue capacity: longer appends are cut (and were never written)
    uint stageWorkgroup;   // workgroup size of the path stages
    uint traceWorkgroup;   // workgroup size of the trace kernels
    uint pad0;
};

// StageParams.countSource: where a queue stage finds how many items it processes.
RIPPLE_CONST uint COUNT_FROM_PARAMS = 0u;    // StageParams.count
RIPPLE_CONST uint COUNT_PATH_QUEUE = 1u;     // PathCounters.pathCount
RIPPLE_CONST uint COUNT_SHADOW_QUEUE = 2u;   // PathCounters.shadowCount

RIPPLE_CONST uint CAMERA_PERSPECTIVE = 0u;
RIPPLE_CONST uint CAMERA_ORTHOGRAPHIC = 1u;
RIPPLE_CONST uint CAMERA_OMNIDIRECTIONAL = 2u;  // equirectangular: the image spans 360 x 180 degrees

RIPPLE_CONST uint LIGHT_SAMPLING_MIS = 0u;         // light and BSDF sampling, power-heuristic weights
RIPPLE_CONST uint LIGHT_SAMPLING_LIGHTS_ONLY = 1u; // debug: area lights found by next-event estimation only
RIPPLE_CONST uint LIGHT_SAMPLING_BSDF_ONLY = 2u;   // debug: area lights found by BSDF-sampled rays only

RIPPLE_CONST uint OUTPUT_RGBA8_UNORM = 0u;
RIPPLE_CONST uint OUTPUT_RGBA8_SRGB = 1u;
RIPPLE_CONST uint OUTPUT_RGBA32_FLOAT = 2u;

// FrameConstants.shading. Path traced: the renderer "default". Eye light: the renderer "eyeLight", a quick
// look that shows the first surface or volume collision lit from the eye by ambientColor * ambientRadiance
// (f.ambient), times 1 - r + r |cos| with r = eyeLightBlendRatio, plus its emission; no other light,
// no further bounce.
RIPPLE_CONST uint SHADING_PATH_TRACED = 0u;
RIPPLE_CONST uint SHADING_EYE_LIGHT = 1u;

// Constant for a render() call: camera, settings and the frame's buffers.
struct FrameConstants {
    vec4 cameraPosition;   // w: CAMERA_* as float bits
    vec4 cameraForward;    // unit; w: aperture radius (perspective depth of field; 0: pinhole)
    vec4 cameraRight;      // half the screen's width: at unit distance (perspective), in world units
                           // (orthographic), unit (omnidirectional); w: focus distance
    vec4 cameraUp;         // half the screen's height, as cameraRight; w: near clip distance along forward
                           // (perspective, orthographic; 0: none)
    vec4 imageRegion;      // (minX, minY, maxX, maxY) of the screen in [0,1]^2
    vec4 background;       // RGBA seen by camera rays that miss
    vec4 ambient;          // rgb: ambientColor * ambientRadiance, seen by secondary rays that miss; w: its
                           // share of the lights' power (ambientLightChance, core/scene/LightTable.h; 1 when
                           // the scene has no lights), for next-event estimation (ambientChance, pt_shade.comp)
    uint width;
    uint height;
    uint maxPathLength;
    uint seed;
    uint64_t sampleRadiance;  // vec4 per sample slot of the pass (PathState::slot): its RGBA, summed over the bounces
    uint64_t accumulation;    // vec4 per pixel: sum of the accepted samples
    uint64_t sampleCount;     // uint per pixel: accepted samples
    uint64_t depth;           // float per pixel, or 0 when no depth channel was asked for
    uint64_t counters;        // PathCounters
    float maxRadiance;        // clamp of each contribution's largest component; 0: no clamp
    uint lightSampling;       // LIGHT_SAMPLING_*
    float phaseAnisotropy;    // Henyey-Greenstein g of scattering in volumes, in (-1, 1); 0: isotropic
    float cameraFar;          // far clip distance along forward (perspective, orthographic); INFINITY: none
    uint shading;             // SHADING_*
    float eyeLightBlendRatio; // SHADING_EYE_LIGHT: the share of the light that falls off with |cos|
    uint passSamples;         // samples of each pixel a sample pass traces together (the last pass may have fewer)
    uint latestSample;        // the index of this render()'s last sample: the one depth and the surface channels show
    uint pad0;
    uint pad1;
};

// Push constants of every pt_*.comp stage; each reads the fields it needs (0 where unused).
struct StageParams {
    uint64_t frame;        // FrameConstants
    uint64_t scene;        // SceneDesc
    uint64_t paths;        // PathState[] of the queue being consumed (or written, by pt_generate)
    uint64_t rays;         // Ray[] beside it
    uint64_t hits;         // Hit[] beside it
    uint64_t nextPaths;    // PathState[] of the next queue
    uint64_t nextRays;     // Ray[] of the next queue
    uint64_t shadowRays;   // Ray[] of the shadow queue
    uint64_t shadowRequests; // ShadowRequest[] beside it
    uint64_t results;      // pt_resolve: the color buffer; pt_shadow_resolve: uint occlusion per shadow ray
    uint64_t surfaces;     // SurfaceRecord[] beside the queue being consumed (pt_surface writes, pt_shade reads)
    uint count;            // items to process (paths, shadow rays or pixels)
    uint firstPixel;       // pixel of invocation 0 (pt_accumulate, pt_resolve); pt_generate: its sample slot
    uint sampleIndex;      // the pass's first pixel sample (over all render() calls); its k-th is sampleIndex + k
    uint bounce;           // pt_shade: interactions every path in the queue has had (RNG key)
    uint mode;             // pt_resolve: OUTPUT_*
    uint countSource;      // COUNT_*: the queue stages' item count (count, or a queue length on the device)
    uint resumeRound;      // pt_volume, pt_shadow_volume: 0 for the stage's items, r > 0 for the marches
                           // parked in round r - 1 (VolumeParkingHeader)
    uint stratifiedSample; // pt_generate, pt_shade: the pass's first point in its pixel's stratified sequences,
                           // (index << 1) | sequence, its k-th sample's + 2k (PathTracer::render; stratified2D)
    uint64_t volumeParking; // pt_volume, pt_shadow_volume: VolumeParkingHeader then its pools (VolumeParking::run)
};

RIPPLE_GPU_END
#endif
