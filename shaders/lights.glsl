// Next-event estimation toward the scene's lights: directional (irradiance from one direction), point
// (intensity over distance squared) and quad (area sampling: radiance * cos at the light / distance^2 /
// area pdf). Lights are not geometry: rays never hit them, so nothing is counted twice.
#ifndef RIPPLE_LIGHTS_GLSL
#define RIPPLE_LIGHTS_GLSL

layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer LightsRef { LightRecord lights[]; };

struct LightSample {
    vec3 direction;   // unit, from the shading point toward the light
    float distance;   // to the sampled point on the light; +inf for directional lights
    vec3 incident;    // what multiplies f * cos: irradiance-like, already divided by the point's pdf
};

// False when the light sends nothing toward p (behind a one-sided quad, or p on the light).
bool sampleLight(LightRecord light, vec3 p, vec2 u, out LightSample s) {
    s.direction = vec3(0.0, 0.0, 1.0);
    s.distance = 0.0;
    s.incident = vec3(0.0);
    if (light.kind == LIGHT_DIRECTIONAL) {
        s.direction = -light.direction.xyz;
        s.distance = INFINITY;
        s.incident = light.emission.rgb;
        return true;
    }
    vec3 target = light.position.xyz;
    if (light.kind == LIGHT_QUAD) target += u.x * light.edge1.xyz + u.y * light.edge2.xyz;
    vec3 toLight = target - p;
    float d2 = dot(toLight, toLight);
    if (!(d2 > 0.0)) return false;
    s.distance = sqrt(d2);
    s.direction = toLight / s.distance;
    if (light.kind == LIGHT_POINT) {
        s.incident = light.emission.rgb / d2;
        return true;
    }
    float cosLight = -dot(light.direction.xyz, s.direction);
    if (light.twoSided != 0u) cosLight = abs(cosLight);
    if (cosLight <= 0.0) return false;
    s.incident = light.emission.rgb * (cosLight * light.edge1.w / d2);  // edge1.w: area, the inverse pdf
    return true;
}

#endif
