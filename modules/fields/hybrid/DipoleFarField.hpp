// Far field of a scene: pairs of bodies far apart against their size interact as
// two point dipoles m = M V at their centres of mass (corrected Eq. 5, Eq. 6).
// The hybrid evaluator says how far is far (its dipole reach: a pair is a dipole
// pair when |c_i - c_j| > reach_i + reach_j); it evaluates all such pairs here,
// in bulk, and only the others pair by pair.
//
// Cost. The bulk sum visits every (target, source) pair once: O(N^2), but far
// cheaper per pair than the per-pair interface (structure of arrays, one vector
// lane per target; timings: cases/benchmarks). Near pairs are found by a uniform
// grid (NearPairs), so they cost O(N) to find. Past a few thousand bodies the
// fast multipole sum of the same pairs (DipoleMultipole.hpp, O(N)) is faster;
// the hybrid picks one by its `farField:` setting.
//
// Accuracy: that of the dipole approximation (see the hybrid evaluator: relative
// O((R/d)^2), O((R/d)^4) for bodies with isotropic second moments); the bulk sum
// equals dipolePairWrench() to rounding (tests/test_dipoleFarField.cpp).
#pragma once

#include "magFoam/Body.hpp"
#include "magFoam/Wrench.hpp"

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

namespace mag {

// Wrench on a dipole mt at c_t from a dipole ms at c_s, r = c_t - c_s (about c_t):
//   F = 3 mu0/(4 pi d^5) [(ms.r) mt + (mt.r) ms + (ms.mt) r - 5 (ms.r)(mt.r) r / d^2]
//   torque = mt x B_s(c_t), energy = -mt . B_s(c_t), mechanicalTorque = 0.
Wrench dipolePairWrench(const Vec3& ms, const Vec3& mt, const Vec3& r);

// Error of the dipole approximation for a pair, from the two shapes (uniform
// magnetization and density). The field of a uniformly magnetized body is
// -M . grad of its volume's Newtonian potential, so the multipoles past the dipole
// are the volume's moments about the centroid: the first vanishes, the second (the
// quadrupole Q = 3 J - tr(J) 1, J = int x x^T dV) gives a relative error
// O(|Q| / (V d^2)), and bodies with isotropic second moments (cubes, spheres) are
// left with the fourth, O((R/d)^4). Estimate, for centre distance d:
//   eps(d) = c2 (q_s + q_t) / d^2 + c4 ((R_s + R_t) / d)^4,   q = |Q|_F / V (m^2),
// bounding |dF| / (3 mu0 |m_s||m_t| / (4 pi d^4)) and |dT| / (3 mu0 |m_s||m_t| /
// (4 pi d^3)) (the errors of force and torque against the scale of a dipole pair's
// force and torque at d). c2 = 12, c4 = 0.3 lie above the largest ratios of the
// error to each term measured against MBM over random orientations of cubes, 3:1
// bars, 20:20:3 plates, 10:1 rods and spheres at d = 2..16 (R_s + R_t); the test
// "dipole tier: the moment estimate bounds the error for any shape and
// orientation" (tests/test_farField.cpp) checks the bound on other orientations.
double shapeQuadrupole(const Shape& shape);  // q = |Q|_F / V, m^2
double dipoleErrorEstimate(const Shape& source, const Shape& target, double distance);
// The reach for tolerance tol: pairs with d > reach_s + reach_t have eps(d) <= tol,
// since then d^2 >= a^2 (q_s + q_t) and d >= b (R_s + R_t) with
// reach = a sqrt(q) + b R, a = sqrt(2 c2 / tol), b = (2 c4 / tol)^(1/4).
double dipoleReachFor(const Shape& shape, double tol);

// One body as the far field sees it.
struct FarFieldBody {
    Vec3 position;  // centre of mass, m
    Vec3 moment;    // M V, A m^2
    double reach;   // m; may be +inf (never a dipole pair)
    bool fixed;
};

// A body as the far field sees it, with the reach the evaluator gives it. Out of
// line, in this kernel's contraction-free code: the moment M V rotated into the
// world rounds the same wherever the evaluator calls it from.
FarFieldBody farFieldBody(const Body& b, double reach);

// The pair test: |c_a - c_b|^2 > (reach_a + reach_b)^2, rounded the same for (a, b)
// and (b, a) and in the bulk sum.
bool isDipolePair(const FarFieldBody& a, const FarFieldBody& b);

// Pairs (i < j) that are NOT dipole pairs, |c_i - c_j|^2 <= (reach_i + reach_j)^2,
// in increasing (i, j) order, found with a uniform grid of cell 2 max(finite reach).
// With skipFixedPairs, pairs of two fixed bodies are left out.
std::vector<std::pair<std::size_t, std::size_t>> nearPairs(std::span<const FarFieldBody> bodies,
                                                           bool skipFixedPairs);

// Adds to out[i] the wrench on body i from every body j that is a dipole pair with
// it (the complement of nearPairs, the same test to the bit); returns the number of
// such pairs (each counted once). Parallel over blocks of targets; each target's sum
// runs over the sources in index order, so the result is bit-identical for any
// thread count.
std::uint64_t addDipoleFarField(std::span<const FarFieldBody> bodies, bool skipFixedPairs, std::span<Wrench> out);

} // namespace mag
