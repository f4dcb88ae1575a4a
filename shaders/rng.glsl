// Random numbers keyed by what they are for, never by thread: (pixel, sample index, bounce, dimension
// group, seed) -> four uniforms. The same pixel sample gets the same numbers however the work is split
// across invocations, queues or ranks, so images are reproducible bit for bit. The hash is pcg4d of
// Jarzynski & Olano, "Hash Functions for GPU Rendering" (JCGT 2020).
//
// The path tracer's dimensions (random4) are low-discrepancy: within one render() call, a pixel's samples
// are the first points of the 4D Sobol sequence, each dimension Owen-scrambled and the point order
// shuffled, with seeds hashed from (pixel, the call's first sample, bounce, group, seed) (Burley,
// "Practical Hash-based Owen Scrambling", JCGT 2020). So a frame of n samples stratifies the pixel area,
// the light and the BSDF lobes the way n jittered strata would, in every pair of its dimensions, while
// distinct frames, pixels, bounces and groups stay independent randomizations: a frame is one unbiased
// randomized-QMC estimate, and the spread between frames (apps/common/ErrorEstimate.h) measures its error
// honestly. A frame of one sample is a plain random sample. The volume tracking loops draw streams of
// their own (volume.glsl).
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

// Generator matrices of Sobol dimensions 2 to 4 as direction numbers, most significant bit first, from
// the primitive polynomials x + 1, x^2 + x + 1, x^3 + x + 1 and Joe & Kuo's initial numbers (1; 1, 3;
// 1, 3, 1). Dimension 1 is the van der Corput sequence, the bit reversal of the index.
const uint SOBOL_DIRECTIONS[96] = uint[96](
    0x80000000u, 0xc0000000u, 0xa0000000u, 0xf0000000u, 0x88000000u, 0xcc000000u, 0xaa000000u, 0xff000000u,
    0x80800000u, 0xc0c00000u, 0xa0a00000u, 0xf0f00000u, 0x88880000u, 0xcccc0000u, 0xaaaa0000u, 0xffff0000u,
    0x80008000u, 0xc000c000u, 0xa000a000u, 0xf000f000u, 0x88008800u, 0xcc00cc00u, 0xaa00aa00u, 0xff00ff00u,
    0x80808080u, 0xc0c0c0c0u, 0xa0a0a0a0u, 0xf0f0f0f0u, 0x88888888u, 0xccccccccu, 0xaaaaaaaau, 0xffffffffu,
    0x80000000u, 0xc0000000u, 0x60000000u, 0x90000000u, 0xe8000000u, 0x5c000000u, 0x8e000000u, 0xc5000000u,
    0x68800000u, 0x9cc00000u, 0xee600000u, 0x55900000u, 0x80680000u, 0xc09c0000u, 0x60ee0000u, 0x90550000u,
    0xe8808000u, 0x5cc0c000u, 0x8e606000u, 0xc5909000u, 0x6868e800u, 0x9c9c5c00u, 0xeeee8e00u, 0x5555c500u,
    0x8000e880u, 0xc0005cc0u, 0x60008e60u, 0x9000c590u, 0xe8006868u, 0x5c009c9cu, 0x8e00eeeeu, 0xc5005555u,
    0x80000000u, 0xc0000000u, 0x20000000u, 0x50000000u, 0xf8000000u, 0x74000000u, 0xa2000000u, 0x93000000u,
    0xd8800000u, 0x25400000u, 0x59e00000u, 0xe6d00000u, 0x78080000u, 0xb40c0000u, 0x82020000u, 0xc3050000u,
    0x208f8000u, 0x51474000u, 0xfbea2000u, 0x75d93000u, 0xa0858800u, 0x914e5400u, 0xdbe79e00u, 0x25db6d00u,
    0x58800080u, 0xe54000c0u, 0x79e00020u, 0xb6d00050u, 0x800800f8u, 0xc00c0074u, 0x200200a2u, 0x50050093u);

// Point `index` of the 4D Sobol sequence, as 32-bit fixed-point coordinates.
uvec4 sobol4(uint index) {
    uvec4 x = uvec4(bitfieldReverse(index), 0u, 0u, 0u);
    for (uint bit = 0u; index != 0u; ++bit, index >>= 1u) {
        if ((index & 1u) != 0u)
            x.yzw ^= uvec3(SOBOL_DIRECTIONS[bit], SOBOL_DIRECTIONS[32u + bit], SOBOL_DIRECTIONS[64u + bit]);
    }
    return x;
}

// A random base-2 Owen scramble of a 32-bit fixed-point coordinate (Laine & Karras' hash with Burley's
// constants, applied to the bit-reversed value so that each bit flips depending on all bits above it).
uint owenScramble(uint x, uint seed) {
    x = bitfieldReverse(x);
    x += seed;
    x ^= x * 0x6c50b47cu;
    x ^= x * 0xb82f1e52u;
    x ^= x * 0xc7afe638u;
    x ^= x * 0x8d22f6e6u;
    return bitfieldReverse(x);
}

// Four uniform numbers in [0, 1), 24 bits each (so 1.0 is never returned), for sample `sampleIndex` of a
// pixel in the render() call whose first sample is `frameFirstSample` (FrameConstants).
vec4 random4(uint pixel, uint sampleIndex, uint frameFirstSample, uint bounce, uint group, uint seed) {
    uvec4 seeds = pcg4d(uvec4(pixel, frameFirstSample, (bounce << 4u) | group, seed));
    uint shuffle = pcg4d(seeds).x;
    uvec4 x = sobol4(owenScramble(sampleIndex - frameFirstSample, shuffle));
    x = uvec4(owenScramble(x.x, seeds.x), owenScramble(x.y, seeds.y), owenScramble(x.z, seeds.z), owenScramble(x.w, seeds.w));
    return vec4(x >> 8u) * (1.0 / 16777216.0);
}

#endif
