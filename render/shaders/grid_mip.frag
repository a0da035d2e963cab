#version 450 core
// Reference MIP: march the trilinear grid (R32F 3D texture) along the ray in fixed steps, keep the max.
#include "ray_common.glsl"

uniform sampler3D uVolume; // texel i holds grid point i; GL_LINEAR = trilinear reconstruction
uniform vec3 uDims;        // grid points per axis
uniform float uStep;       // step in index units (<= 0.5 voxel along every axis)

layout(location = 0) out float outValue;

float sampleAt(vec3 xIndex) { return texture(uVolume, (xIndex + 0.5) / uDims).r; }

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
    int steps = int(floor((tOut - tIn) / uStep));
    float best = sampleAt(origin + tOut * dir);
    for (int i = 0; i <= steps; ++i) best = max(best, sampleAt(origin + (tIn + float(i) * uStep) * dir));
    outValue = best;
}
