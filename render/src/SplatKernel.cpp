// The CPU splat's inner loop in GCC vector extensions: 8 rays of one pixel row per step, one Vot.
#include "SplatKernel.h"

#include <cmath>
#include <cstring>

// The 8-float vectors are 32 bytes: without AVX GCC passes them differently, which it notes once per
// function (-Wpsabi). Every function taking one is inlined into splatVot, so no such call exists.
#pragma GCC diagnostic ignored "-Wpsabi"

namespace vots::render {
namespace {

typedef float Lanes __attribute__((vector_size(32)));
typedef int LaneMask __attribute__((vector_size(32)));

#define SPLAT_INLINE inline __attribute__((always_inline))

SPLAT_INLINE Lanes all(float a) {
    return Lanes{a, a, a, a, a, a, a, a};
}
SPLAT_INLINE Lanes maxOf(Lanes a, Lanes b) {
    return a > b ? a : b;
}
SPLAT_INLINE Lanes minOf(Lanes a, Lanes b) {
    return a < b ? a : b;
}
SPLAT_INLINE Lanes loadLanes(const float* p) {
    Lanes v;
    std::memcpy(&v, p, sizeof v);
    return v;
}
SPLAT_INLINE bool anyLane(LaneMask m) {
    long long words[4];
    std::memcpy(words, &m, sizeof words);
    return (words[0] | words[1] | words[2] | words[3]) != 0;
}

// f(s + u d) as the cubic g0 + g1 u + g2 u^2 + g3 u^3, for the monomials in fit's canonical order
// (Monomials.h): each monomial a product of up to three linear factors in u, as cubic_ray_max.glsl.
struct LaneCubic {
    Lanes g0, g1, g2, g3;
};
SPLAT_INLINE LaneCubic alongRay(const float* c, const Lanes s[3], const Lanes d[3]) {
    const Lanes x0 = s[0], x1 = d[0], y0 = s[1], y1 = d[1], z0 = s[2], z1 = d[2];
    const Lanes two = all(2.f), three = all(3.f);
    const Lanes xx[3] = {x0 * x0, two * x0 * x1, x1 * x1};
    const Lanes yy[3] = {y0 * y0, two * y0 * y1, y1 * y1};
    const Lanes zz[3] = {z0 * z0, two * z0 * z1, z1 * z1};
    const Lanes xy[3] = {x0 * y0, x0 * y1 + x1 * y0, x1 * y1};
    LaneCubic g{all(c[0]) + all(c[1]) * x0 + all(c[2]) * y0 + all(c[3]) * z0,
                all(c[1]) * x1 + all(c[2]) * y1 + all(c[3]) * z1, all(0.f), all(0.f)};
    auto addQuadratic = [&g](float k, Lanes a0, Lanes a1, Lanes a2) {
        const Lanes kk = all(k);
        g.g0 += kk * a0, g.g1 += kk * a1, g.g2 += kk * a2;
    };
    auto addCubic = [&g](float k, Lanes a0, Lanes a1, Lanes a2, Lanes a3) {
        const Lanes kk = all(k);
        g.g0 += kk * a0, g.g1 += kk * a1, g.g2 += kk * a2, g.g3 += kk * a3;
    };
    // A quadratic factor q times a linear one (b0 + b1 u).
    auto addQuadraticTimesLinear = [&addCubic](float k, const Lanes q[3], Lanes b0, Lanes b1) {
        addCubic(k, q[0] * b0, q[0] * b1 + q[1] * b0, q[1] * b1 + q[2] * b0, q[2] * b1);
    };
    addQuadratic(c[4], xx[0], xx[1], xx[2]);
    addQuadratic(c[5], yy[0], yy[1], yy[2]);
    addQuadratic(c[6], zz[0], zz[1], zz[2]);
    addQuadratic(c[7], xy[0], xy[1], xy[2]);
    addQuadratic(c[8], x0 * z0, x0 * z1 + x1 * z0, x1 * z1);
    addQuadratic(c[9], y0 * z0, y0 * z1 + y1 * z0, y1 * z1);
    addCubic(c[10], xx[0] * x0, three * x0 * x0 * x1, three * x0 * x1 * x1, xx[2] * x1);
    addCubic(c[11], yy[0] * y0, three * y0 * y0 * y1, three * y0 * y1 * y1, yy[2] * y1);
    addCubic(c[12], zz[0] * z0, three * z0 * z0 * z1, three * z0 * z1 * z1, zz[2] * z1);
    addQuadraticTimesLinear(c[13], xx, y0, y1);
    addQuadraticTimesLinear(c[14], xx, z0, z1);
    addQuadraticTimesLinear(c[15], yy, x0, x1);
    addQuadraticTimesLinear(c[16], yy, z0, z1);
    addQuadraticTimesLinear(c[17], zz, x0, x1);
    addQuadraticTimesLinear(c[18], zz, y0, y1);
    addQuadraticTimesLinear(c[19], xy, z0, z1);
    return g;
}

SPLAT_INLINE Lanes cubicAt(const LaneCubic& g, Lanes u) {
    return g.g0 + u * (g.g1 + u * (g.g2 + u * g.g3));
}

// Max of g over [0, len]: the end points and the roots of g' inside, by the cancellation-free form of
// cubic_along_ray.glsl's cubicMaxOver (the same critical points, lane by lane).
SPLAT_INLINE Lanes cubicMaxOver(const LaneCubic& g, Lanes len) {
    Lanes best = maxOf(g.g0, cubicAt(g, len));
    const Lanes zero = all(0.f);
    const Lanes a = all(3.f) * g.g3, b = all(2.f) * g.g2, c = g.g1;
    const Lanes disc = b * b - all(4.f) * a * c;
    const LaneMask real = disc >= zero;
    // Lane by lane over a vector already made non-negative: with -fno-math-errno (render/CMakeLists.txt)
    // GCC makes the loop one vector square root.
    const Lanes discOrZero = maxOf(disc, zero);
    Lanes root = all(0.f);
    for (int i = 0; i < 8; ++i)
        root[i] = std::sqrt(discOrZero[i]);
    const Lanes q = all(-0.5f) * (b + (b >= zero ? root : -root));
    const Lanes r1 = q / a, r2 = c / q; // a == 0: r1 is inf or NaN and fails the range test
    best = (real & (r1 > zero) & (r1 < len)) ? maxOf(best, cubicAt(g, r1)) : best;
    best = (real & (r2 > zero) & (r2 < len)) ? maxOf(best, cubicAt(g, r2)) : best;
    return best;
}

// The slab test of the rays against [lo, hi]: narrows [tIn, tOut].
SPLAT_INLINE void clipToBox(const Lanes o[3], const Lanes inv[3], const float lo[3], const float hi[3],
                            Lanes& tIn, Lanes& tOut) {
    for (int i = 0; i < 3; ++i) {
        const Lanes t0 = (all(lo[i]) - o[i]) * inv[i], t1 = (all(hi[i]) - o[i]) * inv[i];
        tIn = maxOf(tIn, minOf(t0, t1));
        tOut = minOf(tOut, maxOf(t0, t1));
    }
}

} // namespace

// The loader's resolver that picks a clone runs before a sanitizer's runtime is up, and crashes the
// sanitized test binaries at start: they take the baseline only (they check correctness, not speed).
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(__SANITIZE_THREAD__) &&      \
    !defined(__SANITIZE_ADDRESS__)
__attribute__((target_clones("arch=x86-64-v3", "default")))
#endif
bool splatVot(const SplatFrame& f, const SplatVot& vot, float upperBound, float* best, int x0, int x1, int y0,
              int y1) {
    const Lanes lane = {0.5f, 1.5f, 2.5f, 3.5f, 4.5f, 5.5f, 6.5f, 7.5f};
    const Lanes upper = all(upperBound);
    bool rose = false;
    for (int y = y0; y <= y1; ++y) {
        const float Y = static_cast<float>(y) + 0.5f;
        float* row = best + static_cast<std::ptrdiff_t>(y) * f.width;
        for (int x = x0; x <= x1; x += 8) {
            const int count = x1 - x + 1 < 8 ? x1 - x + 1 : 8;
            Lanes b = all(-INFINITY);
            std::memcpy(&b, row + x, sizeof(float) * static_cast<unsigned>(count));
            LaneMask live = (b < upper) & (lane < all(static_cast<float>(count)));
            if (!anyLane(live)) continue;
            // The rays of these pixels (ray_common.glsl's pixelRay).
            const Lanes ndcX =
                (all(static_cast<float>(x)) + lane) / all(static_cast<float>(f.width)) * all(2.f) - all(1.f);
            const Lanes ndcY = all(Y / static_cast<float>(f.height) * 2.f - 1.f);
            const float* m = f.clipToIndex;
            Lanes nearH[4], farH[4];
            for (int i = 0; i < 4; ++i) {
                const Lanes xy = all(m[i]) * ndcX + all(m[4 + i]) * ndcY;
                nearH[i] = xy - all(m[8 + i]) + all(m[12 + i]);
                farH[i] = xy + all(m[8 + i]) + all(m[12 + i]);
            }
            Lanes o[3], d[3], inv[3];
            for (int i = 0; i < 3; ++i) {
                o[i] = nearH[i] / nearH[3];
                d[i] = farH[i] / farH[3] - o[i];
            }
            const Lanes length2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
            Lanes farT = all(0.f);
            for (int k = 0; k < 8; ++k)
                farT[k] = std::sqrt(length2[k]);
            const Lanes tiny = all(1e-30f);
            for (int i = 0; i < 3; ++i) {
                d[i] /= farT;
                const Lanes absD = d[i] < all(0.f) ? -d[i] : d[i];
                inv[i] = all(1.f) / (absD < tiny ? tiny : d[i]);
            }
            Lanes tIn = all(0.f), tOut = farT;
            if (f.slabOn) {
                Lanes s0 = all(f.slabOffset), ds = all(0.f);
                for (int i = 0; i < 3; ++i)
                    s0 += all(f.slabNormal[i]) * o[i], ds += all(f.slabNormal[i]) * d[i];
                const Lanes ta = (all(f.slabLo) - s0) / ds, tb = (all(f.slabHi) - s0) / ds;
                const LaneMask flat = (ds < tiny) & (ds > -tiny);
                const LaneMask inside = (s0 >= all(f.slabLo)) & (s0 <= all(f.slabHi));
                tIn = flat ? tIn : maxOf(tIn, minOf(ta, tb));
                tOut = flat ? tOut : minOf(tOut, maxOf(ta, tb));
                live &= ~flat | inside;
            }
            if (f.domainOn) clipToBox(o, inv, f.domainLo, f.domainHi, tIn, tOut);
            clipToBox(o, inv, vot.lo, vot.hi, tIn, tOut);
            live &= tIn <= tOut;
            if (!anyLane(live)) continue;
            // Expanded from the box entry point, not the near plane: float cancellation (DESIGN.md §5).
            Lanes s[3];
            for (int i = 0; i < 3; ++i)
                s[i] = o[i] + tIn * d[i] - all(vot.p[i]);
            const Lanes value = cubicMaxOver(alongRay(vot.c, s, d), tOut - tIn);
            const LaneMask raise = live & (value > b);
            if (!anyLane(raise)) continue;
            b = raise ? value : b;
            std::memcpy(row + x, &b, sizeof(float) * static_cast<unsigned>(count));
            rose = true;
        }
    }
    return rose;
}

} // namespace vots::render
