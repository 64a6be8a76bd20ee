// GJK distance between the convex hulls of two point sets (Gilbert, Johnson & Keerthi
// 1988; the paper's Sec. 7 suggestion for the hybrid switch). Header-only so the tests
// can check it against a brute-force distance.
//
// Each set is given in its own frame with a rigid transform x -> R x + c; only the
// support function (the farthest point along a direction) is used, so the hull is
// never built. The closest point of the current simplex (<= 4 points) to the origin is
// found by trying every sub-simplex (the affine projection of the origin, kept when all
// its barycentric coordinates are positive) and taking the nearest one: the
// brute-force form of Johnson's sub-algorithm, exact and robust for <= 15 subsets.
// The same barycentric coordinates applied to the two sets' support points give the
// closest points themselves (witnesses), which the hybrid's blended switch needs for
// the gradient of the distance (docs/physics.md#hybrid-switch).
#pragma once

#include <magFoam/Types.hpp>

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <span>

namespace mag::gjk {

/// A point set (its convex hull) placed in the world: x_world = R x + c.
struct PlacedPoints {
    std::span<const Vec3> points;
    Mat3 R = Mat3::Identity();
    Vec3 c = Vec3::Zero();

    /// World point of the set farthest along the world direction d.
    Vec3 support(const Vec3& d) const {
        const Vec3 dl = R.transpose() * d;
        std::size_t best = 0;
        double bestDot = -std::numeric_limits<double>::infinity();
        for (std::size_t i = 0; i < points.size(); ++i) {
            const double s = points[i].dot(dl);
            if (s > bestDot) bestDot = s, best = i;
        }
        return R * points[best] + c;
    }
};

namespace detail {

/// Closest point to the origin of the convex hull of W (1..4 points); W is reduced
/// to the points of the sub-simplex that holds it, and `companions` (the support
/// points of the two sets that made each W, moved along) with it. Returns the point;
/// lambda holds its barycentric coordinates over the kept points.
inline Vec3 closestOnSimplex(std::array<Vec3, 4>& W, int& size, std::array<std::array<Vec3, 2>, 4>& companions,
                             std::array<double, 4>& lambda) {
    double bestNorm = std::numeric_limits<double>::infinity();
    Vec3 best = W[0];
    int bestMask = 1;
    std::array<double, 4> bestLambda{1, 0, 0, 0};
    for (int mask = 1; mask < (1 << size); ++mask) {
        int idx[4], k = 0;
        for (int i = 0; i < size; ++i)
            if (mask & (1 << i)) idx[k++] = i;
        Vec3 v;
        std::array<double, 4> l{1, 0, 0, 0};
        if (k == 1) {
            v = W[idx[0]];
        } else {
            // Minimise |y0 + E mu|: Gram system (E^T E) mu = -E^T y0.
            const Vec3& y0 = W[idx[0]];
            Eigen::Matrix<double, 3, Eigen::Dynamic> E(3, k - 1);
            double scale = 1;
            for (int j = 1; j < k; ++j) {
                E.col(j - 1) = W[idx[j]] - y0;
                scale *= E.col(j - 1).squaredNorm();
            }
            const Eigen::MatrixXd G = E.transpose() * E;
            // Skip (nearly) degenerate sub-simplices; a smaller one covers them.
            if (!(scale > 0) || G.determinant() <= 1e-12 * scale) continue;
            const Eigen::VectorXd mu = G.ldlt().solve(-E.transpose() * y0);
            if ((mu.array() <= 0).any() || mu.sum() >= 1) continue; // outside the face
            v = y0 + E * mu;
            l[0] = 1 - mu.sum();
            for (int j = 1; j < k; ++j) l[j] = mu(j - 1);
        }
        const double n2 = v.squaredNorm();
        if (n2 < bestNorm) bestNorm = n2, best = v, bestMask = mask, bestLambda = l;
    }
    std::array<Vec3, 4> kept;
    std::array<std::array<Vec3, 2>, 4> keptCompanions;
    int k = 0;
    for (int i = 0; i < size; ++i)
        if (bestMask & (1 << i)) kept[k] = W[i], keptCompanions[k] = companions[i], ++k;
    W = kept, companions = keptCompanions, size = k;
    lambda = bestLambda;
    return best;
}

} // namespace detail

/// The distance between the convex hulls of a and b and a pair of closest points
/// (onA - onB is the shortest vector between the hulls; both are unset, zero, when the
/// hulls touch or overlap, distance 0).
struct Closest {
    double distance = 0;
    Vec3 onA = Vec3::Zero(), onB = Vec3::Zero();
};

/// Distance between the convex hulls of a and b (0 when they intersect) with its
/// closest points. relTol: stop when the distance is known to this relative accuracy.
inline Closest closest(const PlacedPoints& a, const PlacedPoints& b, double relTol = 1e-10, int maxIterations = 100) {
    if (a.points.empty() || b.points.empty())
        return {std::numeric_limits<double>::infinity(), Vec3::Zero(), Vec3::Zero()};
    // Support of the Minkowski difference a - b, with the two support points that make it.
    std::array<Vec3, 2> pair;
    auto support = [&](const Vec3& d) {
        pair = {a.support(d), b.support(-d)};
        return Vec3(pair[0] - pair[1]);
    };
    Vec3 d0 = a.c - b.c;
    if (d0.squaredNorm() == 0) d0 = Vec3::UnitX();
    std::array<Vec3, 4> W;
    std::array<std::array<Vec3, 2>, 4> companions;
    std::array<double, 4> lambda{1, 0, 0, 0};
    W[0] = support(-d0);
    companions[0] = pair;
    int size = 1;
    Vec3 v = W[0];
    double scale = v.norm();
    for (int it = 0; it < maxIterations; ++it) {
        const double v2 = v.squaredNorm();
        // The origin is (numerically) in the difference: the hulls touch or overlap.
        if (v2 <= 1e-24 * scale * scale || v2 == 0) return {};
        const Vec3 w = support(-v);
        scale = std::max(scale, w.norm());
        // No progress along -v: |v| is the distance (lower bound v.w / |v|).
        if (v2 - v.dot(w) <= relTol * v2) break;
        bool duplicate = false;
        for (int i = 0; i < size; ++i) duplicate |= (W[i] == w);
        if (duplicate) break;
        companions[size] = pair;
        W[size++] = w;
        v = detail::closestOnSimplex(W, size, companions, lambda);
        if (size == 4) return {}; // origin inside a tetrahedron of the difference
    }
    Closest c{v.norm(), Vec3::Zero(), Vec3::Zero()};
    for (int i = 0; i < size; ++i) c.onA += lambda[i] * companions[i][0], c.onB += lambda[i] * companions[i][1];
    return c;
}

/// Euclidean distance between the convex hulls of a and b (0 when they intersect).
/// relTol: stop when the distance is known to this relative accuracy.
inline double distance(const PlacedPoints& a, const PlacedPoints& b, double relTol = 1e-10, int maxIterations = 100) {
    return closest(a, b, relTol, maxIterations).distance;
}

} // namespace mag::gjk
