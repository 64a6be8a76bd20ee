// Builds the per-mesh tables of the Magnetic Boundary Method (see the header).
#include "PolyhedronTables.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <stdexcept>
#include <string>
#include <unordered_map>

namespace mag::mbm {

namespace {

// Key of a directed edge a -> b.
std::uint64_t edgeKey(int a, int b) {
    return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) |
           static_cast<std::uint32_t>(b);
}

[[noreturn]] void fail(const std::string& what) {
    throw std::invalid_argument("PolyhedronTables: " + what);
}

// Unit normal and twice the area of each triangle; a zero-area triangle has no
// normal, so it is an error. File-local, so that it is inlined into the
// constructor: this file is compiled with FMA contraction, and an out-of-line
// copy fuses the cross products differently (other last bits in the tables).
void measureTriangles(const std::vector<Vec3>& vertices, const std::vector<std::array<int, 3>>& tris,
                      std::vector<Vec3>& triNormal, std::vector<double>& triTwiceArea) {
    const int nT = static_cast<int>(tris.size());
    triNormal.resize(static_cast<std::size_t>(nT));
    triTwiceArea.resize(static_cast<std::size_t>(nT));
    for (int t = 0; t < nT; ++t) {
        const auto& v = tris[static_cast<std::size_t>(t)];
        const Vec3 e1 = vertices[v[1]] - vertices[v[0]];
        const Vec3 e2 = vertices[v[2]] - vertices[v[0]];
        const Vec3 c = e1.cross(e2);
        const double twiceArea = c.norm();
        const double longest2 =
            std::max({e1.squaredNorm(), e2.squaredNorm(), (e2 - e1).squaredNorm()});
        // sine of the largest angle below 1e-14: numerically collinear
        if (!(twiceArea > 1e-14 * longest2)) {
            std::ostringstream s;
            s << "triangle " << t << " is degenerate (zero area)";
            fail(s.str());
        }
        triNormal[static_cast<std::size_t>(t)] = c / twiceArea;
        triTwiceArea[static_cast<std::size_t>(t)] = twiceArea;
    }
}

} // namespace

// Per-triangle data that one step produces and later ones read; dropped once
// the tables are built.
struct PolyhedronTables::Build {
    std::vector<std::array<int, 3>> tris; // triangles in compacted vertex indices
    std::vector<Vec3> triNormal;          // unit normal per triangle
    std::vector<double> triTwiceArea;     // |(r1 - r0) x (r2 - r0)| per triangle
    std::vector<int> neighbour;           // 3 t + k -> triangle across edge k of t
    std::vector<int> triFace;             // triangle -> planar face
    std::vector<int> order;               // triangles face by face (face-major)
    std::vector<int> faceStart;           // face f holds order[faceStart[f], faceStart[f + 1])
    int nT() const { return static_cast<int>(tris.size()); }
};

PolyhedronTables::PolyhedronTables(const std::vector<Vec3>& vertices,
                                   const std::vector<std::array<int, 3>>& triangles,
                                   double coplanarTolerance) {
    static std::atomic<std::uint64_t> nextId{1};
    id_ = nextId.fetch_add(1, std::memory_order_relaxed);
    if (triangles.empty()) fail("the mesh has no triangles");

    // The order of the checks fixes which error an unusable mesh reports.
    Build b;
    compactVertices(vertices, triangles, b);
    measureTriangles(vertices_, b.tris, b.triNormal, b.triTwiceArea);
    matchNeighbours(b);
    volumeAndCentroid(b);
    mergeCoplanar(b, coplanarTolerance);
    buildFaces(b);
    buildEdges(b);
    buildLoops();
    bounds();
}

