#version 450 core
// Exact grid projection: walk the ray cell by cell; in each cell the trilinear interpolant along the ray
// is a cubic, whose max, min or integral is taken in closed form (mip, minip, aip).
#include "ray_common.glsl"
#include "cubic_along_ray.glsl"

// One chunk of the grid's z range (all of it unless the volume exceeds one 3D texture): texel i holds
// grid point uChunkOrigin + i. The chunk owns the cells with uCellZ.x <= z < uCellZ.y.
// GridRenderer defines VOLUME_SAMPLER as isampler3D or usampler3D for samples uploaded in their
// 8- or 16-bit source type: texelFetch then gives the integer, whose float is the float-held sample.
#ifndef VOLUME_SAMPLER
#define VOLUME_SAMPLER sampler3D
#endif
uniform VOLUME_SAMPLER uVolume;
uniform vec3 uDims;        // grid points per axis, of the whole volume
uniform vec3 uChunkOrigin; // the grid point of the chunk's texel 0
uniform ivec2 uCellZ;      // the cells' z range this chunk owns: [x, y)
uniform int uMode;         // 0 mip, 1 minip, 2 aip (mean along the clipped ray)
// What a cell with a NaN or Inf corner (no data) counts as in minip and aip: the lowest finite sample, as
// the fit's omitted no-data cells do; mip skips such a cell.
uniform float uNoDataValue;

layout(location = 0) out float outValue;

const float POS_INF = uintBitsToFloat(0x7f800000u);

float corner(ivec3 p) { return float(texelFetch(uVolume, p - ivec3(uChunkOrigin), 0).r); }

// The trilinear interpolant of cell `cell` along p(u) = local + u dir (local: the segment's entry point
// relative to the cell's corner) as g(u) = g.x + g.y u + g.z u^2 + g.w u^3.
// cornerRange: the least and greatest corner, which bound the interpolant anywhere in the cell.
// noData: some corner is NaN or Inf (then g and cornerRange mean nothing).
vec4 cellCubic(ivec3 cell, vec3 local, vec3 dir, out vec2 cornerRange, out bool noData) {
    float c000 = corner(cell), c100 = corner(cell + ivec3(1, 0, 0));
    float c010 = corner(cell + ivec3(0, 1, 0)), c110 = corner(cell + ivec3(1, 1, 0));
    float c001 = corner(cell + ivec3(0, 0, 1)), c101 = corner(cell + ivec3(1, 0, 1));
    float c011 = corner(cell + ivec3(0, 1, 1)), c111 = corner(cell + ivec3(1, 1, 1));
    vec4 low = vec4(c000, c100, c010, c110), high = vec4(c001, c101, c011, c111);
    noData = any(isnan(low)) || any(isnan(high)) || any(isinf(low)) || any(isinf(high));
    cornerRange = vec2(min(min(min(c000, c100), min(c010, c110)), min(min(c001, c101), min(c011, c111))),
                       max(max(max(c000, c100), max(c010, c110)), max(max(c001, c101), max(c011, c111))));
    // f(x, y, z) = a + bx x + by y + bz z + bxy x y + bxz x z + byz y z + bxyz x y z on the unit cube.
    float a = c000;
    float bx = c100 - c000, by = c010 - c000, bz = c001 - c000;
    float bxy = c110 - c100 - c010 + c000;
    float bxz = c101 - c100 - c001 + c000;
    float byz = c011 - c010 - c001 + c000;
    float bxyz = c111 - c110 - c101 - c011 + c100 + c010 + c001 - c000;
    float x = local.x, y = local.y, z = local.z;
    float fx = bx + bxy * y + bxz * z + bxyz * y * z; // the partial derivatives at the entry point
    float fy = by + bxy * x + byz * z + bxyz * x * z;
    float fz = bz + bxz * x + byz * y + bxyz * x * y;
    vec4 g;
    g.x = a + bx * x + by * y + bz * z + bxy * x * y + bxz * x * z + byz * y * z + bxyz * x * y * z;
    g.y = fx * dir.x + fy * dir.y + fz * dir.z;
    g.z = bxy * dir.x * dir.y + bxz * dir.x * dir.z + byz * dir.y * dir.z +
          bxyz * (x * dir.y * dir.z + y * dir.x * dir.z + z * dir.x * dir.y);
    g.w = bxyz * dir.x * dir.y * dir.z;
    return g;
}

float missValue() { return uMode == 1 ? POS_INF : NEG_INF; }

