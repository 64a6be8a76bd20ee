// Contact post-processing for the ODE backend: what ODE's colliders return
// for one pair of geoms is corrected before contact joints are made.
//
// Why. Debian 12's ODE 0.16.2 (OPCODE trimesh collider) returns, for triangle
// meshes that touch face to face, contacts whose normal is the normal of a
// SIDE triangle that happens to cut the other mesh's face. Two cubes given as
// meshes, the upper one 0.17 mm into the lower one: of 17 contacts, 9 have a
// horizontal normal (depth 0.17 mm or 9.8 mm), none carries triangle indices
// (side1 = side2 = -1). Turned into contact joints they push the upper cube
// sideways and spin it: pulled down by 50 N after landing tilted, it is thrown
// 0.9 m away at 2300 m/s (impact 2.6 m/s; with the correction: at most
// 6.8 m/s, a tumbling corner, and at rest after 0.4 s; tests/
// test_odeBackend.cpp [odeArtefact]). Trimesh-box shows the same (normals
// along the lateral offset). Primitive-primitive and anything-plane contacts
// are exact and are left alone.
//
// What is done for a pair with at least one triangle mesh (no plane):
// 1. Hull check. separation(n) = h2(n) + h1(-n) (h: support functions) is
//    how far geom 1 must move along n to clear the convex hull of geom 2: an
//    upper bound of any penetration along n, exact for convex bodies. If the
//    hulls are apart along one of the contact normals, there is no contact.
// 2. Normal correction, per contact, from LOCAL geometry. Candidates are the
//    faces near the contact point, of either geom: the triangles of a mesh
//    within a neighbourhood (the contact's depth, capped by the hull
//    separation, plus `radius`, 2% of the smaller body), the six faces of a
//    box, the tangent plane of a sphere, caps and side of a cylinder. A face
//    is scored by how deep the OTHER geom reaches behind its plane (the
//    corners of the other mesh's nearby triangles, or a primitive's exact
//    support function). The shallowest face is the contact's face: its
//    normal (oriented so geom 1 leaves it) and that depth (capped by the hull
//    separation) replace ODE's. A side triangle that cuts the other body's
//    face scores the whole width of that face, so the face wins; in a
//    concave corner each wall wins for the contacts against it (local, so
//    non-convex meshes work: a clip touching a magnet on two sides keeps
//    both normals). Contacts whose neighbourhoods are apart are dropped. If
//    the best face is much deeper than ODE's contact (deeper than twice
//    ODE's depth plus the neighbourhood), the neighbourhood missed the face
//    that matters and ODE's contact is kept.
// 3. Merging of coincident contacts (same point, same normal).
// 4. Reduction to maxContacts by farthest-point selection from the deepest
//    (in position and normal), which keeps the support polygon of a resting
//    face, and every face of a concave contact.
#pragma once

#include <magFoam/ConvexPieces.hpp>
#include <magFoam/SurfaceMesh.hpp>
#include <magFoam/Types.hpp>

#include <array>
#include <functional>
#include <vector>

namespace mag::ode {

struct ContactPoint {
    Vec3 position = Vec3::Zero();
    Vec3 normal = Vec3::UnitZ(); // ODE convention: moving geom 1 by depth * normal separates
    double depth = 0;
    int source = 0;              // index into what the collider returned
};

// Support function h(u) = max over the geom of x . u (world frame).
using SupportFunction = std::function<double(const Vec3&)>;

// The triangles of a mesh in its body frame, with what the queries need.
struct TriangleSet {
    std::vector<std::array<Vec3, 3>> corners;
    std::vector<Vec3> normals; // unit, outward
    std::vector<Vec3> centres; // bounding sphere of each triangle
    std::vector<double> radii;
    static TriangleSet build(const SurfaceMesh& mesh);
};

// A face plane: outward unit normal and offset (x . normal = offset on it).
struct Plane {
    Vec3 normal;
    double offset;
};

// One geom of a pair, as the correction sees it.
struct GeomView {
    SupportFunction support;                   // the whole geom (its convex hull for a mesh)
    const TriangleSet* triangles = nullptr;    // meshes; null for primitives
    Mat3 rotation = Mat3::Identity();          // geom frame -> world
    Vec3 position = Vec3::Zero();              // geom origin, world
    // Primitives: the face planes near a world point (the six faces of a
    // box, the tangent plane of a sphere, the caps and the tangent plane of
    // the side of a cylinder).
    std::function<void(const Vec3&, std::vector<Plane>&)> surfacePlanes;
};

// Steps 1 and 2 above. `slack` (m) absorbs the surface layer and round-off.
// Returns how many contacts were dropped.
int correctMeshContacts(std::vector<ContactPoint>& contacts, const GeomView& g1, const GeomView& g2, double radius,
                        double slack);

// Step 3: contacts closer than `distance` with normals within ~8 degrees are
// one contact; the deepest is kept. Returns how many were merged away.
int mergeContacts(std::vector<ContactPoint>& contacts, double distance);

// Step 4: at most maxContacts: the deepest first, then repeatedly the one
// farthest from those already chosen (ties: deeper, then earlier). Distance
// counts the normals too, |dp|^2 + normalWeight^2 |dn|^2 (normalWeight: a
// length, the pair's size), so that a box in a concave corner keeps contacts
// on both walls, also where they meet.
void reduceContacts(std::vector<ContactPoint>& contacts, int maxContacts, double normalWeight);

// Face contacts of two convex polytopes (dConvex hulls, boxes) from one
// contact. ODE 0.16 collides convex geoms through libccd, which returns ONE
// point per pair (its penetration depth, normal and a point between the
// shapes): a rod lying on a convex piece of a magnet is held at one point
// only, so any torque that presses one end harder turns it about that point
// and the other end goes into the magnet (docs/rigid-bodies.md#convex-pieces).
// From that contact's normal the full set is clipped, as box-box colliders
// do: the reference face is the face of either polytope most aligned with
// the normal (within ~10 degrees, else the contact is an edge or a corner and
// is left as it is); the incident face is the other polytope's face most
// opposed to it; the incident face is clipped to the reference face's side
// planes (Sutherland-Hodgman) and its points behind the reference plane, or
// in front of it by at most `slack`, are the contacts: normal the reference
// face's, position halfway between the point and the reference plane, depth
// how far behind the plane. Returns false, leaving `out` alone, when there is
// no face contact or the clipped set is not credible (empty, or much deeper
// than libccd's depth).
struct PolytopeView {
    const ConvexHull* hull = nullptr; // in the geom frame
    Mat3 rotation = Mat3::Identity(); // geom frame -> world
    Vec3 position = Vec3::Zero();     // geom origin, world
};
bool clipFaceContacts(const PolytopeView& g1, const PolytopeView& g2, const ContactPoint& seed, double slack,
                      std::vector<ContactPoint>& out);

} // namespace mag::ode
