#include "DipoleFarField.hpp"

#include "magFoam/Threads.hpp"

#include "DipoleBlockSum.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <unordered_map>

// Compiled with -ffp-contract=off (this module's CMakeLists.txt): the pair test
// d^2 > (reach_i + reach_j)^2 must round the same in the grid search, in every
// vector lane of the bulk sum, and for (i, j) as for (j, i), or a pair at the
// boundary could be counted as both near and far, or as neither. And with
// -fno-math-errno -fno-trapping-math, without which GCC leaves the bulk loop
// scalar (sqrt might set errno, a comparison might trap); results are the same.

namespace mag {

Wrench dipolePairWrench(const Vec3& ms, const Vec3& mt, const Vec3& r) {
    // The bulk sums' own loop (DipoleBlockSum.hpp) on one target and one source,
    // so that both round alike: the source at the origin, the target at r.
    // One pair's arrays per thread, reused: no allocation per call.
    thread_local detail::DipoleArrays t, s;
    t.resize(1), s.resize(1);
    t.set(0, FarFieldBody{r, mt, 0.0, false}, false);
    s.set(0, FarFieldBody{Vec3::Zero(), ms, 0.0, false}, false);
    detail::BlockSums sums;
    const detail::SourceRange one{0, 1};
    detail::sumBlock(t, 0, 1, s, {&one, 1}, sums);
    return sums.wrench(0);
}

FarFieldBody farFieldBody(const Body& b, double reach) {
    // m = V (q M q*), q M q* = M + w U + q_v x U with U = 2 q_v x M (Eigen's
    // rotation), with every multiply-add fused as written: the rounding of the
    // moments the far field has always used, now fixed in this file instead of
    // left to the compiler at the caller.
    const Vec3& M = b.magnetizationBody;
    const double qx = b.orientation.x(), qy = b.orientation.y(), qz = b.orientation.z(), qw = b.orientation.w();
    const double ux = 2 * std::fma(-qz, M.y(), qy * M.z()), uy = 2 * std::fma(-qx, M.z(), qz * M.x()),
                 uz = 2 * std::fma(qx, M.y(), -(qy * M.x()));
    const double cx = std::fma(-qz, uy, qy * uz), cy = std::fma(-qx, uz, qz * ux), cz = std::fma(qx, uy, -(qy * ux));
    const Vec3 world(std::fma(qw, ux, M.x()) + cx, std::fma(qw, uy, M.y()) + cy, std::fma(qw, uz, M.z()) + cz);
    return {b.position, world * b.shape->volume, reach, b.fixed};
}

namespace {
constexpr double kC2 = 12.0, kC4 = 0.3;  // see the header
}

double shapeQuadrupole(const Shape& shape) {
    // J = tr(I)/2 1 - I for the unit-density inertia I, so Q = 3 J - tr(J) 1 = tr(I) 1 - 3 I.
    const Mat3 Q = shape.unitInertia.trace() * Mat3::Identity() - 3.0 * shape.unitInertia;
    return Q.norm() / shape.volume;
}

double dipoleErrorEstimate(const Shape& source, const Shape& target, double distance) {
    const double x = (source.boundingRadius + target.boundingRadius) / distance;
    return kC2 * (shapeQuadrupole(source) + shapeQuadrupole(target)) / (distance * distance) + kC4 * x * x * x * x;
}

double dipoleReachFor(const Shape& shape, double tol) {
    return std::sqrt(2.0 * kC2 / tol) * std::sqrt(shapeQuadrupole(shape)) +
           std::sqrt(std::sqrt(2.0 * kC4 / tol)) * shape.boundingRadius;
}

namespace {

// |c_i - c_j|^2, component differences taken i minus j: the same bits for (j, i).
double distance2(const FarFieldBody& a, const FarFieldBody& b) {
    const double rx = a.position.x() - b.position.x(), ry = a.position.y() - b.position.y(),
                 rz = a.position.z() - b.position.z();
    return rx * rx + ry * ry + rz * rz;
}

} // namespace

bool isDipolePair(const FarFieldBody& a, const FarFieldBody& b) {
    const double lim = a.reach + b.reach;
    return distance2(a, b) > lim * lim;
}

std::vector<std::pair<std::size_t, std::size_t>> nearPairs(std::span<const FarFieldBody> bodies,
                                                           bool skipFixedPairs) {
    const std::size_t n = bodies.size();
    std::vector<std::pair<std::size_t, std::size_t>> out;
    auto consider = [&](std::size_t i, std::size_t j) {
        if (i > j) std::swap(i, j);
        if (skipFixedPairs && bodies[i].fixed && bodies[j].fixed) return;
        if (!isDipolePair(bodies[i], bodies[j])) out.emplace_back(i, j);
    };
    // Bodies that are never dipole pairs pair with everyone; the others go in a
    // grid whose cell (2 max reach) holds any near partner in the 27 cells around.
    std::vector<std::size_t> always, gridded;
    double maxReach = 0, extent = 0;
    for (std::size_t i = 0; i < n; ++i) {
        if (std::isfinite(bodies[i].reach) && bodies[i].position.allFinite()) {
            gridded.push_back(i);
            maxReach = std::max(maxReach, bodies[i].reach);
            extent = std::max(extent, bodies[i].position.cwiseAbs().maxCoeff());
        } else {
            always.push_back(i);
        }
    }
    for (std::size_t i : always)
        for (std::size_t j = 0; j < n; ++j)
            if (j != i) consider(i, j);
    // At most ~1e6 cells per axis across the scene: the cell coordinates then stay
    // small integers, and pairs of zero reach still find each other (same cell).
    const double cell = std::max(2.0 * maxReach, 2e-6 * extent + std::numeric_limits<double>::min());
    using Key = std::array<std::int64_t, 3>;
    struct KeyHash {
        std::size_t operator()(const Key& k) const {
            return static_cast<std::size_t>(k[0] * 73856093LL ^ k[1] * 19349663LL ^ k[2] * 83492791LL);
        }
    };
    auto keyOf = [&](const Vec3& p) {
        return Key{static_cast<std::int64_t>(std::floor(p.x() / cell)), static_cast<std::int64_t>(std::floor(p.y() / cell)),
                   static_cast<std::int64_t>(std::floor(p.z() / cell))};
    };
    std::unordered_map<Key, std::vector<std::size_t>, KeyHash> grid;
    for (std::size_t i : gridded) grid[keyOf(bodies[i].position)].push_back(i);
    for (std::size_t i : gridded) {
        const Key k = keyOf(bodies[i].position);
        for (int dx = -1; dx <= 1; ++dx)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dz = -1; dz <= 1; ++dz) {
                    const auto it = grid.find(Key{k[0] + dx, k[1] + dy, k[2] + dz});
                    if (it == grid.end()) continue;
                    for (std::size_t j : it->second)
                        if (j > i) consider(i, j);
                }
    }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());  // pairs of two `always` bodies come twice
    return out;
}