// Checks indices and compacts the vertices: only used ones are kept, in input
// order, so an unused (even non-finite) vertex cannot disturb the tables.
void PolyhedronTables::compactVertices(const std::vector<Vec3>& vertices,
                                       const std::vector<std::array<int, 3>>& triangles, Build& b) {
    const int nIn = static_cast<int>(vertices.size());
    std::vector<int> compact(static_cast<std::size_t>(nIn), -1);
    for (std::size_t t = 0; t < triangles.size(); ++t) {
        const auto& tri = triangles[t];
        for (int k = 0; k < 3; ++k) {
            if (tri[k] < 0 || tri[k] >= nIn) {
                std::ostringstream s;
                s << "triangle " << t << " has vertex index " << tri[k] << " outside [0, "
                  << nIn << ")";
                fail(s.str());
            }
        }
        if (tri[0] == tri[1] || tri[1] == tri[2] || tri[2] == tri[0]) {
            std::ostringstream s;
            s << "triangle " << t << " repeats a vertex (" << tri[0] << ", " << tri[1] << ", "
              << tri[2] << ")";
            fail(s.str());
        }
    }
    {
        std::vector<char> used(static_cast<std::size_t>(nIn), 0);
        for (const auto& tri : triangles)
            for (int k = 0; k < 3; ++k) used[static_cast<std::size_t>(tri[k])] = 1;
        for (int v = 0; v < nIn; ++v) {
            if (!used[static_cast<std::size_t>(v)]) continue;
            if (!vertices[static_cast<std::size_t>(v)].allFinite()) {
                std::ostringstream s;
                s << "vertex " << v << " is not finite";
                fail(s.str());
            }
            compact[static_cast<std::size_t>(v)] = static_cast<int>(vertices_.size());
            vertices_.push_back(vertices[static_cast<std::size_t>(v)]);
            inputVertex_.push_back(v);
        }
    }
    const int nT = static_cast<int>(triangles.size());
    b.tris.resize(static_cast<std::size_t>(nT));
    for (int t = 0; t < nT; ++t)
        for (int k = 0; k < 3; ++k)
            b.tris[static_cast<std::size_t>(t)][k] =
                compact[static_cast<std::size_t>(triangles[static_cast<std::size_t>(t)][k])];
}

// Directed half-edges: each must appear once and its reverse exactly once
// (closed, manifold, consistently oriented); the reverse names the neighbour.
void PolyhedronTables::matchNeighbours(Build& b) const {
    const int nT = b.nT();
    const auto& tris = b.tris;
    std::unordered_map<std::uint64_t, int> halfEdge; // key -> 3 t + k
    halfEdge.reserve(static_cast<std::size_t>(3 * nT) * 2);
    auto inputIndex = [&](int v) { return inputVertex_[static_cast<std::size_t>(v)]; };
    for (int t = 0; t < nT; ++t)
        for (int k = 0; k < 3; ++k) {
            const int a = tris[static_cast<std::size_t>(t)][k];
            const int c = tris[static_cast<std::size_t>(t)][(k + 1) % 3];
            const auto [it, inserted] = halfEdge.emplace(edgeKey(a, c), 3 * t + k);
            if (!inserted) {
                std::ostringstream s;
                s << "edge (" << inputIndex(a) << ", " << inputIndex(c)
                  << ") is used in the same direction by triangles " << it->second / 3
                  << " and " << t
                  << ": the mesh is non-manifold or inconsistently oriented";
                fail(s.str());
            }
        }
    b.neighbour.assign(static_cast<std::size_t>(3 * nT), -1);
    for (int t = 0; t < nT; ++t)
        for (int k = 0; k < 3; ++k) {
            const int a = tris[static_cast<std::size_t>(t)][k];
            const int c = tris[static_cast<std::size_t>(t)][(k + 1) % 3];
            const auto it = halfEdge.find(edgeKey(c, a));
            if (it == halfEdge.end()) {
                std::ostringstream s;
                s << "edge (" << inputIndex(a) << ", " << inputIndex(c) << ") of triangle " << t
                  << " has no opposite triangle: the mesh is open (or the neighbour is "
                     "oriented the same way)";
                fail(s.str());
            }
            b.neighbour[static_cast<std::size_t>(3 * t + k)] = it->second / 3;
        }
}

