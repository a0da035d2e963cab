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

// Max of the polynomial sum_a c_a ((X - p) * invScale)^a along origin + t dir, t in [0, farT], over the
// box [lo, hi] grown by CLIP_SLACK (invScale: 1 for index units, 1 / half sides for box units). Returns
// false (value untouched) when the ray misses the box.
bool cubicRayMax(float c[TAYLOR_TERMS], vec3 lo, vec3 hi, vec3 p, vec3 invScale, vec3 origin, vec3 dir, float farT,
                 out float value) {
    vec2 span = clipRayToBox(origin, dir, lo - CLIP_SLACK, hi + CLIP_SLACK);
    float tIn = max(span.x, 0.0); // the near plane clips boxes the camera sits in
    float tOut = min(span.y, farT);
    if (tIn > tOut) return false;

    // Expand from the box entry point, not the near plane: float cancellation (docs/DESIGN.md §5).
    vec3 s = (origin + tIn * dir - p) * invScale;
    vec4 g = taylorAlongRay(c, s, dir * invScale); // g(u) = g0 + g1 u + g2 u^2 + g3 u^3, u in [0, len]
    float len = tOut - tIn;

    value = cubicMaxOver(g, len);
    return true;
}

