// The blocked SIMD part of the MBM field kernel (evaluate(), PolyhedronField.hpp) behind
// a plain-data interface, so that it can be compiled once per instruction set and
// chosen at run time (KernelPath.hpp):
//
//   PolyhedronBlocks.inc    the kernel body (SimdMath.hpp vectors, one lane per point)
//   PolyhedronBlocks.cpp    it with the build's flags (x86-64-v3 by default: AVX2, 4 lanes)
//   PolyhedronBlocksV4.cpp  it with -march=x86-64-v4 (AVX-512, 8 lanes), built on x86-64
//                           with GCC or Clang unless MAG_NATIVE (CMakeLists.txt)
//   KernelPath.cpp          picks one copy at first use
//
// Only plain doubles, ints and the structs below cross this interface: no Eigen type,
// no template and no inline function is shared by the copies, so code compiled for
// AVX-512 can never be linked in place of a function the rest of the program calls
// (see PolyhedronBlocks.inc). Internal to the MBM module and its tests.
#pragma once

#include <cstddef>

namespace mag::mbm::blocks {

/// An edge between two different faces (PolyEdge) with the per-call coefficients.
struct Edge {
    int v0, v1, face0, face1;
    double length;              ///< L
    double dx, dy, dz;          ///< r_v1 - r_v0
    double cx, cy, cz;          ///< B coefficient: B gets omega_e c (Eqs. 11, 13)
    double i0x, i0y, i0z;       ///< n_face0 x u_e
    double i1x, i1y, i1z;       ///< n_face1 x (-u_e)
    double cross2Min;           ///< |a x delta|^2 below this: within delta L of the line
    double smlMin;              ///< S - L at or below this (a . b >= 0): near a vertex
};

/// A planar face with the per-call coefficient d = M - n (n . M).
struct Face {
    double nx, ny, nz, dx, dy, dz;
    int vertex;            ///< a vertex of the face (h = (r_v - r) . n)
    int triBegin, triEnd;  ///< its triangles
};

/// A triangle of a face (PolyTriangle).
struct Triangle {
    int v0, v1, v2;
    double twiceArea;
};

/// One call's polyhedron: vertices as x, y, z triples (m, body frame).
struct Problem {
    const double* vertices;
    std::size_t nVertices;
    const Edge* edges;
    std::size_t nEdges;
    const Face* faces;
    std::size_t nFaces;
    const Triangle* triangles;
    std::size_t nTriangles;
    double vertexScale; ///< max_v |r_v|
};

/// The sums of one point before scaling (see evaluatePoint in PolyhedronField.cpp):
/// sum_e omega_e c + sum_p Omega_p d, S = sum_p W_p n_p (0 unless requested),
/// sum_p Omega_p; special: the point needs the scalar form (sums not set).
struct PointSums {
    double B[3];
    double S[3];
    double omegaTotal;
    bool special;
};

/// One compiled copy of the blocked kernel.
struct BlockKernel {
    const char* name; ///< "avx512", "avx2", "sse2" or "generic": what it was compiled for
    int width;        ///< points per block (SIMD lanes)
    /// Per-call tables (broadcast to every lane) for sums(), kept per thread.
    void (*prepare)(const Problem& problem);
    /// The sums at n points (x, y, z triples) of the problem last prepared on this
    /// thread. A point's sums do not depend on the other points of the call.
    void (*sums)(const double* points, std::size_t n, bool wantS, PointSums* out);
    /// The vector log, log1p and atan2 of SimdMath.hpp applied to n values (for the
    /// tests: every copy's own polynomials and reductions).
    void (*elementary)(const double* x, const double* q, const double* y, const double* z,
                       std::size_t n, double* logX, double* log1pQ, double* atan2YZ);
};

/// The copy with the build's flags.
namespace baseline {
const BlockKernel& kernel();
}

#if defined(MAG_MBM_KERNEL_V4)
/// The x86-64-v4 (AVX-512) copy; call only where the CPU has AVX-512 (KernelPath.cpp).
namespace x86_64_v4 {
const BlockKernel& kernel();
}
#endif

/// The copy evaluate() uses now (KernelPath.hpp: MAG_KERNEL at first use, or the one
/// set by setKernelPath()). Throws mag::InputError where MAG_KERNEL is invalid.
const BlockKernel& current();

} // namespace mag::mbm::blocks
