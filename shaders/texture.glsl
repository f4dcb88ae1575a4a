// Image lookup from the scene's one texel buffer: wrap modes (repeat, clamp to edge, mirrored repeat),
// nearest or linear filtering of 1D/2D/3D images, sRGB decoding of Rgba8Srgb texels. Texel row 0 is at
// v = 0. Samplers (inputs, transforms) are in sampler.glsl. Needs the buffer views of pt_common.glsl.
#ifndef RIPPLE_TEXTURE_GLSL
#define RIPPLE_TEXTURE_GLSL

layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer TexturesRef { TextureRecord textures[]; };

// Texel index along one axis for the integer coordinate i (as a float, so huge or non-finite coordinates
// never overflow an int conversion); always within [0, n).
int wrapTexel(float i, float n, uint mode) {
    float w;
    if (mode == WRAP_CLAMP_TO_EDGE) {
        w = clamp(i, 0.0, n - 1.0);
    } else if (mode == WRAP_MIRROR_REPEAT) {
        float m = i - 2.0 * n * floor(i / (2.0 * n));   // in [0, 2n)
        w = m < n ? m : 2.0 * n - 1.0 - m;
    } else {
        w = i - n * floor(i / n);
    }
    return clamp(int(w), 0, int(n) - 1);
}

float srgbToLinear(float c) {
    return c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4);
}

vec4 fetchTexel(TextureRecord tex, uint64_t texels, int x, int y) {
    uint index = uint(y) * tex.width + uint(x);
    UintsRef words = UintsRef(texels);
    if (tex.format == TEXTURE_RGBA32_FLOAT) {
        uint first = tex.texelOffset + 4u * index;
        return uintBitsToFloat(uvec4(words.values[first], words.values[first + 1u], words.values[first + 2u],
                                     words.values[first + 3u]));
    }
    vec4 c = unpackUnorm4x8(words.values[tex.texelOffset + index]);
    if (tex.format == TEXTURE_RGBA8_SRGB) c.rgb = vec3(srgbToLinear(c.r), srgbToLinear(c.g), srgbToLinear(c.b));
    return c;
}

// An image at texture coordinate st (z used by 3D images only): wrap modes per axis, nearest, or linear
// between the texel centres (bilinear, trilinear when the image has slices). Slices follow each other in
// the texel buffer, so slice z row y is row z * height + y.
vec4 sampleImage(TextureRecord tex, uint64_t texels, vec3 st) {
    vec3 size = vec3(tex.width, tex.height, tex.depth);
    if (tex.linearFilter == 0u) {
        vec3 i = floor(st * size);
        int z = wrapTexel(i.z, size.z, tex.wrapR);
        return fetchTexel(tex, texels, wrapTexel(i.x, size.x, tex.wrapS), z * int(tex.height) + wrapTexel(i.y, size.y, tex.wrapT));
    }
    // Texel centres sit at half-integers: blend the texels around st.
    vec3 x = st * size - 0.5;
    vec3 i = floor(x);
    vec3 f = x - i;
    int x0 = wrapTexel(i.x, size.x, tex.wrapS), x1 = wrapTexel(i.x + 1.0, size.x, tex.wrapS);
    int y0 = wrapTexel(i.y, size.y, tex.wrapT), y1 = wrapTexel(i.y + 1.0, size.y, tex.wrapT);
    int h = int(tex.height);
    int z0 = tex.depth > 1u ? wrapTexel(i.z, size.z, tex.wrapR) * h : 0;
    vec4 value = mix(mix(fetchTexel(tex, texels, x0, z0 + y0), fetchTexel(tex, texels, x1, z0 + y0), f.x),
                     mix(fetchTexel(tex, texels, x0, z0 + y1), fetchTexel(tex, texels, x1, z0 + y1), f.x), f.y);
    if (tex.depth > 1u) {
        int z1 = wrapTexel(i.z + 1.0, size.z, tex.wrapR) * h;
        vec4 upper = mix(mix(fetchTexel(tex, texels, x0, z1 + y0), fetchTexel(tex, texels, x1, z1 + y0), f.x),
                         mix(fetchTexel(tex, texels, x0, z1 + y1), fetchTexel(tex, texels, x1, z1 + y1), f.x), f.y);
        value = mix(value, upper, f.z);
    }
    return value;
}

#endif
