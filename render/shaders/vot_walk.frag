#version 450 core
// Walk strategy on the rasteriser: the back faces of the grid box give each pixel of it one fragment.
// llvmpipe's fragment shading is what the walk was tuned for (vot_walk.glsl).
#include "vot_walk.glsl"

layout(location = 0) out float outValue;

void main() { outValue = walkPixel(gl_FragCoord.xy); }
