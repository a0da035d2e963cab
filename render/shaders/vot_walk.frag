#version 450 core
// Walk strategy: each pixel walks its ray front to back through a cell -> Vot grid, stepping over whole
// bricks and whole Vot boxes that cannot raise its max and evaluating the Vots that can.
#include "vot_common.glsl"
#include "ray_common.glsl"
#include "vot_ray_max.glsl"

uniform usampler3D uCellVot; // R32UI, one texel per cell: index into vots[], or EMPTY_CELL (background)
uniform sampler3D uBrickMax; // R32F, one texel per brick: max upperBound of the Vots touching it, or -inf
uniform ivec3 uCells;        // cells per axis (grid points - 1)
uniform usamplerBuffer uVotBox; // RGBA32UI per Vot: lo.x | lo.y << 16, lo.z | hi.x << 16, hi.y | hi.z << 16, bound bits
uniform int uBrickShift;     // a brick is (1 << uBrickShift)^3 cells
uniform int uDebug; // TEMP
uniform int uCull;           // 1: step over bricks and Vots whose bound cannot beat the pixel's max

const uint EMPTY_CELL = 0xffffffffu;

layout(location = 0) out float outValue;

void main() {
    vec3 origin, dir;
    float farT;
    pixelRay(origin, dir, farT);
    vec2 span = clipRayToBox(origin, dir, vec3(0.0), vec3(uCells));
    float tIn = max(span.x, 0.0);
    float tOut = min(span.y, farT);
    float best = NEG_INF;
    int nIter = 0, nEval = 0, nBrick = 0, nEmpty = 0, nVotSkip = 0; // TEMP
    bool walking = tIn <= tOut;
    vec3 safeDir = mix(dir, vec3(1e-30), lessThan(abs(dir), vec3(1e-30)));
    vec3 invDir = 1.0 / safeDir;
    bvec3 up = greaterThan(safeDir, vec3(0.0));
    ivec3 cell = clamp(ivec3(floor(origin + tIn * dir)), ivec3(0), uCells - 1);
    // Every step moves at least one axis past the block it leaves and none backwards, so the walk ends
    // within the sum of the sides; the budget only guards against the unforeseen.
    int budget = uCells.x + uCells.y + uCells.z + 3;
    // Two nested loops (walk to the next Vot worth evaluating, then evaluate it) rather than one loop
    // that may evaluate at any step: the rasteriser shades several pixels in lockstep, and this way they
    // evaluate together instead of each paying for its neighbours' evaluations at every step.
    while (walking) {
        uint candidate = EMPTY_CELL;
        while (walking && candidate == EMPTY_CELL) {
            ++nIter;
            ivec3 lo, hi; // the block of cells [lo, hi) the ray leaves next; it contains `cell`
            ivec3 brick = cell >> uBrickShift;
            float brickMax = texelFetch(uBrickMax, brick, 0).r;
            if (brickMax == NEG_INF || (uCull != 0 && brickMax <= best)) {
                lo = brick << uBrickShift;
                hi = min(lo + (1 << uBrickShift), uCells);
                ++nBrick;
            } else {
                uint id = texelFetch(uCellVot, cell, 0).r;
                if (id == EMPTY_CELL) {
                    lo = cell;
                    hi = cell + 1;
                    ++nEmpty;
                } else {
                    uvec4 box = texelFetch(uVotBox, int(id));
                    lo = ivec3(box.x & 0xffffu, box.x >> 16, box.y & 0xffffu);
                    hi = ivec3(box.y >> 16, box.z & 0xffffu, box.z >> 16);
                    if (uCull == 0 || uintBitsToFloat(box.w) > best) candidate = id; else ++nVotSkip;
                }
            }
            // Leave the block: the first face crossed sets the axis that moves past it; the other axes
            // follow the ray, clamped into the block and never backwards (rounding cannot skip cells).
            vec3 tFace = (vec3(mix(lo, hi, up)) - origin) * invDir;
            float tExit = min(min(tFace.x, tFace.y), tFace.z);
            int axis = tFace.x <= tFace.y && tFace.x <= tFace.z ? 0 : (tFace.y <= tFace.z ? 1 : 2);
            ivec3 at = ivec3(floor(origin + tExit * dir));
            cell = mix(clamp(at, lo, cell), clamp(at, cell, hi - 1), up);
            cell[axis] = up[axis] ? hi[axis] : lo[axis] - 1;
            if (tExit > tOut || any(lessThan(cell, ivec3(0))) || any(greaterThanEqual(cell, uCells)) ||
                --budget <= 0)
                walking = false;
        }
        float value;
        // The whole box is evaluated, exactly as the raster strategy does for this Vot.
        if (uDebug == 9 && candidate != EMPTY_CELL) { best = max(best, vots[candidate].lowerBound); ++nEval; } else
        if (candidate != EMPTY_CELL && votRayMax(candidate, origin, dir, farT, value)) {
            best = max(best, value);
            ++nEval;
        }
    }
    outValue = best;
    if (uDebug == 1) outValue = float(nIter);
    if (uDebug == 2) outValue = float(nEval);
    if (uDebug == 3) outValue = float(nBrick);
    if (uDebug == 4) outValue = float(nEmpty);
    if (uDebug == 5) outValue = float(nVotSkip);
}
