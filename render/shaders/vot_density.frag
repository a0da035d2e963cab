#version 450 core
// Density view: each covered pixel takes the smallest log2 box size along its ray (GL_MIN blending).
#include "vot_common.glsl"

flat in uint vVot;
layout(location = 0) out float outValue;

void main() { outValue = vots[vVot].logSize; }
