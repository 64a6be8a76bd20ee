// Target samples on a body's boundary for the boundary integrals of Eqs. 16-18, built
// once per mesh in the body frame from the merged planar faces of PolyhedronTables.
//
// Rules (n >= 1):
//   regular  the paper's rule (Sec. 6.1: "n^2 points sampled from each square face"):
//            - planar convex quadrilateral face: centres of the n x n cells of the
//              bilinear map of [0,1]^2, weight = |J| at the centre / n^2 (the midpoint
//              rule; the weights of a planar quad sum to its area exactly);
//            - triangular face: the centroids of the n^2 congruent sub-triangles
//              (n(n+1)/2 upright, n(n-1)/2 inverted), weight area / n^2;
//            - any other face: each of its triangles with the triangle rule.
//            This is the variant that reproduces the paper's Fig. 5 numbers (coaxial
//            1 cm cubes, Br = 1 T, gap 0.02 cm: 30.33 N at n = 2, 28.68 N at n = 20);
//            see test_mbmWrench.cpp for the comparison with the other variants.
//   gauss    (the default in magFoam) n x n tensor Gauss-Legendre on the bilinear map
//            of a convex quadrilateral face (exact for degree 2n-1 in each direction
//            on a parallelogram); on a triangle the collapsed (Duffy) n x n
//            Gauss-Legendre rule: (u, v) in [0,1]^2 -> r0 + u (r1 - r0) + u v (r2 - r1),
//            weight 2 area u w_u w_v, exact for total degree <= 2n - 2 (its points
//            cluster at r0); other faces: each triangle with the triangle rule.
//            Coaxial 1 cm cubes (test_mbmWrench.cpp, "gauss rule: force between coaxial
//            cubes"): n = 20 (400 per face) stays within 1e-4 of Akoun-Yonnet at every
//            gap from 0.02 cm, n = 10 within 1e-3 from 0.1 cm; convergence is spectral
//            once the points resolve the gap.
//            Limitation: a source edge running close beneath the INTERIOR of a face
//            (not its rim, where Gauss points cluster) needs a larger n.
//
// Sample order: face by face (faces[] says which), so per-face sums are contiguous.
#pragma once

#include "PolyhedronTables.hpp"

#include <Eigen/Geometry>

#include <string_view>
#include <span>
#include <vector>

namespace mag::mbm {

/// Boundary quadrature rule.
enum class QuadratureRule {
    regular, ///< the paper's n x n midpoint rule per planar face
    gauss    ///< n x n Gauss-Legendre per face (collapsed on triangles)
};

/// Parses "regular" or "gauss"; throws std::invalid_argument listing the valid names.
QuadratureRule quadratureRuleFromName(std::string_view name);

/// Samples on the boundary, body frame.
struct SurfaceQuadrature {
    std::vector<Vec3> points;   ///< m
    std::vector<double> weights; ///< m^2 (sum = surface area)
    std::vector<Vec3> normals;  ///< outward unit normal of the sample's face
    std::vector<int> faces;     ///< index into PolyhedronTables::faces()
    std::size_t size() const { return points.size(); }
};

/// Corners of face `face` when it is a single boundary loop whose turning vertices form
/// a strictly convex polygon (CCW about its normal, collinear intermediate vertices
/// skipped); empty otherwise (the face is then used triangle by triangle).
std::vector<Vec3> convexFaceCorners(const PolyhedronTables& tables, int face);

/// Builds the samples of `rule` with parameter n (>= 1) on every planar face of `tables`.
SurfaceQuadrature buildSurfaceQuadrature(const PolyhedronTables& tables, QuadratureRule rule,
                                         int n);

/// Samples moved by the rigid transform x -> T x (e.g. target body -> source body):
/// points transformed, normals rotated; weights are unchanged and not copied.
void transformSamples(const SurfaceQuadrature& q, const Eigen::Isometry3d& T,
                      std::vector<Vec3>& points, std::vector<Vec3>& normals);

/// Gauss-Legendre nodes and weights on [-1, 1] (n >= 1), by Newton on P_n.
void gaussLegendre(int n, std::vector<double>& nodes, std::vector<double>& weights);

/// Bilinear map of the planar quadrilateral c[0..3] (CCW): point and |J| at (s, t) in [0,1]^2.
void bilinearMap(std::span<const Vec3> c, double s, double t, Vec3& p, double& jac);

} // namespace mag::mbm