std::uint64_t addDipoleFarField(std::span<const FarFieldBody> bodies, bool skipFixedPairs, std::span<Wrench> out) {
    const std::size_t n = bodies.size();
    if (n < 2 || std::none_of(bodies.begin(), bodies.end(), [](const auto& b) { return std::isfinite(b.reach); }))
        return 0;
    detail::DipoleArrays a;
    a.resize(n);
    for (std::size_t i = 0; i < n; ++i) a.set(i, bodies[i], skipFixedPairs);
    constexpr std::size_t kBlock = detail::kBlock;
    const std::size_t nBlocks = (n + kBlock - 1) / kBlock;
    std::vector<double> count(nBlocks, 0.0);
    parallelFor(nBlocks, [&](std::size_t block) {
        const std::size_t i0 = block * kBlock, m = std::min(kBlock, n - i0);
        detail::BlockSums sums;
        const detail::SourceRange all{0, n};
        detail::sumBlock(a, i0, m, a, {&all, 1}, sums);
        double pairs = 0;
        for (std::size_t k = 0; k < m; ++k) {
            out[i0 + k] += sums.wrench(k);
            pairs += sums.c[k];
        }
        count[block] = pairs;
    });
    double total = 0;
    for (double v : count) total += v;
    return static_cast<std::uint64_t>(total / 2 + 0.5);  // each pair seen from both ends
}

} // namespace mag
