// A tiny SIMD layer for the MBM field kernel: 4 doubles per GCC vector (one AVX2
// register; plain x86-64 lowers each operation to two SSE2 ones; 8 doubles where the
// code is compiled for AVX-512: the x86-64-v4 copy of the kernel, or MAG_NATIVE on such
// a machine), and the two
// transcendental functions the kernel needs, log (Eq. 14) and atan2 (Eq. 15), to full
// double accuracy (< 1 ulp, fdlibm's reductions and polynomials). No -ffast-math and no
// libmvec: results must not depend on the compiler's or the C library's choices.
//
// Internal to the MBM module: included by PolyhedronBlocks.inc, which is compiled once
// per instruction set (runtime dispatch, KernelPath.hpp). Everything here has internal
// linkage (static functions, const variables): the copies of different widths never
// share a symbol, and no function is emitted out of line anyway (always_inline).
#pragma once

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

#include <cstdint>

// Vector arguments of the always-inlined helpers below never cross an ABI boundary.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"

namespace mag::mbm::simd {

#if defined(__AVX512F__)
constexpr int kWidth = 8;
#else
constexpr int kWidth = 4;
#endif
typedef double vd __attribute__((vector_size(8 * kWidth)));
typedef std::uint64_t vu __attribute__((vector_size(8 * kWidth)));
typedef std::int64_t vi __attribute__((vector_size(8 * kWidth)));
/// Result of a comparison: all bits set (true) or clear, per lane.
using vm = decltype(vd{} < vd{});

#define MAG_SIMD_INLINE static inline __attribute__((always_inline))

MAG_SIMD_INLINE vd splat(double x) {
    vd r;
    for (int i = 0; i < kWidth; ++i) r[i] = x; // one broadcast
    return r;
}
MAG_SIMD_INLINE vd select(vm m, vd a, vd b) { return m ? a : b; }

/// Lane i set in bit i.
MAG_SIMD_INLINE unsigned bits(vm m) {
#if defined(__AVX512F__)
    return static_cast<unsigned>(_mm512_cmpneq_epi64_mask((__m512i)m, _mm512_setzero_si512()));
#elif defined(__AVX__)
    return static_cast<unsigned>(_mm256_movemask_pd((__m256d)m));
#else
    unsigned r = 0;
    for (int i = 0; i < kWidth; ++i) r |= (m[i] != 0 ? 1u : 0u) << i;
    return r;
#endif
}

MAG_SIMD_INLINE vd sqrt(vd x) {
#if defined(__AVX512F__)
    return (vd)_mm512_maskz_sqrt_pd(0xff, (__m512d)x); // (the unmasked form trips -Wuninitialized)
#elif defined(__AVX__)
    return (vd)_mm256_sqrt_pd((__m256d)x);
#elif defined(__SSE2__)
    const __m128d lo = _mm_sqrt_pd(__m128d{x[0], x[1]}), hi = _mm_sqrt_pd(__m128d{x[2], x[3]});
    return vd{lo[0], lo[1], hi[0], hi[1]};
#else
    vd r;
    for (int i = 0; i < kWidth; ++i) r[i] = __builtin_sqrt(x[i]);
    return r;
#endif
}

/// a * b + c, fused where the target has FMA (only used inside polynomials, whose
/// error bounds hold either way).
MAG_SIMD_INLINE vd fma(vd a, vd b, vd c) {
#if defined(__AVX512F__)
    return (vd)_mm512_fmadd_pd((__m512d)a, (__m512d)b, (__m512d)c);
#elif defined(__FMA__)
    return (vd)_mm256_fmadd_pd((__m256d)a, (__m256d)b, (__m256d)c);
#else
    return a * b + c;
#endif
}

constexpr std::uint64_t kSignBit = 0x8000000000000000ull;

/// 2^-e for x in [2^e, 2^(e+1)), finite normal x > 0 (x * result in [1, 2), exact);
/// used to renormalize a running product without rounding.
MAG_SIMD_INLINE vd pow2Inverse(vd x) {
    return (vd)(0x7fe0000000000000ull - ((vu)x & 0x7ff0000000000000ull));
}

MAG_SIMD_INLINE vd abs(vd x) { return (vd)((vu)x & ~kSignBit); }
/// |a| with the sign bit of b (std::copysign per lane).
MAG_SIMD_INLINE vd copysign(vd a, vd b) {
    return (vd)(((vu)a & ~kSignBit) | ((vu)b & kSignBit));
}

/// log(u + lo) for finite normal u > 0 and a small correction |lo| <~ ulp(u) (the
/// rounding error of u = fl(1 + q), so that log1p(q) = logPlus(fl(1 + q), err) keeps
/// full relative accuracy for tiny q). fdlibm's e_log.c: u = 2^k (1 + f) with 1 + f in
/// [sqrt(2)/2, sqrt(2)), log(1 + f) = f - f^2/2 + s (f^2/2 + R(s^2)), s = f / (2 + f),
/// error < 1 ulp; lo enters to first order as lo 2^-k / (1 + f) ~ lo 2^-k (1 - f).
MAG_SIMD_INLINE vd logPlus(vd u, vd lo) {
    constexpr double ln2Hi = 6.93147180369123816490e-01, ln2Lo = 1.90821492927058770002e-10;
    constexpr double Lg1 = 6.666666666666735130e-01, Lg2 = 3.999999999940941908e-01,
                     Lg3 = 2.857142874366239149e-01, Lg4 = 2.222219843214978396e-01,
                     Lg5 = 1.818357216161805012e-01, Lg6 = 1.531383769920937332e-01,
                     Lg7 = 1.479819860511658591e-01;
    const vu b = (vu)u;
    const vi e = (vi)(b >> 52); // biased exponent (u > 0)
    vd m = (vd)((b & 0x000fffffffffffffull) | 0x3ff0000000000000ull); // [1, 2)
    const vm big = m > splat(1.41421356237309504880);
    m = select(big, m * 0.5, m);
    const vi k = e - 1023 - (vi)big; // big is -1 where set
    // k as a double: exponent bits planted under 2^52, then the offset removed
    const vd dk = (vd)(k + 0x4338000000000000ll) - 6755399441055744.0; // 2^52 + 2^51
    const vd twoMinusK = (vd)((vu)(1023 - k) << 52);
    const vd f = m - 1.0; // exact (Sterbenz)
    const vd corr = (lo * twoMinusK) * (1.0 - f);
    const vd s = f / (2.0 + f);
    const vd z = s * s, w = z * z;
    const vd t1 = w * fma(w, fma(w, splat(Lg6), splat(Lg4)), splat(Lg2));
    const vd t2 = z * fma(w, fma(w, fma(w, splat(Lg7), splat(Lg5)), splat(Lg3)), splat(Lg1));
    const vd R = t2 + t1;
    const vd hfsq = 0.5 * f * f;
    return dk * ln2Hi - ((hfsq - (s * (hfsq + R) + (dk * ln2Lo + corr))) - f);
}

/// log(x) for finite normal x > 0.
MAG_SIMD_INLINE vd log(vd x) { return logPlus(x, vd{}); }

/// log1p(q) for q >= 0 finite: u = fl(1 + q) and its exact rounding error (TwoSum).
MAG_SIMD_INLINE vd log1p(vd q) {
    const vd u = 1.0 + q, bb = u - 1.0;
    const vd err = (1.0 - (u - bb)) + (q - bb);
    return logPlus(u, err);
}

/// atan2(y, x) for finite x, y with C's conventions for signed zeros (atan2(+-0, -0)
/// = +-pi, atan2(+-0, +0) = +-0). fdlibm's s_atan.c on t = |y|/|x|: t reduced by
/// atan(t) = atan(c) + atan((t - c)/(1 + c t)), c in {0, 1/2, 1, 3/2, inf}, each
/// reduction folded into one division (|y| and |x| scaled, never overflowing for the
/// kernel's |x|, |y| <= 4^n); then the quadrant from the signs (e_atan2.c), error < 1 ulp.
MAG_SIMD_INLINE vd atan2(vd y, vd x) {
    constexpr double aT0 = 3.33333333333329318027e-01, aT1 = -1.99999999998764832476e-01,
                     aT2 = 1.42857142725034663711e-01, aT3 = -1.11111104054623557880e-01,
                     aT4 = 9.09088713343650656196e-02, aT5 = -7.69187620504482999495e-02,
                     aT6 = 6.66107313738753120669e-02, aT7 = -5.83357013379057348645e-02,
                     aT8 = 4.97687799461593236017e-02, aT9 = -3.65315727442169155270e-02,
                     aT10 = 1.62858201153657823623e-02;
    const vd ay = abs(y), ax = abs(x);
    // intervals of t = ay/ax: [0, 7/16], (7/16, 11/16], (11/16, 19/16], (19/16, 39/16], beyond
    const vm r1 = ay > (7.0 / 16.0) * ax, r2 = ay > (11.0 / 16.0) * ax,
             r3 = ay > (19.0 / 16.0) * ax, r4 = ay > (39.0 / 16.0) * ax;
    // (t - c)/(1 + c t) as num/den in ay, ax (c = inf: -1/t)
    vd num = ay, den = ax, hi = vd{}, lo = vd{};
    num = select(r1, 2.0 * ay - ax, num);
    den = select(r1, 2.0 * ax + ay, den);
    hi = select(r1, splat(4.63647609000806093515e-01), hi);
    lo = select(r1, splat(2.26987774529616870924e-17), lo);
    num = select(r2, ay - ax, num);
    den = select(r2, ax + ay, den);
    hi = select(r2, splat(7.85398163397448278999e-01), hi);
    lo = select(r2, splat(3.06161699786838301793e-17), lo);
    num = select(r3, 2.0 * ay - 3.0 * ax, num);
    den = select(r3, 2.0 * ax + 3.0 * ay, den);
    hi = select(r3, splat(9.82793723247329054082e-01), hi);
    lo = select(r3, splat(1.39033110312309984516e-17), lo);
    num = select(r4, -ax, num);
    den = select(r4, ay, den);
    hi = select(r4, splat(1.57079632679489655800e+00), hi);
    lo = select(r4, splat(6.12323399573676603587e-17), lo);
    den = select(den == 0.0, splat(1.0), den); // x = y = 0: t = 0
    const vd t = num / den;
    const vd z = t * t, w = z * z;
    const vd s1 = z * fma(w, fma(w, fma(w, fma(w, fma(w, splat(aT10), splat(aT8)), splat(aT6)),
                                            splat(aT4)), splat(aT2)), splat(aT0));
    const vd s2 = w * fma(w, fma(w, fma(w, fma(w, splat(aT9), splat(aT7)), splat(aT5)), splat(aT3)),
                          splat(aT1));
    const vd a = hi - ((t * (s1 + s2) - lo) - t); // atan(ay/ax) in [0, pi/2]
    // x < 0 (sign bit, so -0 counts): pi - a
    const vm negX = (vi)((vu)x & kSignBit) != 0;
    const vd r = select(negX, 3.1415926535897931160E+00 - (a - 1.2246467991473531772E-16), a);
    return copysign(r, y);
}

#undef MAG_SIMD_INLINE

} // namespace mag::mbm::simd

#pragma GCC diagnostic pop
