// Walk strategy, shared by vot_walk.frag and vot_walk.comp: each pixel walks its ray front to back
// through a cell -> Vot grid, stepping over whole bricks and whole Vot boxes that cannot raise its max
// and evaluating the Vots that can, from their 64-byte walk records.
#include "vot_common.glsl"
#include "ray_common.glsl"
#include "cubic_ray_max.glsl"

// Buffer textures, not 3D textures or SSBOs: llvmpipe gathers texel fetches for all lanes at once.
// RGBA32UI: the cell tables of bricks with more than one block (PalettedCells, VotWalkGrid.h), each
// cell's index into its brick's palette in 1 to 16 bits.
layout(binding = WALK_CELL_TABLE_UNIT) uniform usamplerBuffer uCellTable;
// RGBA32UI per brick, x fastest: the bits of the max upperBound of the Vots touching it (or -inf) and
// of the max of that over every brick this view's rays can reach from it (BrickAhead.h); its first
// palette index; its cell table's first word << CELL_TABLE_CODE_BITS | width code (0: no table).
layout(binding = WALK_BRICK_MAX_UNIT) uniform usamplerBuffer uBrickMax;
// RGBA32UI per palette entry, for the block it names: a box [lo, hi) in cells, 16 bits each
// (lo.x | lo.y << 16, lo.z | hi.x << 16, hi.y | hi.z << 16), and the bound's bits (-inf for empty
// blocks). A Vot's box here is the box to step over when it is culled: its own, or its skip box once
// grown (SkipBoxes.h); its own box is in its walk record (uWalkRecord).
layout(binding = WALK_VOT_BOX_UNIT) uniform usamplerBuffer uVotBox;
// WALK_RECORD_TEXELS RGBA32UI texels per palette entry naming a Vot (WalkRecord.h): its box, its
// polynomial around the box centre in box units, the higher terms in 16 bits.
layout(binding = WALK_RECORD_UNIT) uniform usamplerBuffer uWalkRecord;
uniform ivec3 uCells;    // cells per axis (grid points - 1)
uniform ivec3 uBricks;   // bricks per axis
uniform int uBrickShift; // a brick is (1 << uBrickShift)^3 cells
uniform int uCull;       // 1: step over bricks and Vots whose bound cannot beat the pixel's max
// WALK_MODE_MAX, WALK_MODE_MIN (the max of the negated polynomials, with bounds to match: -lowerBound per
// block, and per brick over its blocks), WALK_MODE_MEAN (the integral, every Vot, no culling) or
// WALK_MODE_LENGTH (no walk: the length the mean divides by, 0 for a ray that misses).
uniform int uMode;
// The cells [uDomainLo, uDomainHi) every ray is cut to (the whole grid unless a rank holds one z slab of
// it): outside them nothing counts, not even background. uDomainClips != 0 when they are less than the
// grid, so that a whole-grid frame runs exactly the arithmetic it ran before domains existed.
uniform ivec3 uDomainLo, uDomainHi;
uniform int uDomainClips;
// What a background cell (no Vot: the fit left it out) contributes, in the walked quantity: -inf for
// the max (nothing), -background for the min, background for the mean (per unit length).
uniform float uEmptyValue;

// The ray of this pixel, set once by main() for walkStep(): [gTIn, gTOut] is its part inside the grid,
// the near and far planes and the slab; gRange is what a Vot's max may use (the planes and the slab;
// the Vot's own box clips it further); gTBlock is where the ray entered the block it is in.
vec3 gOrigin, gDir, gInvDir;
bvec3 gUp;
float gTIn, gTOut, gTBlock;
vec2 gRange;

// The box [lo, hi) in cells packed in a texel's first three words (packBoxCorners, VotWalkGrid.h).
void unpackBox(uvec4 texel, out ivec3 lo, out ivec3 hi) {
    lo = ivec3(texel.x & 0xffffu, texel.x >> 16, texel.y & 0xffffu);
    hi = ivec3(texel.y >> 16, texel.z & 0xffffu, texel.z >> 16);
}

