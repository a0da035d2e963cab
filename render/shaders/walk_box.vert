#version 450 core
// Walk strategy: the back faces of the grid's bounding box, so only pixels whose ray can meet the data run
// the walk shader (the rest keep the cleared -inf).
#include "unit_cube.glsl"

uniform mat4 uIndexToClip;
uniform vec3 uBoxLo; // grid box in index space, grown by a hair
uniform vec3 uBoxHi;

void main() { gl_Position = uIndexToClip * vec4(mix(uBoxLo, uBoxHi, cubeCorner(gl_VertexID)), 1.0); }
