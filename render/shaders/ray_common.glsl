// Rebuilds a pixel's ray in grid index space from the inverse view-projection (ortho and perspective).
uniform mat4 uClipToIndex; // inverse of projection * view * (index -> world)
uniform vec2 uViewport;    // framebuffer size in pixels

// Ray through the pixel centre `fragCoord` (window coordinates, as gl_FragCoord): origin on the near
// plane, unit direction (index space), and the distance to the far plane. Nothing in front of the near
// plane is ever visible.
void pixelRay(vec2 fragCoord, out vec3 origin, out vec3 dir, out float farT) {
    vec2 ndc = fragCoord / uViewport * 2.0 - 1.0;
    vec4 a = uClipToIndex * vec4(ndc, -1.0, 1.0);
    vec4 b = uClipToIndex * vec4(ndc, 1.0, 1.0);
    origin = a.xyz / a.w;
    vec3 d = b.xyz / b.w - origin;
    farT = length(d);
    dir = d / farT;
}

// Slab test of the ray against the closed box [lo, hi]; returns (tIn, tOut), empty when tIn > tOut.
vec2 clipRayToBox(vec3 origin, vec3 dir, vec3 lo, vec3 hi) {
    // A zero direction component would give 0 * inf = NaN; a tiny one keeps the slab test exact enough.
    vec3 safeDir = mix(dir, vec3(1e-30), lessThan(abs(dir), vec3(1e-30)));
    vec3 inv = 1.0 / safeDir;
    vec3 t0 = (lo - origin) * inv;
    vec3 t1 = (hi - origin) * inv;
    vec3 tMin = min(t0, t1);
    vec3 tMax = max(t0, t1);
    return vec2(max(max(tMin.x, tMin.y), tMin.z), min(min(tMax.x, tMax.y), tMax.z));
}

const float NEG_INF = uintBitsToFloat(0xff800000u);

// The thick slab (Slab.h): a point x (index units) counts when uSlabRange.x <= dot(uSlabPlane.xyz, x) +
// uSlabPlane.w <= uSlabRange.y; uSlabOn == 0: every point counts.
uniform int uSlabOn;
uniform vec4 uSlabPlane;
uniform vec2 uSlabRange;

// The part [tIn, tOut] of `span` along origin + t dir that lies in the slab (all of it without one);
// empty (x > y) when the ray never enters it. The end points are the exact plane crossings.
vec2 clipRayToSlab(vec3 origin, vec3 dir, vec2 span) {
    if (uSlabOn == 0) return span;
    float s0 = dot(uSlabPlane.xyz, origin) + uSlabPlane.w; // signed distance at t = 0
    float ds = dot(uSlabPlane.xyz, dir);                   // its change per unit t
    if (abs(ds) < 1e-30) return s0 >= uSlabRange.x && s0 <= uSlabRange.y ? span : vec2(1.0, 0.0);
    float ta = (uSlabRange.x - s0) / ds, tb = (uSlabRange.y - s0) / ds;
    return vec2(max(span.x, min(ta, tb)), min(span.y, max(ta, tb)));
}
