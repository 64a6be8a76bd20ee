// Closed-form field of a uniformly magnetized polyhedron (Fabbri 2008; paper Eqs. 9-15),
// evaluated in the polyhedron's own frame.
//
//   A(r) = mu0/(4 pi) M x sum_p W_p(r) n_p                              (Eq. 9)
//   B(r) = mu0/(4 pi) sum_p grad W_p(r) x (M x n_p)                     (Eq. 11)
//   W_p  = sum_{e in dp} omega_e (n_p x (r_e - r)) . u_e - Omega_p (r_p - r) . n_p  (Eq. 12)
//   grad W_p = sum_{e in dp} omega_e (n_p x u_e) + Omega_p n_p          (Eq. 13)
//   omega_e = ln((R1 + R2 + L) / (R1 + R2 - L))                          (Eq. 14)
//   Omega_p = sum_t 2 atan2(a . (b x c), D)  (Van Oosterom-Strackee)    (Eq. 15)
//
// Conventions (docs/physics.md#solid-angle, verified by the tests):
//   - Omega_p > 0 when r lies on the inner side of face p; sum_p Omega_p = 4 pi inside
//     the body and 0 outside, so insideFraction = sum_p Omega_p / (4 pi).
//   - B includes mu0 M inside the body; H = B/mu0 - M insideFraction is the charge
//     (demagnetizing) field; scalarPotential phi = M . sum_p W_p n_p / (4 pi) is the
//     magnetic scalar potential of the surface charge M . n, with H = -grad phi.
//
// Numerically stable forms (docs/physics.md#stable-forms):
//   - omega_e far away: log1p(2L / (S - L)), S = R1 + R2;
//   - near the segment (a . b < 0): ln[(S + L)^2 (R1 R2 - a . b) / (2 |a x (r2 - r1)|^2)];
//   - triple product a . (b x c) = 2 area (a . n_p), a . n_p = (r_v - r) . n_p from one
//     vertex per face (exactly 0 for a point on an axis-aligned face).
//
// Values ON the source's boundary are defined and finite (touching/overlapping bodies put
// samples there):
//   - on a face plane Omega_p = 0: the principal value, i.e. the mean of both one-sided
//     limits (insideFraction = 1/2 inside a face, the interior solid-angle fraction on an
//     edge or at a vertex). "On the plane" means |(r_p - r) . n_p| <= 16 eps (|r| +
//     max_v |r_v|), the rounding of the coordinates: without that, a point on the edge
//     of a tilted face gets atan2(~1e-19, ~1e-22), an arbitrary angle;
//   - omega_e is regularized by clamping the distance to the edge LINE to at least
//     delta L, delta = kEdgeRegularization (the point is moved perpendicularly off the
//     line to that distance, its abscissa along the line kept, and Eq. 14 evaluated
//     there). The result is continuous, omega_e <= ln(1/delta^2) = 41.4, and points
//     farther than delta L from the line are unaffected (beyond the segment's ends
//     and more than 1e-4 L from a vertex the clamp is skipped: it would change omega
//     by < 1e-10 there).
//
// Cost per point: one distance per vertex, one log per edge between different faces
// (omega_e shared by its two faces, Sec. 5), one atan2 per planar face (the triangles'
// Van Oosterom-Strackee fractions are multiplied as complex numbers D + iN first);
// no allocation per point (scratch reused per thread).
//
// Throughput: evaluate() takes the points in blocks of 4 (AVX2) or 8 (AVX-512), one
// SIMD lane per point (SimdMath.hpp: vector log and atan2 to < 1 ulp), the last block
// padded. The default x86-64 build holds both widths and picks the one the CPU runs at
// the first call (KernelPath.hpp: MAG_KERNEL=auto|avx2|avx512, setKernelPath()).
// The per-call tables (the M-dependent coefficients of every edge and face) are kept
// per thread and reused while a call repeats the last one's tables, M and kernel copy
// (the wrench evaluates a target's samples in blocks of 32, all with the same source).
// A lane that needs edgeLogTerm's special forms (within delta L of an edge line or
// ~1e-4 L of a vertex) is recomputed by the scalar form, so the semantics above hold
// per point; results agree with the face-by-face form (MBMReference.hpp) to rounding
// (tests/test_mbmKernel.cpp). Timings: the `kernel` study of cases/benchmarks.
#pragma once

#include "PolyhedronTables.hpp"

#include <magFoam/Types.hpp>

#include <numbers>
#include <span>

