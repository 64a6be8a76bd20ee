// Tolerance-driven boundary quadrature for the MBM interaction (Eqs. 16-18): the paper's
// "auto-setting technique" for the sample count (Sec. 7), docs/physics.md#adaptive-quadrature.
//
//   field: {type: MBM, quadrature: {type: adaptive, tolerance: 1e-4}}
//
// 1. Contact geometry first (ContactSplit.hpp): each target face is cut into convex
//    pieces along the source features lying in or near its plane, so that the
//    integrand is smooth inside every piece; sides on such features are `singular`.
// 2. Elements: each piece is a quadrilateral (bilinear map of [0,1]^2) or a triangle
//    (collapsed map, apex at s = 0) - polygons with more corners are fanned into both.
//    An element's rule is n x n tensor Gauss-Legendre (n = order) in (s, t). In a
//    direction whose end lies on a source feature, or within one box width of one, the
//    rule is graded towards it with max(2n, 8) points: s = tau^3 for a feature on the
//    side (a log x becomes tau^2 ln tau), a geometric chain of Gauss intervals each
//    three times as wide as its distance to the feature for a feature at a distance g
//    (a gap: the chain reaches the scale g in log_4(1/g) intervals). A triangle's apex
//    counts as a
//    feature when a side through it does.
// 3. Two kinds of element. On a feature, or nearer to the source than 0.05 of its
//    width: refined by HALVING. An element's value is the sum of its four children's
//    rules (the halves in s and t); the parent's error is |children - parent| in the
//    metric e(W) = max(|F|, |T + Tm| / L), L = the target's bounding radius, and the
//    children sum's error is estimated as a quarter of it (a halving gains 2^(2n) on
//    a smooth integrand, at least 4 on a graded one).
//    Otherwise: refined by ORDER. Gauss m x m, m the order that the geometric
//    convergence rate rho (Bernstein ellipse; guaranteed by a lower bound of the
//    distance to the source's faces) predicts for the tolerance, 2..n + 2, with its
//    estimate from Gauss (m - 2) scaled by rho; raising the order jumps to the one
//    the rate predicts, up to 12, then the element halves into order elements.
//    The tolerance chart in cases/benchmarks compares the estimates with the
//    achieved error.
// 4. Refinement: while the summed estimate exceeds tolerance x e(W_total) (with a floor
//    of 1e-9 of the summed |F| of the elements, for pairs whose force cancels to 0),
//    the elements holding half of the estimated error (largest first) are refined.
//    A far pair stops at its first rules (5 samples per face 4 cm from a 1 cm cube);
//    a touching pair spends its samples beside the contact.
//
// Deterministic: each round's elements are evaluated in parallel (parallelFor), and
// every sum runs over the elements in a fixed order, so the result does not depend on
// the thread count.
#pragma once

#include "ContactSplit.hpp"
#include "InteractionWrench.hpp"

#include <cstddef>

namespace mag::mbm {

/// Settings of the adaptive rule (MBMField reads them from quadrature: {...}).
struct AdaptiveSettings {
    double tolerance = 1e-4;          ///< relative, of the pair's force and torque / L
    int order = 3;                    ///< Gauss points per element side, 1..12
    std::size_t maxSamples = 200000;  ///< per pair; reached = `capped`
    ForceForm form = ForceForm::split; ///< how each element's integrals are written
};

/// Result of one pair, in the source frame.
struct AdaptiveResult {
    Wrench wrench;             ///< force, torques about rc, energy
    std::size_t samples = 0;   ///< field evaluations taken
    std::size_t elements = 0;  ///< elements in the final partition
    double estimate = 0.0;     ///< estimated error / e(W_total) at the end
    bool capped = false;       ///< stopped at maxSamples before meeting the tolerance
};

/// The wrench on `target` (placed by T: target frame -> source frame, magnetization Mt
/// and centre of mass rc in the source frame) in the field of `source` (magnetization
/// Ms, source frame), to `settings.tolerance`.
AdaptiveResult adaptiveInteraction(const PolyhedronTables& source, const Vec3& Ms,
                                   const PolyhedronTables& target, const Eigen::Isometry3d& T,
                                   const Vec3& Mt, const Vec3& rc, OverlapModel model,
                                   const AdaptiveSettings& settings);

} // namespace mag::mbm
