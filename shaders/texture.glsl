// Texture lookup from the scene's one texel buffer: the input transform, wrap modes (repeat, clamp to
// edge, mirrored repeat), nearest or bilinear filtering, sRGB decoding of Rgba8Srgb texels, and the
// output transform. Texel row 0 is at v = 0. Needs SceneDesc and the buffer views of pt_common.glsl.
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

vec4 sampleTexture(SceneDesc scene, int textureIndex, vec2 uv) {
    TextureRecord tex = TexturesRef(scene.textures).textures[textureIndex];
    mat4 inTransform = mat4(tex.inTransform[0], tex.inTransform[1], tex.inTransform[2], tex.inTransform[3]);
    mat4 outTransform = mat4(tex.outTransform[0], tex.outTransform[1], tex.outTransform[2], tex.outTransform[3]);
    vec2 st = (inTransform * vec4(uv, 0.0, 1.0)).xy;
    vec2 size = vec2(tex.width, tex.height);
    vec4 value;
    if (tex.linearFilter == 0u) {
        vec2 i = floor(st * size);
        value = fetchTexel(tex, scene.texels, wrapTexel(i.x, size.x, tex.wrapS), wrapTexel(i.y, size.y, tex.wrapT));
    } else {
        // Texel centres sit at half-integers: blend the four around st.
        vec2 x = st * size - 0.5;
        vec2 i = floor(x);
        vec2 f = x - i;
        int x0 = wrapTexel(i.x, size.x, tex.wrapS), x1 = wrapTexel(i.x + 1.0, size.x, tex.wrapS);
        int y0 = wrapTexel(i.y, size.y, tex.wrapT), y1 = wrapTexel(i.y + 1.0, size.y, tex.wrapT);
        value = mix(mix(fetchTexel(tex, scene.texels, x0, y0), fetchTexel(tex, scene.texels, x1, y0), f.x),
                    mix(fetchTexel(tex, scene.texels, x0, y1), fetchTexel(tex, scene.texels, x1, y1), f.x), f.y);
    }
    return outTransform * value;
}

#endif
