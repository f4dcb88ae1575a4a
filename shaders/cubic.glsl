// The turning points of a cubic, which split it into monotone pieces for iso-surface root finding
// (intersect.glsl's structured cells, unstructured.glsl's mesh cells).
#ifndef RIPPLE_CUBIC_GLSL
#define RIPPLE_CUBIC_GLSL

// The roots of the cubic's derivative A s^2 + B s + C strictly inside (0, len), in order: how many (0 to 2) and
// which. The quadratic formula in its cancellation-free form.
uint cubicExtrema(float A, float B, float C, float len, out float first, out float second) {
    float e0 = -1.0, e1 = -1.0;
    if (A != 0.0) {
        float disc = B * B - 4.0 * A * C;
        if (disc > 0.0) {
            float h = -0.5 * (B + (B < 0.0 ? -sqrt(disc) : sqrt(disc)));
            e0 = h / A;
            e1 = h != 0.0 ? C / h : -1.0;
            if (e0 > e1) {
                float t = e0;
                e0 = e1;
                e1 = t;
            }
        }
    } else if (B != 0.0) {
        e0 = -C / B;
    }
    uint count = 0u;
    first = len;
    second = len;
    if (e0 > 0.0 && e0 < len) {
        first = e0;
        ++count;
    }
    if (e1 > 0.0 && e1 < len && e1 != e0) {
        if (count == 0u) first = e1;
        else second = e1;
        ++count;
    }
    return count;
}

#endif
