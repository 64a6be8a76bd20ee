// Face-by-face polyhedron field (see the header).
#include "MBMReference.hpp"

#include <stdexcept>
#include <string>

namespace mag::mbm::reference {

void evaluate(const PolyhedronTables& tables, const Vec3& M, std::span<const Vec3> points,
              const FieldOutputs& out) {
    const std::size_t nP = points.size();
    for (const std::size_t n : {out.B.size(), out.A.size(), out.insideFraction.size(),
                                out.scalarPotential.size(), out.S.size()})
        if (n != 0 && n != nP)
            throw std::invalid_argument(
                "mbm::reference::evaluate: every output must be empty or as long as points");
    const double k = mu0 / (4.0 * std::numbers::pi);
    const int nFaces = static_cast<int>(tables.faces().size());
    for (std::size_t i = 0; i < nP; ++i) {
        const Vec3& r = points[i];
        const double tolerance = planeTolerance(tables, r);
        Vec3 B = Vec3::Zero(), S = Vec3::Zero();
        double omega = 0.0;
        for (int p = 0; p < nFaces; ++p) {
            const Vec3& n = tables.faces()[static_cast<std::size_t>(p)].normal;
            const FaceIntegrals fi = faceIntegrals(tables, p, r, tolerance);
            B += fi.gradW.cross(M.cross(n)); // Eq. 11
            S += fi.W * n;                   // Eq. 9
            omega += fi.solidAngle;          // Eq. 15
        }
        if (!out.B.empty()) out.B[i] = k * B;
        if (!out.A.empty()) out.A[i] = k * M.cross(S);
        if (!out.insideFraction.empty()) out.insideFraction[i] = omega / (4.0 * std::numbers::pi);
        if (!out.scalarPotential.empty()) out.scalarPotential[i] = M.dot(S) / (4.0 * std::numbers::pi);
        if (!out.S.empty()) out.S[i] = S;
    }
}

} // namespace mag::mbm::reference