// Volume and centroid by the divergence theorem, origin at a vertex for
// precision; a non-positive volume means the triangles face inwards.
void PolyhedronTables::volumeAndCentroid(const Build& b) {
    const Vec3 o = vertices_[0];
    double sixV = 0.0;
    Vec3 m = Vec3::Zero();
    for (const auto& v : b.tris) {
        const Vec3 a = vertices_[v[0]] - o, bb = vertices_[v[1]] - o, c = vertices_[v[2]] - o;
        const double d = a.dot(bb.cross(c));
        sixV += d;
        m += d * (a + bb + c);
    }
    volume_ = sixV / 6.0;
    if (!(volume_ > 0.0)) {
        std::ostringstream s;
        s << "the enclosed volume is " << volume_
          << " m^3 (not positive): the triangles are oriented inwards";
        fail(s.str());
    }
    centroid_ = o + m / (4.0 * sixV);
}

// Merges coplanar neighbours into faces by region growing: a triangle joins when
// its normal is within the tolerance of the SEED's normal (no drift along curved
// parts). The edges inside a face cancel exactly and are never stored.
void PolyhedronTables::mergeCoplanar(Build& b, double coplanarTolerance) {
    const int nT = b.nT();
    b.triFace.assign(static_cast<std::size_t>(nT), -1);
    b.order.reserve(static_cast<std::size_t>(nT));
    std::vector<int> stack;
    for (int seed = 0; seed < nT; ++seed) {
        if (b.triFace[static_cast<std::size_t>(seed)] >= 0) continue;
        const int f = static_cast<int>(b.faceStart.size());
        b.faceStart.push_back(static_cast<int>(b.order.size()));
        const Vec3 nSeed = b.triNormal[static_cast<std::size_t>(seed)];
        b.triFace[static_cast<std::size_t>(seed)] = f;
        stack.assign(1, seed);
        while (!stack.empty()) {
            const int t = stack.back();
            stack.pop_back();
            b.order.push_back(t);
            for (int k = 0; k < 3; ++k) {
                const int u = b.neighbour[static_cast<std::size_t>(3 * t + k)];
                if (b.triFace[static_cast<std::size_t>(u)] >= 0) continue;
                const Vec3& nu = b.triNormal[static_cast<std::size_t>(u)];
                if (nu.dot(nSeed) > 0.0 && nu.cross(nSeed).norm() <= coplanarTolerance) {
                    b.triFace[static_cast<std::size_t>(u)] = f;
                    stack.push_back(u);
                }
            }
        }
    }
    b.faceStart.push_back(nT);
}

// Faces: normal (area-weighted), area, centroid, plane offset; the triangles
// stored face-major so a face's solid angle sums one contiguous range.
void PolyhedronTables::buildFaces(const Build& b) {
    const int nF = static_cast<int>(b.faceStart.size()) - 1;
    faces_.resize(static_cast<std::size_t>(nF));
    triangles_.reserve(b.tris.size());
    for (int f = 0; f < nF; ++f) {
        PolyFace& face = faces_[static_cast<std::size_t>(f)];
        face.triBegin = b.faceStart[static_cast<std::size_t>(f)];
        face.triEnd = b.faceStart[static_cast<std::size_t>(f + 1)];
        Vec3 n = Vec3::Zero(), c = Vec3::Zero();
        double twiceArea = 0.0;
        for (int i = face.triBegin; i < face.triEnd; ++i) {
            const int t = b.order[static_cast<std::size_t>(i)];
            const auto& v = b.tris[static_cast<std::size_t>(t)];
            const double w = b.triTwiceArea[static_cast<std::size_t>(t)];
            n += w * b.triNormal[static_cast<std::size_t>(t)];
            c += w * (vertices_[v[0]] + vertices_[v[1]] + vertices_[v[2]]) / 3.0;
            twiceArea += w;
            triangles_.push_back({v, w, f});
        }
        face.normal = n.normalized();
        face.area = 0.5 * twiceArea;
        face.centroid = c / twiceArea;
        face.offset = face.normal.dot(vertices_[triangles_[static_cast<std::size_t>(face.triBegin)].v[0]]);
    }
}