// What this pixel's ray takes from the Vot that palette entry `entry` names: its max (of the negated
// polynomial for WALK_MODE_MIN; -inf when the ray misses its box) or its integral, and its box [lo, hi)
// in cells. The whole box is evaluated, as the raster strategy does.
float walkRecordAlongRay(int entry, out ivec3 lo, out ivec3 hi) {
    int base = entry * WALK_RECORD_TEXELS;
    uvec4 r0 = texelFetch(uWalkRecord, base), r1 = texelFetch(uWalkRecord, base + 1);
    uvec4 r2 = texelFetch(uWalkRecord, base + 2), r3 = texelFetch(uWalkRecord, base + 3);
    unpackBox(r0, lo, hi);
    float c[TAYLOR_TERMS];
    c[0] = uintBitsToFloat(r0.w);
    c[1] = uintBitsToFloat(r1.x);
    c[2] = uintBitsToFloat(r1.y);
    c[3] = uintBitsToFloat(r1.z);
    float quantum = uintBitsToFloat(r1.w);
    if (uMode == WALK_MODE_MIN) {
        c[0] = -c[0], c[1] = -c[1], c[2] = -c[2], c[3] = -c[3];
        quantum = -quantum;
    }
    uint steps[8] = uint[8](r2.x, r2.y, r2.z, r2.w, r3.x, r3.y, r3.z, r3.w);
    for (int k = 0; k < 8; ++k) {
        c[4 + 2 * k] = float(bitfieldExtract(int(steps[k]), 0, 16)) * quantum;
        c[5 + 2 * k] = float(int(steps[k]) >> 16) * quantum;
    }
    vec3 boxLo = vec3(lo), boxHi = vec3(hi);
    vec3 centre = 0.5 * (boxLo + boxHi), invScale = 2.0 / (boxHi - boxLo);
    if (uMode == WALK_MODE_MEAN)
        return cubicRayIntegral(c, boxLo, boxHi, centre, invScale, gOrigin, gDir, vec2(gTIn, gTOut));
    float value = NEG_INF;
    cubicRayMax(c, boxLo, boxHi, centre, invScale, gOrigin, gDir, gRange, value);
    return value;
}

// One step of the walk: leaves the block at `cell` (evaluating it first when it is a Vot that can raise
// the max, or for the mean any Vot; a background block adds uEmptyValue) or ends the walk. `best` is the
// max so far, or for the mean the integral so far. With mayEvaluate false, a Vot to evaluate is left as it is, for the next
// call that may.
void walkStep(const bool mayEvaluate, inout ivec3 cell, inout float best, inout bool walking, inout int budget) {
    ivec3 lo, hi; // the block of cells [lo, hi) the ray leaves next; it contains `cell`
    ivec3 brick = cell >> uBrickShift;
    int brickIndex = brick.x + uBricks.x * (brick.y + uBricks.y * brick.z);
    uvec4 brickRecord = texelFetch(uBrickMax, brickIndex);
    float brickMax = uintBitsToFloat(brickRecord.x);
    if (uCull != 0 && uintBitsToFloat(brickRecord.y) <= best) { // nothing further along can raise the max
        walking = false;
        return;
    }
    // llvmpipe runs every texel fetch for all lanes of a SIMD group, inside a branch or not, and the
    // walk waits on memory more than on arithmetic (bench/RESULTS.md): lanes that do not
    // need a fetch read texel 0, which stays in cache, rather than an address of their own.
    bool skipBrick = brickMax == NEG_INF || (uCull != 0 && brickMax <= best);
    ivec3 local = cell - (brick << uBrickShift);
    int inBrick = (((local.z << uBrickShift) | local.y) << uBrickShift) | local.x;
    uint code = brickRecord.w & ((1u << CELL_TABLE_CODE_BITS) - 1u);
    uint bitsLog = max(code, 1u) - 1u; // a cell's index has 2^bitsLog bits
    uint bit = uint(inBrick) << bitsLog;
    uint word = (brickRecord.w >> CELL_TABLE_CODE_BITS) + (bit >> 5);
    uvec4 cellTexel = texelFetch(uCellTable, skipBrick || code == 0u ? 0 : int(word >> 2));
    uint paletteIndex = code == 0u ? 0u : bitfieldExtract(cellTexel[word & 3u], int(bit & 31u), 1 << bitsLog);
    int entry = skipBrick ? 0 : int(brickRecord.z + paletteIndex);
    uvec4 box = texelFetch(uVotBox, entry);
    float bound = uintBitsToFloat(box.w);
    bool empty = bound == NEG_INF; // an empty block: background cells
    bool stepOver = empty || (uCull != 0 && bound <= best);
    if (!mayEvaluate && !skipBrick && !stepOver) return; // left for the next iteration's first step
    if (skipBrick) {
        lo = brick << uBrickShift;
        hi = min(lo + (1 << uBrickShift), uCells);
    } else if (stepOver) {
        unpackBox(box, lo, hi);
    } else if (mayEvaluate) {
        float value = walkRecordAlongRay(skipBrick || stepOver ? 0 : entry, lo, hi);
        best = uMode == WALK_MODE_MEAN ? best + value : max(best, value);
    }
    // Leave the block: the first face crossed sets the axis that moves past it; the other axes
    // follow the ray, clamped into the block and never backwards (rounding cannot skip cells).
    vec3 tFace = (vec3(mix(lo, hi, gUp)) - gOrigin) * gInvDir;
    float tExit = min(min(tFace.x, tFace.y), tFace.z);
    bvec3 first = bvec3(tFace.x == tExit, tFace.y == tExit && tFace.x != tExit,
                        tFace.z == tExit && tFace.x != tExit && tFace.y != tExit);
    // Background: a brick without Vots stepped over whole, or an empty block. A brick skipped by its
    // bound holds nothing that could change the max (for the min, its bound includes its background).
    if (skipBrick ? brickMax == NEG_INF : empty) {
        float len = min(tExit, gTOut) - max(gTBlock, gTIn);
        if (len > 0.0) best = uMode == WALK_MODE_MEAN ? best + uEmptyValue * len : max(best, uEmptyValue);
    }
    gTBlock = tExit;
    ivec3 at = ivec3(floor(gOrigin + tExit * gDir));
    cell = mix(clamp(at, lo, cell), clamp(at, cell, hi - 1), gUp);
    cell = mix(cell, mix(lo - 1, hi, gUp), first);
    if (tExit > gTOut || any(lessThan(cell, uDomainLo)) || any(greaterThanEqual(cell, uDomainHi)) ||
        --budget <= 0)
        walking = false;
}