namespace mag::mbm {

/// Vacuum permeability: the one of magFoam/Types.hpp.
using mag::mu0;

/// Relative edge regularization delta: omega_e uses max(distance to the edge line,
/// delta L). 1e-9 L (1e-11 m for a 1 cm edge) changes nothing measurable elsewhere.
inline constexpr double kEdgeRegularization = 1e-9;

/// Optional outputs of evaluate(); an empty span is not computed.
struct FieldOutputs {
    std::span<Vec3> B;                  ///< flux density (T), Eq. 11
    std::span<Vec3> A;                  ///< vector potential (T m), Eq. 9
    std::span<double> insideFraction;   ///< sum_p Omega_p / (4 pi), Eq. 15
    std::span<double> scalarPotential;  ///< phi (A), H = -grad phi (charge model)
    /// S = sum_p W_p n_p = oint n'/|r - r'| dA' (m): the geometric part of A = mu0/(4 pi)
    /// M x S and phi = M . S / (4 pi); S = -grad of the body's Newtonian potential
    /// int_V dV'/|r - r'|, so int over a closed surface of S . n / (4 pi) is the volume
    /// of the body inside that surface.
    std::span<Vec3> S;
};

/// Everything at one point.
struct PointField {
    Vec3 B = Vec3::Zero();       ///< T
    Vec3 A = Vec3::Zero();       ///< T m
    double insideFraction = 0.0; ///< 1 inside, 0 outside, 1/2 on a face
    double scalarPotential = 0.0; ///< A
    Vec3 S = Vec3::Zero();        ///< m, sum_p W_p n_p
};

/// Field of the polyhedron `tables` uniformly magnetized with M (A/m, body frame) at
/// `points` (m, body frame). B.size() == points.size(); A and insideFraction may be
/// empty (not computed), otherwise of the same size.
void evaluate(const PolyhedronTables& tables, const Vec3& M, std::span<const Vec3> points,
              std::span<Vec3> B, std::span<Vec3> A = {}, std::span<double> insideFraction = {});

/// General form: any subset of the outputs (each empty or points.size() long).
void evaluate(const PolyhedronTables& tables, const Vec3& M, std::span<const Vec3> points,
              const FieldOutputs& out);

/// Single-point convenience overload (all outputs).
PointField evaluate(const PolyhedronTables& tables, const Vec3& M, const Vec3& point);

/// Charge (Coulombian) field H = B/mu0 - M insideFraction (A/m).
inline Vec3 chargeField(const Vec3& B, const Vec3& M, double insideFraction) {
    return B / mu0 - insideFraction * M;
}

/// Per-face integrals of one planar face p at one point (the slow reference path used
/// by tests and diagnostics; evaluate() regroups the same terms edge-major).
struct FaceIntegrals {
    double W = 0.0;              ///< W_p = int_p dA'/|r - r'| (m), Eq. 12
    Vec3 gradW = Vec3::Zero();   ///< grad W_p = int_p (r' - r)/|r' - r|^3 dA', Eq. 13
    double solidAngle = 0.0;     ///< Omega_p (sr), Eq. 15
};

/// W_p, grad W_p and Omega_p of face `face` of `tables` at `point`.
FaceIntegrals faceIntegrals(const PolyhedronTables& tables, int face, const Vec3& point);

/// The same with the on-plane tolerance given (see planeTolerance()), so that a loop
/// over the faces computes it once per point.
FaceIntegrals faceIntegrals(const PolyhedronTables& tables, int face, const Vec3& point,
                            double planeTolerance);

/// |h| at or below which `point` counts as on a face plane: 16 eps (|r| + max_v |r_v|),
/// the rounding of the coordinates (see the file comment).
double planeTolerance(const PolyhedronTables& tables, const Vec3& point);

/// Edge term omega_e (Eq. 14) of the segment r1 -> r2 seen from r, in stable form and
/// regularized as described above: a = r1 - r, b = r2 - r, R1 = |a|, R2 = |b|,
/// delta = r2 - r1, L = |delta|.
double edgeLogTerm(const Vec3& a, const Vec3& b, double R1, double R2, double L,
                   const Vec3& delta);

/// Signed solid angle (Eq. 15) of the triangle (r1, r2, r3), CCW about unit normal n,
/// seen from r: a, b, c = r_i - r, R_i their norms, twiceArea = 2 area,
/// height = (r1 - r) . n. Positive when r is on the inner side (-n); 0 where the triple
/// product is exactly 0 (principal value on the plane).
double triangleSolidAngle(const Vec3& a, const Vec3& b, const Vec3& c, double Ra, double Rb,
                          double Rc, double twiceArea, double height);

} // namespace mag::mbm
