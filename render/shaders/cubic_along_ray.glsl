// A cubic g(u) = g.x + g.y u + g.z u^2 + g.w u^3 on [0, len]: its exact maximum, minimum and integral,
// shared by the Vot shaders (a Vot's polynomial along a ray) and the grid shader (the trilinear
// interpolant along a ray inside one cell).

float cubicAt(vec4 g, float u) { return g.x + u * (g.y + u * (g.z + u * g.w)); }

// Max of g over [0, len]: the end points and the roots of g' inside.
float cubicMaxOver(vec4 g, float len) {
    float best = max(g.x, cubicAt(g, len));
    // g'(u) = A u^2 + B u + C; roots via the cancellation-free form q = -(B + sign(B) sqrt(disc)) / 2,
    // r1 = q / A, r2 = C / q. A == 0 gives r1 = inf (ignored) and r2 = -C / B, the linear root;
    // A == B == 0 gives no finite root. Non-finite roots fail the range test below.
    float A = 3.0 * g.w, B = 2.0 * g.z, C = g.y;
    float disc = B * B - 4.0 * A * C;
    if (disc >= 0.0) {
        float q = -0.5 * (B + (B >= 0.0 ? 1.0 : -1.0) * sqrt(disc));
        float r1 = q / A;
        float r2 = C / q;
        if (r1 > 0.0 && r1 < len) best = max(best, cubicAt(g, r1));
        if (r2 > 0.0 && r2 < len) best = max(best, cubicAt(g, r2));
    }
    return best;
}

// Min of g over [0, len]: the max of -g, negated (the same critical points).
float cubicMinOver(vec4 g, float len) { return -cubicMaxOver(-g, len); }

// Integral of g over [0, len].
float cubicIntegralOver(vec4 g, float len) {
    return len * (g.x + len * (0.5 * g.y + len * (g.z / 3.0 + len * 0.25 * g.w)));
}