// The max, min or mean along the ray through the pixel centre `fragCoord` (window coordinates); -inf
// when it meets nothing to take (no Vot, nor for the min and mean any background cell).
float walkPixel(vec2 fragCoord) {
    vec3 origin, dir;
    float farT;
    pixelRay(fragCoord, origin, dir, farT);
    gRange = clipRayToSlab(origin, dir, vec2(0.0, farT));
    vec2 span = clipRayToBox(origin, dir, vec3(uDomainLo), vec3(uDomainHi));
    float tIn = max(span.x, gRange.x);
    float tOut = min(span.y, gRange.y);
    // A Vot crossing the domain's faces counts only inside them: its max or min is taken over the part of
    // the ray in the domain, as its integral already is ([gTIn, gTOut]). Grown by the Vots' own clip
    // slack, so that on the grid's faces a domain takes what the whole grid takes, and domains sharing a
    // face overlap by a sliver, which leaves a min or max over them unchanged.
    if (uDomainClips != 0) {
        vec2 grown = clipRayToBox(origin, dir, vec3(uDomainLo) - CLIP_SLACK, vec3(uDomainHi) + CLIP_SLACK);
        gRange = vec2(max(gRange.x, grown.x), min(gRange.y, grown.y));
    }
    if (uMode == WALK_MODE_LENGTH) return tOut > tIn ? tOut - tIn : 0.0;
    float best = uMode == WALK_MODE_MEAN ? 0.0 : NEG_INF;
    bool walking = tIn <= tOut;
    vec3 safeDir = mix(dir, vec3(1e-30), lessThan(abs(dir), vec3(1e-30)));
    vec3 invDir = 1.0 / safeDir;
    bvec3 up = greaterThan(safeDir, vec3(0.0));
    ivec3 cell = clamp(ivec3(floor(origin + tIn * dir)), uDomainLo, uDomainHi - 1);
    // Every step moves at least one axis past the block it leaves and none backwards, so the walk ends
    // within the sum of the sides; the budget only guards against the unforeseen.
    int budget = uCells.x + uCells.y + uCells.z + 3;
    // One loop that may evaluate at any step, not a walk-then-evaluate pair of loops: the rasteriser
    // shades 8 pixels in lockstep, and nested loops make each wait for the slowest at every Vot.
    // llvmpipe runs an evaluation's code for all 8 lanes whenever one of them evaluates, so each round
    // adds a second step that cannot evaluate: a lane crossing empty or culled blocks moves on twice as
    // fast. A third such step costs more than it saves (bench/RESULTS.md compares them).
    gOrigin = origin, gDir = dir, gInvDir = invDir, gUp = up, gTIn = tIn, gTOut = tOut, gTBlock = tIn;
    while (walking) {
        walkStep(true, cell, best, walking, budget);
        if (walking) walkStep(false, cell, best, walking, budget);
    }
    if (uMode == WALK_MODE_MEAN) return tOut > tIn ? best / (tOut - tIn) : NEG_INF;
    if (uMode == WALK_MODE_MIN) return best == NEG_INF ? NEG_INF : -best;
    return best;
}
