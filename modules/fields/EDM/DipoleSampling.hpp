// Dipole sampling of a uniformly magnetized body for the Equivalent Dipole Method
// (paper Sec. 3; Kim et al. 2018): cell centres of a regular n x n x n grid over the
// body-frame bounding box, kept when inside the mesh.
//
// Inside test for any closed, outward-oriented triangle mesh: the generalized winding
// number w(p) = sum_t Omega_t(p) / (4 pi) > 0.5, with the signed solid angle of each
// triangle after Van Oosterom & Strackee (paper Eq. 15; positive on the inner side):
//   Omega_t = 2 atan2(a . (b x c), |a||b||c| + |a|(b.c) + |b|(c.a) + |c|(a.b)),
//   a, b, c = corners - p.
// w is 1 inside, 0 outside and degrades gracefully for slightly open meshes.
#pragma once

#include <magFoam/SurfaceMesh.hpp>
#include <magFoam/Types.hpp>

#include <vector>

namespace mag::edm {

// The inside test of gridDipoles is core's windingNumber (SurfaceMesh.hpp).

/// Dipole positions (body frame) and the volume each one carries: moment = M * volume.
struct DipoleTable {
    std::vector<Vec3> positions; ///< m, body frame (origin = centre of mass)
    double cellVolume = 0;       ///< m^3 per dipole; cellVolume * size() = body volume
    int n = 0;                   ///< grid cells per bounding-box edge (1: one dipole at the COM)
    bool fallback = false;       ///< no cell centre was inside: one dipole at the COM
    std::size_t size() const { return positions.size(); }
};

/// One dipole at the centre of mass carrying the whole volume: exact outside a
/// uniformly magnetized sphere, the point-dipole model otherwise.
DipoleTable singleDipole(double volume);

/// The n x n x n grid sampling of `mesh` (body frame, COM at the origin); each kept
/// cell centre carries volume / (number kept), so the total moment is exactly M * volume.
/// No cell centre inside (thin body, coarse grid): one dipole at the COM (fallback).
DipoleTable gridDipoles(const SurfaceMesh& mesh, double volume, int n);

} // namespace mag::edm