// Edges between different faces, each stored once with both faces (edge-major:
// omega_e is then computed once per edge and point), and each face's boundary
// edges with their inward directions.
void PolyhedronTables::buildEdges(const Build& b) {
    const int nF = static_cast<int>(faces_.size());
    std::unordered_map<std::uint64_t, int> edgeIndex; // undirected key -> edge
    edgeIndex.reserve(b.tris.size() * 3);
    for (int f = 0; f < nF; ++f) {
        PolyFace& face = faces_[static_cast<std::size_t>(f)];
        face.edgeBegin = static_cast<int>(faceEdges_.size());
        for (int i = face.triBegin; i < face.triEnd; ++i) {
            const int t = b.order[static_cast<std::size_t>(i)];
            for (int k = 0; k < 3; ++k) {
                const int g = b.triFace[static_cast<std::size_t>(
                    b.neighbour[static_cast<std::size_t>(3 * t + k)])];
                if (g == f) continue; // interior edge of a planar face: cancels exactly
                const int a = b.tris[static_cast<std::size_t>(t)][k];
                const int c = b.tris[static_cast<std::size_t>(t)][(k + 1) % 3];
                const auto key = edgeKey(std::min(a, c), std::max(a, c));
                const auto it = edgeIndex.find(key);
                FaceEdge fe;
                if (it == edgeIndex.end()) {
                    // first seen from this face: a -> c is CCW about this face
                    PolyEdge e;
                    e.v0 = a;
                    e.v1 = c;
                    e.face0 = f;
                    e.face1 = g;
                    e.delta = vertices_[c] - vertices_[a];
                    e.length = e.delta.norm();
                    e.inward0 = face.normal.cross(e.delta / e.length);
                    fe.edge = static_cast<int>(edges_.size());
                    fe.reversed = false;
                    fe.inward = e.inward0;
                    edgeIndex.emplace(key, fe.edge);
                    edges_.push_back(e);
                } else {
                    // seen before from the other face, which traversed it c -> a
                    PolyEdge& e = edges_[static_cast<std::size_t>(it->second)];
                    e.inward1 = face.normal.cross(-e.delta / e.length);
                    fe.edge = it->second;
                    fe.reversed = true;
                    fe.inward = e.inward1;
                }
                faceEdges_.push_back(fe);
            }
        }
        face.edgeEnd = static_cast<int>(faceEdges_.size());
    }
}

// Boundary loops of each face (a face may be holed or have several loops):
// chains its directed boundary edges into vertex cycles.
void PolyhedronTables::buildLoops() {
    for (auto& face : faces_) {
        std::vector<std::pair<int, int>> directed; // (from, to)
        for (int i = face.edgeBegin; i < face.edgeEnd; ++i) {
            const FaceEdge& fe = faceEdges_[static_cast<std::size_t>(i)];
            const PolyEdge& e = edges_[static_cast<std::size_t>(fe.edge)];
            directed.emplace_back(fe.reversed ? e.v1 : e.v0, fe.reversed ? e.v0 : e.v1);
        }
        std::vector<char> done(directed.size(), 0);
        for (std::size_t s = 0; s < directed.size(); ++s) {
            if (done[s]) continue;
            std::vector<int> loop;
            std::size_t cur = s;
            while (!done[cur]) {
                done[cur] = 1;
                loop.push_back(directed[cur].first);
                const int next = directed[cur].second;
                std::size_t found = cur;
                for (std::size_t j = 0; j < directed.size(); ++j)
                    if (!done[j] && directed[j].first == next) {
                        found = j;
                        break;
                    }
                cur = found;
            }
            face.loops.push_back(std::move(loop));
        }
    }
}

// Size scales of the mesh: farthest vertex from the centroid, longest edge.
void PolyhedronTables::bounds() {
    for (const auto& v : vertices_)
        boundingRadius_ = std::max(boundingRadius_, (v - centroid_).norm());
    for (const auto& e : edges_) maxEdgeLength_ = std::max(maxEdgeLength_, e.length);
}

} // namespace mag::mbm
