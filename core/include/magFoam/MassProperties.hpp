// Exact mass properties of a closed triangulated solid of uniform density.
//
// The volume integrals of 1, x, y, z, x^2, y^2, z^2, xy, yz, zx are turned into
// sums over the triangles by the divergence theorem (D. Eberly, "Polyhedral Mass
// Properties (Revisited)", 2002; same results as Mirtich 1996 and Tonon 2004).
// The formulas are exact for polyhedra, so only rounding limits the result:
// vertices are taken relative to the bounding-box centre and the sums are
// compensated, which keeps a box exact to ~1e-15 relative wherever it sits.
#pragma once

#include <magFoam/SurfaceMesh.hpp>

namespace mag {

struct MassProperties {
    double density = 1.0;      // kg/m^3 (1: the values below are per unit density)
    double volume = 0.0;       // m^3
    double mass = 0.0;         // density * volume, kg
    Vec3 centreOfMass = Vec3::Zero();
    // Inertia tensor about the centre of mass, world axes, kg m^2:
    // I = integral of rho (|r|^2 1 - r r^T) dV, r from the centre of mass.
    Mat3 inertia = Mat3::Zero();
    // Eigenvalues of inertia in ascending order, and the matching unit axes as the
    // columns of a proper rotation (det = +1): inertia = axes diag(moments) axes^T.
    Vec3 principalMoments = Vec3::Zero();
    Mat3 principalAxes = Mat3::Identity();
    // Largest vertex distance from the centre of mass (the body's bounding sphere).
    double boundingRadius = 0.0;
};

// Signed volume enclosed by the mesh (> 0 for outward normals). Meaningful only for
// a closed, consistently oriented mesh.
double signedVolume(const SurfaceMesh& mesh);

// Mass properties for the given density. Expects a usable mesh (requireUsable);
// throws InputError if the signed volume is not positive, since every quantity
// would then be meaningless.
MassProperties computeMassProperties(const SurfaceMesh& mesh, double density = 1.0);

// Largest distance from centre to a vertex.
double boundingSphereRadius(const SurfaceMesh& mesh, const Vec3& centre);

// Inertia of a body about another point (parallel axis theorem), world axes.
Mat3 inertiaAbout(const MassProperties& properties, const Vec3& point);

// Moves the mesh so that its centre of mass is the origin (a body's frame, see
// docs/physics.md#units-and-conventions); returns the centre of mass it had, i.e. the translation undone.
Vec3 recentre(SurfaceMesh& mesh);

} // namespace mag
