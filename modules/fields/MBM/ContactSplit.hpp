// Contact geometry for the adaptive boundary quadrature (docs/physics.md#adaptive-quadrature):
// the target's planar faces cut into convex pieces on whose interiors the source's field
// is smooth.
//
// Where the source touches or nearly touches a target face the integrand of Eqs. 16-18
// is rough along lines in the face plane, and only there:
//   - it JUMPS across the line where a source face meets the plane (the solid angle
//     Omega_p of Eq. 15 steps by 4 pi across face p; insideFraction steps with it);
//   - it is LOGARITHMIC along a source edge lying in the plane (omega_e of Eq. 14),
//     and nearly so along the projection of a source edge within dNear of it (a gap).
// Both are split out exactly: every such line segment (a source edge within dNear of
// the plane, projected onto it; the chord of a source face crossing the plane) cuts
// the pieces it passes through, and the sides on such lines, or parallel to one within
// dNear, carry the distance to it (`feature`: 0 on it, the gap otherwise), so that the
// quadrature grades its points towards them down to that scale. A piece is never cut
// by a line that only passes near it (the segment must reach the piece).
//
// Point features (a source vertex on the face, a source edge piercing it) are left to
// the adaptive refinement: a point singularity costs a few refinement levels, a line
// costs the length of the line.
//
// `inwardOffset` is non-zero for target faces lying on a source face plane (to the plane
// tolerance 1e-10 of the size plus the coordinates' rounding): their samples must take
// the field's one-sided limit from the target's interior, where the kernel returns the
// principal value (the mean of both sides) on the plane. The quadrature moves them
// that far into the target: ten plane tolerances, ~1e-9 of the size, so the kernel
// sees them decidedly on the target's side; the field moves by O(1e-9) there.
#pragma once

#include "PolyhedronTables.hpp"

#include <Eigen/Geometry>

#include <vector>

namespace mag::mbm {

/// A convex piece of one target face, in the source frame.
struct FacePiece {
    int face = -1;                ///< target face index (PolyhedronTables::faces())
    std::vector<Vec3> corners;    ///< CCW about the face's outward normal
    /// Per side i (corner i -> i + 1): distance (m) to the nearest source feature along
    /// it: 0 on a feature, > 0 for a feature that close (a gap), -1 for none.
    std::vector<double> feature;
};

/// The pieces of every target face for one source/target placement.
struct TargetPieces {
    std::vector<FacePiece> pieces;
    std::vector<Vec3> normals;  ///< per target face: outward unit normal, source frame
    std::vector<double> inwardOffset; ///< per target face: m, > 0 on a source face plane
    /// per target face: dNear (m); every source feature nearer to the face plane was cut
    /// along (or lies outside the face), so the pieces see nearer features only on their sides
    std::vector<double> nearDistance;
    std::size_t cuts = 0;       ///< pieces created by cutting (diagnostics)
};

/// Cuts the faces of `target` (placed in the source frame by T: target -> source) along
/// the source features within dNear = nearFraction x (face diameter) of each face plane.
void splitTargetFaces(const PolyhedronTables& source, const PolyhedronTables& target,
                      const Eigen::Isometry3d& T, TargetPieces& out, double nearFraction = 0.3);

} // namespace mag::mbm