void main() {
    vec3 origin, dir;
    float farT;
    pixelRay(gl_FragCoord.xy, origin, dir, farT);
    vec2 box = clipRayToBox(origin, dir, vec3(0.0), uDims - 1.0);
    vec2 span = clipRayToSlab(origin, dir, vec2(max(box.x, 0.0), min(box.y, farT)));
    if (span.x > span.y) { // the ray misses the grid (or the slab): background in every chunk
        outValue = missValue();
        return;
    }
    // Every chunk divides by the whole ray's length, so the chunks' parts add up to the mean.
    float wholeLength = span.y - span.x;

    // The chunk's share of the span: the z range of its cells (a ray parallel to the chunk faces belongs
    // to the chunk whose half-open range holds its z, the last chunk also holding the far face).
    float zLo = float(uCellZ.x), zHi = float(uCellZ.y);
    bool lastChunk = uCellZ.y >= int(uDims.z) - 1;
    vec2 own = span;
    if (dir.z == 0.0) {
        float z = origin.z;
        if (z < zLo || (z >= zHi && !(lastChunk && z == zHi))) own = vec2(1.0, 0.0);
    } else {
        // Only faces between chunks cut: the grid's own z faces are already in span, and cutting there
        // again would round a short ray's length differently from wholeLength. Neighbours compute a shared
        // face's t alike, so their parts tile the span.
        float ta = uCellZ.x > 0 ? (zLo - origin.z) / dir.z : (dir.z > 0.0 ? -POS_INF : POS_INF);
        float tb = !lastChunk ? (zHi - origin.z) / dir.z : (dir.z > 0.0 ? POS_INF : -POS_INF);
        own = vec2(max(span.x, min(ta, tb)), min(span.y, max(ta, tb)));
    }
    float result = uMode == 2 ? 0.0 : missValue();
    if (own.x <= own.y) {
        // 3D DDA over the cells [i, i+1]^3, i in [0, dims-2] (z in the chunk's range).
        ivec3 cellLo = ivec3(0, 0, uCellZ.x);
        ivec3 cellHi = ivec3(int(uDims.x) - 2, int(uDims.y) - 2, uCellZ.y - 1);
        // An axis the ray runs parallel to is never crossed (its face distance is +inf).
        bvec3 parallel = lessThan(abs(dir), vec3(1e-30));
        vec3 inv = 1.0 / mix(dir, vec3(1.0), parallel);
        bvec3 forward = greaterThan(dir, vec3(0.0));
        ivec3 stepDir = ivec3(forward) * 2 - 1;
        // The cell of the entry point, nudged along the ray so a start on a cell face picks the cell the
        // ray goes into.
        float t = own.x;
        vec3 start = origin + (t + 1e-4 * min(1.0, own.y - own.x)) * dir;
        ivec3 cell = clamp(ivec3(floor(start)), cellLo, cellHi);
        int budget = int(uDims.x + uDims.y + uDims.z) + 3;
        float total = 0.0;
        for (int i = 0; i < budget; ++i) { // at least once: a ray may only touch the grid
            vec3 tFace = mix((vec3(cell) + vec3(forward) - origin) * inv, vec3(POS_INF), parallel);
            // Never backwards (a face behind t by rounding): the segments tile [own.x, own.y] once.
            float tExit = clamp(min(min(tFace.x, tFace.y), tFace.z), t, own.y);
            // Leave through the nearest face; ties (an edge or a corner) step every axis that meets it.
            ivec3 next = cell + ivec3(lessThanEqual(tFace, vec3(tExit))) * stepDir;
            // Where the cells end before own.y by rounding, the last cell takes the rest of the span, so a
            // short ray's mean is not shortened by a rounding of its length.
            bool last = tExit >= own.y || any(lessThan(next, cellLo)) || any(greaterThan(next, cellHi));
            if (last) tExit = own.y;
            float len = tExit - t;
            vec2 cornerRange;
            bool noData;
            vec4 g = cellCubic(cell, origin + t * dir - vec3(cell), dir, cornerRange, noData);
            // A cell whose corners cannot beat the value so far cannot change it: skip its roots.
            if (noData) {
                if (uMode == 1) result = min(result, uNoDataValue);
                else if (uMode == 2) total += uNoDataValue * len;
            } else if (uMode == 0) result = cornerRange.y > result ? max(result, cubicMaxOver(g, len)) : result;
            else if (uMode == 1) result = cornerRange.x < result ? min(result, cubicMinOver(g, len)) : result;
            else total += cubicIntegralOver(g, len);
            t = tExit;
            if (last) break;
            cell = next;
        }
        if (uMode == 2) {
            // A ray that only touches the grid (zero length) has its one value as the mean.
            vec2 unused;
            bool noData;
            float touch = cellCubic(cell, origin + t * dir - vec3(cell), dir, unused, noData).x;
            result = wholeLength > 0.0 ? total / wholeLength : (noData ? uNoDataValue : touch);
        }
    }
    outValue = result;
}
