#version 450 core
// Display pass: window/level + colour map (256-entry table); non-finite (background) -> low end.
uniform sampler2D uImage;    // R32F values
uniform sampler2D uColormap; // 256 x 1 RGBA8
uniform float uLow;          // level - width / 2
uniform float uWidth;

layout(location = 0) out vec4 outColor;

void main() {
    float v = texelFetch(uImage, ivec2(gl_FragCoord.xy), 0).r;
    int index = 0;
    if (!isinf(v) && !isnan(v)) index = int(floor(255.0 * clamp((v - uLow) / uWidth, 0.0, 1.0) + 0.5));
    outColor = texelFetch(uColormap, ivec2(index, 0), 0);
}
