// Analytic maximum of a cubic polynomial along a ray (docs/DESIGN.md §5), for the raster and walk MIP shaders.
// Needs vot_common.glsl (CLIP_SLACK) and ray_common.glsl (clipRayToBox) included before it.

// vec4 linearProductN(...): coefficients in u of a product of N linear factors (a_i + b_i u).
vec4 linearProduct1(float a, float b) { return vec4(a, b, 0.0, 0.0); }
vec4 linearProduct2(float a0, float b0, float a1, float b1) {
    return vec4(a0 * a1, a0 * b1 + b0 * a1, b0 * b1, 0.0);
}
vec4 linearProduct3(float a0, float b0, float a1, float b1, float a2, float b2) {
    vec4 q = linearProduct2(a0, b0, a1, b1);
    return vec4(q.x * a2, q.x * b2 + q.y * a2, q.y * b2 + q.z * a2, q.z * b2);
}
#include "taylor.glsl"
#include "cubic_along_ray.glsl"

// The polynomial sum_a c_a ((X - p) * invScale)^a along origin + t dir as a cubic g(u), u = t - tIn in
// [0, len], over the part [tIn, tIn + len] of `range` inside the box [lo, hi] grown by `slack` (invScale: 1
// for index units, 1 / half sides for box units). Returns false when the ray misses that part.
bool cubicAlongRay(float c[TAYLOR_TERMS], vec3 lo, vec3 hi, float slack, vec3 p, vec3 invScale, vec3 origin,
                   vec3 dir, vec2 range, out vec4 g, out float len) {
    vec2 span = clipRayToBox(origin, dir, lo - slack, hi + slack);
    float tIn = max(span.x, range.x); // the near plane clips boxes the camera sits in
    float tOut = min(span.y, range.y);
    if (tIn > tOut) return false;
    // Expand from the box entry point, not the near plane: float cancellation (docs/DESIGN.md §5).
    vec3 s = (origin + tIn * dir - p) * invScale;
    g = taylorAlongRay(c, s, dir * invScale); // g(u) = g0 + g1 u + g2 u^2 + g3 u^3
    len = tOut - tIn;
    return true;
}

// Max of the polynomial along the ray, t in `range`, over its box grown by CLIP_SLACK (so that a ray on a
// face shared by two boxes is seen by one of them at least). Returns false (value untouched) when the
// ray misses it.
bool cubicRayMax(float c[TAYLOR_TERMS], vec3 lo, vec3 hi, vec3 p, vec3 invScale, vec3 origin, vec3 dir, vec2 range,
                 out float value) {
    vec4 g;
    float len;
    if (!cubicAlongRay(c, lo, hi, CLIP_SLACK, p, invScale, origin, dir, range, g, len)) return false;
    value = cubicMaxOver(g, len);
    return true;
}

// Integral of the polynomial along the ray, t in `range`, over its box exactly (boxes tile the covered
// cells, so the integrals of the Vots along a ray add up with no overlap); 0 when the ray misses it.
float cubicRayIntegral(float c[TAYLOR_TERMS], vec3 lo, vec3 hi, vec3 p, vec3 invScale, vec3 origin, vec3 dir,
                       vec2 range) {
    vec4 g;
    float len;
    if (!cubicAlongRay(c, lo, hi, 0.0, p, invScale, origin, dir, range, g, len)) return 0.0;
    return cubicIntegralOver(g, len);
}
