// The volume average of a field over a closed polyhedron from its boundary,
// and the body's demagnetization tensor from its mesh.
//
// Volume average (Stokes on the volume): for B = curl A,
//   integral_V B dV = closed integral of n x A dA,
// so B-bar = (1/V) sum_q w_q (n_q x A(x_q)) over Gauss points of the surface:
// A is continuous across a body's surface, so the same rule serves a source
// outside the body and the body's own field.
//
// Demagnetization tensor (magnetometric): uniform M in the body gives the
// volume-averaged self-field H-bar = -N M, and with B = mu0 (H + M) inside,
//   N e_k = e_k - (1/(mu0 V)) integral_V B_k dV,
// B_k the body's own field for M = e_k (A/m), evaluated by the closed forms of
// MBM (Fabbri) at the surface points. Symmetric, trace 1; a cube and a sphere
// have I/3. A's gradient is log-singular at edges, so the rule (tensorRule) is
// a graded centroid fan; every rule for N is symmetric under the permutations
// of each triangle's corners, so N keeps the mesh's symmetry exactly (an
// icosphere's N is isotropic to rounding, and a sphere feels no torque in a
// uniform field). A 1:2:3 box is 7.5e-12 off Aharoni at order 20
// (docs/physics.md#demag).
#pragma once

#include <magFoam/Body.hpp>
#include <magFoam/FieldEvaluator.hpp>

#include <vector>

namespace mag::demag {

// Gauss points on a body's surface in its body frame: where, and the weighted
// outward normal w_q n_q (m^2) of each.
struct SurfaceRule {
    std::vector<Vec3> points, weightedNormals;
};

// The rule for N: order >= 1 the graded centroid fan of 3 order^2 points per
// triangle; order -3, -6, -7 a symmetric rule of that many points (for meshes of
// many triangles, where cost ~ points x triangles). Both symmetric in each
// triangle's corners.
SurfaceRule tensorRule(const SurfaceMesh& mesh, int order);
int tensorRulePoints(int order); // points per triangle

// (1/V) sum_q wn_q x A_q: the volume average of B = curl A.
Vec3 volumeAverage(const std::vector<Vec3>& weightedNormals, const std::vector<Vec3>& A, double volume);

// N of `shape` in its body frame, from the closed-form A of `mbm` (an MBM
// evaluator: its A must be exact on the body's own surface).
Mat3 demagTensor(const std::shared_ptr<const Shape>& shape, const FieldEvaluator& mbm, int order = 20);

} // namespace mag::demag
