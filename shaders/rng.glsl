// Random numbers keyed by what they are for, never by thread: (pixel, sample index, bounce, dimension
// group, seed) -> four uniforms. The same pixel sample gets the same numbers however the work is split
// across invocations, queues or ranks, so images are reproducible bit for bit. The hash is pcg4d of
// Jarzynski & Olano, "Hash Functions for GPU Rendering" (JCGT 2020).
#ifndef RIPPLE_RNG_GLSL
#define RIPPLE_RNG_GLSL

uvec4 pcg4d(uvec4 v) {
    v = v * 1664525u + 1013904223u;
    v.x += v.y * v.w;
    v.y += v.z * v.x;
    v.z += v.x * v.y;
    v.w += v.y * v.z;
    v ^= v >> 16u;
    v.x += v.y * v.w;
    v.y += v.z * v.x;
    v.z += v.x * v.y;
    v.w += v.y * v.z;
    return v;
}

// Dimension groups: each consumer of random numbers has its own, so no two read the same ones.
const uint RNG_CAMERA = 0u;     // pixel jitter (xy)
const uint RNG_LIGHT = 1u;      // light choice (x), point on the light (yz), opacity (w)
const uint RNG_BSDF = 2u;       // lobe choice (x), direction (yz), Russian roulette (w)
const uint RNG_VOLUME = 3u;     // free-flight sampling: a stream (volume.glsl), counter in the high bits
const uint RNG_VOLUME_SHADOW = 4u; // ratio tracking of shadow rays: a stream likewise

// Four uniform numbers in [0, 1), 24 bits each (so 1.0 is never returned).
vec4 random4(uint pixel, uint sampleIndex, uint bounce, uint group, uint seed) {
    uvec4 h = pcg4d(uvec4(pixel, sampleIndex, (bounce << 4u) | group, seed));
    return vec4(h >> 8u) * (1.0 / 16777216.0);
}

#endif
