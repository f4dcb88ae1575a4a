// The bits of a FeatureSet (core/render/FeatureSet.h): what a committed world and frame use. Kernels see
// the mask as specialization constant 1 (shaders/features.glsl), so code for a feature that is absent is
// removed when the pipeline is built, not skipped at run time.
#ifndef RIPPLE_SHARED_FEATURES_H
#define RIPPLE_SHARED_FEATURES_H
#include "common.h"

RIPPLE_GPU_BEGIN

// Geometry kinds: bit GEOMETRY_* (shared/scene.h).
RIPPLE_CONST uint FEATURE_TRIANGLES = 1u << 0;
RIPPLE_CONST uint FEATURE_SPHERES = 1u << 1;
RIPPLE_CONST uint FEATURE_CYLINDERS = 1u << 2;
RIPPLE_CONST uint FEATURE_CONES = 1u << 3;     // cones and curves
RIPPLE_CONST uint FEATURE_ISOSURFACES = 1u << 23; // GEOMETRY_ISOSURFACES (bit 4 was taken by volumes)
RIPPLE_CONST uint FEATURE_MESH_ISOSURFACES = 1u << 27; // some of them are in an unstructured mesh's cells
RIPPLE_CONST uint FEATURE_GEOMETRY = 0xFu | FEATURE_ISOSURFACES | FEATURE_MESH_ISOSURFACES;
RIPPLE_CONST uint FEATURE_VOLUMES = 1u << 4;   // the world has volumes: pt_volume and pt_shadow_volume run
RIPPLE_CONST uint FEATURE_TEXTURES = 1u << 5;  // a material reads a texture
RIPPLE_CONST uint FEATURE_EMISSIVE = 1u << 6;  // a material emits
RIPPLE_CONST uint FEATURE_ALPHA = 1u << 7;     // a material has opacity below 1
// Light kinds: bit 8 + the kind of a light record (LIGHT_* in shared/material.h: core::Light::Kind, and
// LIGHT_TRIANGLE for the triangles of emissive surfaces); any of them means shadow rays.
RIPPLE_CONST uint FEATURE_LIGHT_SHIFT = 8u;
RIPPLE_CONST uint FEATURE_LIGHTS = 0xFFu << 8;
// Frame channels besides color.
RIPPLE_CONST uint FEATURE_CHANNEL_DEPTH = 1u << 16;
RIPPLE_CONST uint FEATURE_CHANNEL_ALBEDO = 1u << 17;
RIPPLE_CONST uint FEATURE_CHANNEL_NORMAL = 1u << 18;
RIPPLE_CONST uint FEATURE_CHANNEL_PRIMITIVE_ID = 1u << 19;
RIPPLE_CONST uint FEATURE_CHANNEL_OBJECT_ID = 1u << 20;
RIPPLE_CONST uint FEATURE_CHANNEL_INSTANCE_ID = 1u << 21;
RIPPLE_CONST uint FEATURE_SURFACE_CHANNELS = 0x1Fu << 17;  // written by pt_channels from the first hit
RIPPLE_CONST uint FEATURE_MULTI_RANK = 1u << 22;           // rays cross ranks: exchange stages run
// Material models besides matte (which every scene may use: it is the default material).
RIPPLE_CONST uint FEATURE_PHYSICALLY_BASED = 1u << 24;     // a physicallyBased material
RIPPLE_CONST uint FEATURE_CLEARCOAT = 1u << 25;            // one with a clear coat
RIPPLE_CONST uint FEATURE_TRANSMISSION = 1u << 26;         // one with transmission
// Volume kinds besides structured grids (VOLUME_KIND_* in shared/volume.h): the volume kernels carry
// point location in meshes, NanoVDB's tree walks and AMR block lists only where a world has them.
RIPPLE_CONST uint FEATURE_UNSTRUCTURED_VOLUMES = 1u << 28;
RIPPLE_CONST uint FEATURE_NANOVDB_VOLUMES = 1u << 29;
RIPPLE_CONST uint FEATURE_AMR_VOLUMES = 1u << 30;
RIPPLE_CONST uint FEATURE_ALL = 0x7FFFFFFFu;

RIPPLE_GPU_END
#endif
