#version 330 core
// Scene-linear radiance -> display: exposure, tone curve, sRGB transfer. The same steps, in the
// same order and with the same constants, as crates/pathtrace/src/film/tonemap.rs, so the window
// shows exactly what `pathtrace render` writes to a PNG.
uniform sampler2D u_image;
uniform float u_scale;   // 2^exposure, computed on the CPU with the same exp2 as the engine
uniform int u_tonemap;   // 0: clamp, 1: ACES (Narkowicz 2016)
in vec2 v_uv;
out vec4 out_color;

// Narkowicz, "ACES Filmic Tone Mapping Curve" (2016): x(2.51x + 0.03) / (x(2.43x + 0.59) + 0.14),
// evaluated as (Ax + B) / (Cx + D + E/x) like the engine, which requires x > 0.
float aces(float x) {
    float y = (2.51 * x + 0.03) / (2.43 * x + 0.59 + 0.14 / x);
    return clamp(y, 0.0, 1.0);
}

float tone(float x) {
    // NaN and non-positive values map to 0 (the NaN test is written so it also holds for NaN).
    if (!(x > 0.0)) {
        return 0.0;
    }
    return u_tonemap == 1 ? aces(min(x, 3.402823e38)) : min(x, 1.0);
}

// IEC 61966-2-1: 12.92 x up to 0.0031308, else 1.055 x^(1/2.4) - 0.055.
float srgb(float x) {
    x = clamp(x, 0.0, 1.0);
    return x <= 0.0031308 ? 12.92 * x : 1.055 * pow(x, 1.0 / 2.4) - 0.055;
}

void main() {
    vec3 c = texture(u_image, v_uv).rgb * u_scale;
    out_color = vec4(srgb(tone(c.r)), srgb(tone(c.g)), srgb(tone(c.b)), 1.0);
}
