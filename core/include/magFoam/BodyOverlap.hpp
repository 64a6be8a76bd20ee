// Bodies whose meshes overlap in their current placement. A case that starts
// with two bodies inside each other is almost always a typo in
// constant/bodies.yaml; a contact solver then pushes them apart with whatever
// speed that takes (kinetic energy from nowhere), so magFoam reports it.
#pragma once

#include "magFoam/Body.hpp"

#include <limits>
#include <string>
#include <vector>

namespace mag {

struct BodyOverlap {
    std::size_t a, b;  // indices, a < b
    // Deepest vertex, face centroid or inner point of one body inside the
    // other (m; its distance to the other's surface); 0 when only edges cross faces.
    double depth;
};

// Pairs whose world meshes interpenetrate by more than tol = relTol * max(R_a,
// R_b) (bounding radii): a vertex, face centroid or inner point of one inside
// the other (winding number) and farther than tol from its surface, or an edge
// of one crossing a face of the other with both ends and the crossing point
// more than tol from the face's plane and edges. The inner point catches
// identical bodies at one place: the centre of mass, or where that lies in
// empty space (a ring, a washer, a paperclip, through which another body may
// pass untouched) a point of the material. Bodies that touch (a vertex on a
// face, faces flush) are not reported. Cost: vertices x triangles for each
// pair whose bounding spheres overlap; meant for the start of a run.
std::vector<BodyOverlap> findOverlaps(const std::vector<Body>& bodies, double relTol = 1e-6);

// Smallest distance between the surfaces of two bodies in their current
// placement: every vertex of each against every triangle of the other and
// every edge against every edge (exact for meshes apart). For bodies resting
// in each other, the nearest vertex's distance to the other surface
// (findOverlaps says how deep). Returns `cap` when the bounding spheres are
// farther apart than that; vertices and edges farther from the other's centre
// than its bounding radius + the best gap so far are skipped.
double surfaceGap(const Body& a, const Body& b, double cap = std::numeric_limits<double>::infinity());

// One warning per overlapping pair: "bodies 'a' and 'b' overlap (0.001 m deep, or
// edges through faces; <bodiesFile>): <consequence>; check their positions".
// Returns the count.
std::size_t warnOverlaps(const std::vector<Body>& bodies, const std::string& bodiesFile,
                         const std::string& consequence);

} // namespace mag
