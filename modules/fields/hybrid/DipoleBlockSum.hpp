// Direct sum of dipole pairs for a block of targets against a run of sources, in
// structure-of-arrays form with one vector lane per target. Private to the far
// field (DipoleFarField.cpp: all pairs; DipoleMultipole.cpp: the pairs of
// neighbouring tree leaves). Both files are compiled with -ffp-contract=off
// -fno-math-errno -fno-trapping-math (this module's CMakeLists.txt), so the pair test
// rounds as in isDipolePair() and the loop vectorizes.
#pragma once

#include "DipoleFarField.hpp"

#include <array>
#include <cmath>
#include <span>
#include <utility>
#include <vector>

namespace mag::detail {

inline constexpr double kMu = mu0 / (4.0 * pi);

// The bodies as arrays. `fixed` is 1 for bodies whose pairs with each other are
// skipped (fixed bodies when skipFixedPairs), else 0.
struct DipoleArrays {
    std::vector<double> x, y, z, mx, my, mz, reach, fixed;

    void resize(std::size_t n) {
        for (auto* v : {&x, &y, &z, &mx, &my, &mz, &reach, &fixed}) v->resize(n);
    }
    void set(std::size_t i, const FarFieldBody& b, bool skipFixedPairs) {
        x[i] = b.position.x(), y[i] = b.position.y(), z[i] = b.position.z();
        mx[i] = b.moment.x(), my[i] = b.moment.y(), mz[i] = b.moment.z();
        reach[i] = b.reach;
        fixed[i] = skipFixedPairs && b.fixed ? 1.0 : 0.0;
    }
};

inline constexpr std::size_t kBlock = 64;

// Per-target sums of a block: force, torque, energy and the number of pairs.
struct BlockSums {
    std::array<double, kBlock> fx{}, fy{}, fz{}, tx{}, ty{}, tz{}, e{}, c{};

    // The wrench on the block's k-th target.
    Wrench wrench(std::size_t k) const {
        Wrench w;
        w.force = Vec3(fx[k], fy[k], fz[k]);
        w.torque = Vec3(tx[k], ty[k], tz[k]);
        w.energy = e[k];
        return w;
    }
};

// Adds to acc the wrenches on targets t[i0 .. i0 + m - 1] (m <= kBlock) from the
// sources s[j], j in the ranges in turn, that are dipole pairs with them. Each lane does exactly
// the scalar sequence of operations (no FMA, IEEE division and sqrt, no sums
// across lanes), so the result does not depend on the vector width. One division
// and one sqrt a pair bound the speed (timings: cases/benchmarks, `scaling`).
// This loop is the dipole-pair formula (corrected Eq. 5, Eq. 6;
// docs/physics.md#dipoles-and-edm) of every dipole sum here: the bulk and
// multipole sums and dipolePairWrench() all run it, so they round alike. It is
// written out in the loop, not called: a helper returning the terms as a struct
// keeps the compiler from vectorizing it (3-4x slower).
// A run of sources [first, second).
using SourceRange = std::pair<std::size_t, std::size_t>;

inline void sumBlock(const DipoleArrays& t, std::size_t i0, std::size_t m, const DipoleArrays& s,
                     std::span<const SourceRange> ranges, BlockSums& acc) {
    // Accumulate in local arrays (no aliasing with the inputs: the loop vectorizes).
    alignas(64) std::array<double, kBlock> fx = acc.fx, fy = acc.fy, fz = acc.fz, tx = acc.tx, ty = acc.ty,
                                           tz = acc.tz, e = acc.e, c = acc.c;
    const double *xi = &t.x[i0], *yi = &t.y[i0], *zi = &t.z[i0], *mxi = &t.mx[i0], *myi = &t.my[i0],
                 *mzi = &t.mz[i0], *ri = &t.reach[i0], *fi = &t.fixed[i0];
    for (const auto& [j0, j1] : ranges)
    for (std::size_t j = j0; j < j1; ++j) {
        const double xj = s.x[j], yj = s.y[j], zj = s.z[j], sx = s.mx[j], sy = s.my[j], sz = s.mz[j],
                     rj = s.reach[j], fj = s.fixed[j];
        for (std::size_t k = 0; k < m; ++k) {
            // Target i = i0 + k, source j, r = c_i - c_j (the pair test as in isDipolePair).
            const double rx = xi[k] - xj, ry = yi[k] - yj, rz = zi[k] - zj;
            const double d2 = rx * rx + ry * ry + rz * rz;
            const double lim = ri[k] + rj;
            // Other pairs (and i = j) are computed with d^2 = 1 and then dropped
            // by the selects (a NaN position drops out the same way).
            const bool far = (d2 > lim * lim) & (fi[k] * fj == 0.0);
            const double inv2 = 1.0 / (far ? d2 : 1.0);
            const double inv3 = inv2 * std::sqrt(inv2);
            const double tmx = mxi[k], tmy = myi[k], tmz = mzi[k];
            const double msr = sx * rx + sy * ry + sz * rz, mtr = tmx * rx + tmy * ry + tmz * rz;
            const double mm = sx * tmx + sy * tmy + sz * tmz;
            // B of the source at the target.
            const double b3 = 3.0 * msr * inv2, kb = kMu * inv3;
            const double bx = kb * (b3 * rx - sx), by = kb * (b3 * ry - sy), bz = kb * (b3 * rz - sz);
            const double f = 3.0 * kMu * inv3 * inv2, g = 5.0 * msr * mtr * inv2;
            fx[k] += far ? f * ((mtr * sx + msr * tmx) + mm * rx - g * rx) : 0.0;
            fy[k] += far ? f * ((mtr * sy + msr * tmy) + mm * ry - g * ry) : 0.0;
            fz[k] += far ? f * ((mtr * sz + msr * tmz) + mm * rz - g * rz) : 0.0;
            tx[k] += far ? tmy * bz - tmz * by : 0.0;
            ty[k] += far ? tmz * bx - tmx * bz : 0.0;
            tz[k] += far ? tmx * by - tmy * bx : 0.0;
            e[k] -= far ? tmx * bx + tmy * by + tmz * bz : 0.0;
            c[k] += far ? 1.0 : 0.0;
        }
    }
    acc.fx = fx, acc.fy = fy, acc.fz = fz, acc.tx = tx, acc.ty = ty, acc.tz = tz, acc.e = e, acc.c = c;
}

} // namespace mag::detail
