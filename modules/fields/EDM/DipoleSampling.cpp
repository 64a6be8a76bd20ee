#include "DipoleSampling.hpp"

#include <cmath>

namespace mag::edm {

DipoleTable singleDipole(double volume) {
    DipoleTable t;
    t.positions = {Vec3::Zero()};
    t.cellVolume = volume;
    t.n = 1;
    return t;
}

DipoleTable gridDipoles(const SurfaceMesh& mesh, double volume, int n) {
    if (n <= 1) return singleDipole(volume);
    const BoundingBox box = boundingBox(mesh);
    const Vec3 h = box.size() / n;
    DipoleTable t;
    t.n = n;
    // Cell centres inside the mesh (winding number > 1/2).
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            for (int k = 0; k < n; ++k) {
                const Vec3 c = box.lower + Vec3((i + 0.5) * h.x(), (j + 0.5) * h.y(), (k + 0.5) * h.z());
                if (windingNumber(mesh, c) > 0.5) t.positions.push_back(c);
            }
    // Nothing inside: the point-dipole model at the COM.
    if (t.positions.empty()) {
        t = singleDipole(volume);
        t.n = n;
        t.fallback = true;
        return t;
    }
    // Equal cells; rescaled so that the total moment is M * volume exactly.
    t.cellVolume = volume / static_cast<double>(t.positions.size());
    return t;
}

} // namespace mag::edm
