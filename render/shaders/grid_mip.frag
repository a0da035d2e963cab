#version 450 core
// Reference MIP: march the trilinear grid (R32F 3D texture) along the ray in fixed steps, keep the max.
#include "ray_common.glsl"

// One chunk of the grid's z range (all of it unless the volume exceeds one 3D texture): texel i holds
// grid point uChunkOrigin + i; GL_LINEAR = trilinear reconstruction.
uniform sampler3D uVolume;
uniform vec3 uDims;       // grid points per axis, of the whole volume
uniform vec3 uChunkOrigin; // the grid point of the chunk's texel 0
uniform vec3 uChunkDims;   // the chunk texture's texels per axis
uniform vec2 uChunkZ;      // the z range (index units) whose samples this chunk takes; x < -1e30: all
uniform float uStep;      // step in index units (<= 0.5 voxel along every axis)

layout(location = 0) out float outValue;

float sampleAt(vec3 xIndex) { return texture(uVolume, (xIndex - uChunkOrigin + 0.5) / uChunkDims).r; }

void main() {
    vec3 origin, dir;
    float farT;
    pixelRay(gl_FragCoord.xy, origin, dir, farT);
    vec2 span = clipRayToBox(origin, dir, vec3(0.0), uDims - 1.0);
    float tIn = max(span.x, 0.0);
    float tOut = min(span.y, farT);
    if (tIn > tOut) {
        outValue = NEG_INF;
        return;
    }
    // The samples are those of the whole ray whatever the chunk, so that chunks together give the image
    // of one texture; a chunk takes the ones whose z lies in its range (widened by a hundredth of a
    // step, so a sample on the face between two chunks is taken by both rather than by neither).
    int steps = int(floor((tOut - tIn) / uStep));
    int first = 0, last = steps;
    bool takeEnd = true;
    if (uChunkZ.x >= -1e30) {
        float zEnd = origin.z + tOut * dir.z;
        takeEnd = zEnd >= uChunkZ.x - 1e-3 && zEnd <= uChunkZ.y + 1e-3; // rays leave through z faces too
        if (abs(dir.z) < 1e-30) {
            float z = origin.z + tIn * dir.z;
            if (z < uChunkZ.x || z > uChunkZ.y) last = -1;
        } else {
            // Clamped as floats: a ray almost parallel to the chunk faces gives huge sample indices.
            float a = ((uChunkZ.x - origin.z) / dir.z - tIn) / uStep;
            float b = ((uChunkZ.y - origin.z) / dir.z - tIn) / uStep;
            first = int(ceil(clamp(min(a, b) - 0.01, 0.0, float(steps) + 1.0)));
            last = int(floor(clamp(max(a, b) + 0.01, -1.0, float(steps))));
        }
    }
    float best = takeEnd ? sampleAt(origin + tOut * dir) : NEG_INF;
    for (int i = first; i <= last; ++i) best = max(best, sampleAt(origin + (tIn + float(i) * uStep) * dir));
    outValue = best;
}
