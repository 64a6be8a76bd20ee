// Immutable per-mesh tables for the Magnetic Boundary Method (paper Sec. 4.1, 5).
//
// Built ONCE from a closed, outward-oriented triangle mesh and shared by every body
// that uses the mesh; the field kernel (PolyhedronField) and the boundary quadrature
// (SurfaceQuadrature) only read them.
//
// What the tables hold:
//   - faces: coplanar neighbouring triangles merged into planar polygons (a box's 12
//     triangles become 6 squares). The edge shared by two coplanar triangles cancels
//     exactly in Eqs. 12-13 (same n_p, opposite u_e, same omega_e) and is dropped; the
//     solid angles of a face's triangles are summed (Eq. 15).
//   - per face: outward unit normal n_p, plane offset n_p . r, area, its triangles
//     (contiguous), its boundary edges with n_p x u_e (u_e counter-clockwise about
//     n_p, pointing into the face), and its boundary loops (vertex cycles, CCW).
//   - edges: only the edges between two DIFFERENT faces, each stored once with both
//     faces (edge-major layout), so omega_e (Eq. 14) is computed once per edge per
//     point (Sec. 5).
//
// Conventions:
//   - vertices are compacted: only vertices used by a triangle are kept, in order of
//     first appearance in the input vertex array (the index map is kept).
//   - edge e runs v0 -> v1; that direction is counter-clockwise about face0's normal,
//     and face1 traverses it v1 -> v0.
//   - errors (open, non-manifold, inconsistently or inward oriented, degenerate or
//     out-of-range triangles, non-finite vertices) throw std::invalid_argument with
//     the offending element named.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace mag::mbm {

using Vec3 = Eigen::Vector3d;

/// An edge between two different planar faces (Eqs. 12-14).
struct PolyEdge {
    int v0 = -1, v1 = -1;        ///< compacted vertex indices; v0 -> v1 is CCW about face0
    int face0 = -1, face1 = -1;  ///< adjacent faces (face1 traverses v1 -> v0)
    double length = 0.0;         ///< L = |r_v1 - r_v0|
    Vec3 delta = Vec3::Zero();   ///< r_v1 - r_v0
    Vec3 inward0 = Vec3::Zero(); ///< n_face0 x u_e (unit, in face0's plane, into face0)
    Vec3 inward1 = Vec3::Zero(); ///< n_face1 x (-u_e) (unit, into face1)
};

/// One boundary edge of a face, as seen from that face.
struct FaceEdge {
    int edge = -1;              ///< index into PolyhedronTables::edges()
    bool reversed = false;      ///< true where this face traverses the edge v1 -> v0
    Vec3 inward = Vec3::Zero(); ///< n_p x u_e, u_e CCW about n_p (Eq. 13)
};

/// A triangle of the input mesh, grouped by face.
struct PolyTriangle {
    std::array<int, 3> v{-1, -1, -1}; ///< compacted vertex indices, CCW about n_p
    double twiceArea = 0.0;           ///< |(r1 - r0) x (r2 - r0)|
    int face = -1;                    ///< the planar face it belongs to
};

/// A planar polygon (one or more coplanar triangles), possibly non-convex or holed.
struct PolyFace {
    Vec3 normal = Vec3::Zero();   ///< outward unit normal n_p
    double offset = 0.0;          ///< n_p . r_v for a vertex r_v of the face (plane offset)
    double area = 0.0;            ///< m^2
    Vec3 centroid = Vec3::Zero(); ///< area centroid
    int triBegin = 0, triEnd = 0; ///< range in PolyhedronTables::triangles()
    int edgeBegin = 0, edgeEnd = 0; ///< range in PolyhedronTables::faceEdges()
    std::vector<std::vector<int>> loops; ///< boundary loops (compacted vertices, CCW)
};

/// Immutable tables of a closed, outward-oriented polyhedron (see the file comment).
class PolyhedronTables {
public:
    /// Builds the tables. vertices in m; triangles CCW about the outward normal.
    /// coplanarTolerance: neighbouring triangles whose unit normals differ by less than
    /// this (|n_a x n_seed| with n_a . n_seed > 0, i.e. the angle in radians) are merged
    /// into one planar face. Throws std::invalid_argument for unusable meshes.
    PolyhedronTables(const std::vector<Vec3>& vertices,
                     const std::vector<std::array<int, 3>>& triangles,
                     double coplanarTolerance = 1e-10);

    const std::vector<Vec3>& vertices() const { return vertices_; }
    const std::vector<PolyEdge>& edges() const { return edges_; }
    const std::vector<PolyFace>& faces() const { return faces_; }
    const std::vector<FaceEdge>& faceEdges() const { return faceEdges_; }
    const std::vector<PolyTriangle>& triangles() const { return triangles_; }
    /// Boundary edges of one face.
    std::span<const FaceEdge> edgesOf(int face) const {
        const PolyFace& f = faces_[static_cast<std::size_t>(face)];
        return {faceEdges_.data() + f.edgeBegin, static_cast<std::size_t>(f.edgeEnd - f.edgeBegin)};
    }
    /// Input vertex index of each compacted vertex.
    const std::vector<int>& inputVertex() const { return inputVertex_; }

    double volume() const { return volume_; }          ///< m^3 (> 0)
    const Vec3& centroid() const { return centroid_; } ///< volume centroid (m)
    double boundingRadius() const { return boundingRadius_; } ///< max |r_v - centroid|
    double maxEdgeLength() const { return maxEdgeLength_; }   ///< over edges() (m)
    /// Distinct for tables built by different constructor calls; a copy keeps it (same
    /// contents). evaluate() reuses its per-call tables while the id, M and kernel repeat.
    std::uint64_t id() const { return id_; }

private:
    // The constructor's steps, in order (the triangle normals and areas, after
    // compactVertices, are measured by a file-local function); each checks what
    // it needs and throws std::invalid_argument naming the offending element.
    struct Build; // per-triangle scratch passed between the steps (PolyhedronTables.cpp)
    void compactVertices(const std::vector<Vec3>& vertices,
                         const std::vector<std::array<int, 3>>& triangles, Build& b);
    void matchNeighbours(Build& b) const;
    void volumeAndCentroid(const Build& b);
    static void mergeCoplanar(Build& b, double coplanarTolerance);
    void buildFaces(const Build& b);
    void buildEdges(const Build& b);
    void buildLoops();
    void bounds();

    std::vector<Vec3> vertices_;
    std::vector<int> inputVertex_;
    std::vector<PolyEdge> edges_;
    std::vector<PolyFace> faces_;
    std::vector<FaceEdge> faceEdges_;
    std::vector<PolyTriangle> triangles_;
    double volume_ = 0.0;
    Vec3 centroid_ = Vec3::Zero();
    double boundingRadius_ = 0.0;
    double maxEdgeLength_ = 0.0;
    std::uint64_t id_ = 0;
};

} // namespace mag::mbm
