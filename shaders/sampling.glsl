// Small sampling and geometry helpers of the shading stage: orthonormal frames, cosine-weighted
// hemisphere sampling, and the self-intersection-free ray origin offset.
#ifndef RIPPLE_SAMPLING_GLSL
#define RIPPLE_SAMPLING_GLSL

const float PI = 3.14159265358979;

// An orthonormal frame (t, b, n) around the unit vector n, continuous except at n.z = -1 (Duff et al.,
// "Building an Orthonormal Basis, Revisited", JCGT 2017).
void orthonormalFrame(vec3 n, out vec3 t, out vec3 b) {
    float s = n.z >= 0.0 ? 1.0 : -1.0;
    float a = -1.0 / (s + n.z);
    float c = n.x * n.y * a;
    t = vec3(1.0 + s * n.x * n.x * a, s * c, -s * n.x);
    b = vec3(c, s + n.y * n.y * a, -n.y);
}

vec3 toWorld(vec3 local, vec3 n) {
    vec3 t, b;
    orthonormalFrame(n, t, b);
    return local.x * t + local.y * b + local.z * n;
}

vec3 toLocal(vec3 v, vec3 n) {
    vec3 t, b;
    orthonormalFrame(n, t, b);
    return vec3(dot(v, t), dot(v, b), dot(v, n));
}

// Cosine-weighted direction about +z (pdf = cos / pi).
vec3 sampleCosineHemisphere(vec2 u) {
    float r = sqrt(u.x);
    float phi = 2.0 * PI * u.y;
    return vec3(r * cos(phi), r * sin(phi), sqrt(max(0.0, 1.0 - u.x)));
}

// Uniform over the unit sphere (pdf 1 / 4 pi).
vec3 sampleUniformSphere(vec2 u) {
    float z = 1.0 - 2.0 * u.x;
    float r = sqrt(max(0.0, 1.0 - z * z));
    float phi = 2.0 * PI * u.y;
    return vec3(r * cos(phi), r * sin(phi), z);
}

float luminance(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }

float maxComponent(vec3 c) { return max(c.x, max(c.y, c.z)); }

// Moves a hit point off its surface along the geometric normal n (pointing to the side the new ray
// leaves from) by a few ULPs of its coordinates, so rounding of the hit point never puts the origin on
// the wrong side; near the origin, where ULPs are tiny, by a small absolute amount instead. The method of
// Waechter & Binder, "A Fast and Robust Method for Avoiding Self-Intersection" (Ray Tracing Gems, ch. 6),
// whose near-origin constants assume a world of unit size: `unit` (SceneDesc.originUnit, at most 1)
// shrinks them for a smaller world, whose surfaces would otherwise all lie within 2^-16 of each other.
vec3 offsetRayOrigin(vec3 p, vec3 n, float unit) {
    float nearOrigin = unit / 32.0;
    float floatScale = unit / 65536.0;
    const float intScale = 256.0;
    ivec3 ulps = ivec3(intScale * n);
    vec3 moved = vec3(intBitsToFloat(floatBitsToInt(p.x) + (p.x < 0.0 ? -ulps.x : ulps.x)),
                      intBitsToFloat(floatBitsToInt(p.y) + (p.y < 0.0 ? -ulps.y : ulps.y)),
                      intBitsToFloat(floatBitsToInt(p.z) + (p.z < 0.0 ? -ulps.z : ulps.z)));
    return mix(moved, p + floatScale * n, lessThan(abs(p), vec3(nearOrigin)));
}

#endif
