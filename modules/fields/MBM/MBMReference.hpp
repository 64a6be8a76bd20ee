// The straightforward, face-by-face form of the polyhedron field (paper Eqs. 9-15): for
// every point and every planar face p, W_p, grad W_p and Omega_p from faceIntegrals()
// (each edge's omega_e computed once per adjacent face, one atan2 per triangle), then
//   B = mu0/(4 pi) sum_p grad W_p x (M x n_p)      (Eq. 11)
//   S = sum_p W_p n_p,  A = mu0/(4 pi) M x S       (Eq. 9)
//   insideFraction = sum_p Omega_p / (4 pi)        (Eq. 15)
//
// The baseline the fast kernel (PolyhedronField.hpp, evaluate()) is checked and timed
// against: same outputs, same conventions on the boundary, no regrouping, no SIMD.
#pragma once

#include "PolyhedronField.hpp"

namespace mag::mbm::reference {

/// Same contract as mag::mbm::evaluate(tables, M, points, out).
void evaluate(const PolyhedronTables& tables, const Vec3& M, std::span<const Vec3> points,
              const FieldOutputs& out);

} // namespace mag::mbm::reference
