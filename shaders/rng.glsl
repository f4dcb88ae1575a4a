// Random numbers keyed by what they are for, never by thread: (pixel, sample index, bounce, dimension
// group, seed) -> four uniforms. The same pixel sample gets the same numbers however the work is split
// across invocations, queues or ranks, so images are reproducible bit for bit. The pixel jitter and the
// first BSDF direction (stratified2D below) are keyed by the sample's place in the sequence of its frame's
// parity instead, so an image also depends on how its samples were grouped into frames. The hash is pcg4d of
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
const uint RNG_CAMERA = 0u;     // lens (zw); the pixel jitter is stratified2D's (below)
const uint RNG_LIGHT = 1u;      // light choice (x), point on the light (yz; stratified2D's at the first), opacity (w)
const uint RNG_BSDF = 2u;       // lobe choice (x), direction (yz), Russian roulette (w)
const uint RNG_VOLUME = 3u;     // free-flight sampling: a stream (volume.glsl), counter in the high bits
const uint RNG_VOLUME_SHADOW = 4u; // ratio tracking of shadow rays: a stream likewise
// 5, 6 and 7 are stratified2D's (RNG_CAMERA_JITTER, RNG_FIRST_BSDF, RNG_FIRST_LIGHT below), keyed (pixel,
// 0 or 1, group, seed): random4 must not use them.

// Four uniform numbers in [0, 1), 24 bits each (so 1.0 is never returned).
vec4 random4(uint pixel, uint sampleIndex, uint bounce, uint group, uint seed) {
    uvec4 h = pcg4d(uvec4(pixel, sampleIndex, (bounce << 4u) | group, seed));
    return vec4(h >> 8u) * (1.0 / 16777216.0);
}

// Stratified samples for the decisions where a pixel's samples gain most from it: the camera's pixel
// jitter, and the first scattering's BSDF direction and point on a light (or ambient direction). The point
// `stratifiedSample >> 1` of an Owen-scrambled 2D Sobol sequence of its own for each pixel, seed and use
// (`group`), and for each of two sequences (`stratifiedSample & 1`; PathTracer::render deals the
// accumulation's even and odd frames to the two, so that halves of frames taken in turns stay
// independent). Any 2^k consecutive points from the start stratify the square into 2^k cells of every
// shape 2^i x 2^(k-i), so edges, textures and glossy reflections converge faster than with independent
// samples, while each point alone is uniform (unbiased). Sobol's first two dimensions (van der Corput, and
// the one from x + 1, whose direction numbers are v ^ (v >> 1)) form a (0, 2)-sequence; the scramble is
// the hash-based nested uniform scramble of Burley, "Practical Hash-based Owen Scrambling" (JCGT 2020),
// which also shuffles the index per use, so that two uses of one pixel sample (pixel jitter, BSDF
// direction, light point) are not correlated; the shuffle keeps every block of 2^k indices from the start,
// so the stratification survives it.
const uint RNG_CAMERA_JITTER = 5u; // stratified2D's uses
const uint RNG_FIRST_BSDF = 6u;
const uint RNG_FIRST_LIGHT = 7u;

uint owenScramble(uint x, uint seed) {
    x = bitfieldReverse(x);
    x += seed;
    x ^= x * 0x6c50b47cu;
    x ^= x * 0xb82f1e52u;
    x ^= x * 0xc7afe638u;
    x ^= x * 0x8d22f6e6u;
    return bitfieldReverse(x);
}

vec2 stratified2D(uint pixel, uint stratifiedSample, uint group, uint seed) {
    uvec4 scramble = pcg4d(uvec4(pixel, stratifiedSample & 1u, group, seed));
    uint index = owenScramble(stratifiedSample >> 1u, scramble.z);
    uint x = bitfieldReverse(index);
    uint y = 0u;
    for (uint v = 1u << 31u; index != 0u; index >>= 1u, v ^= v >> 1u)
        if ((index & 1u) != 0u) y ^= v;
    return vec2(uvec2(owenScramble(x, scramble.x), owenScramble(y, scramble.y)) >> 8u) * (1.0 / 16777216.0);
}

#endif
