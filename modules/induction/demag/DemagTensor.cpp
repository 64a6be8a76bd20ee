#include "DemagTensor.hpp"

#include <cmath>
#include <numbers>

namespace mag::demag {

namespace {
// Gauss-Legendre on [0, 1] (Newton on the Legendre recurrence).
void gaussLegendre(int n, std::vector<double>& x, std::vector<double>& w) {
    x.resize(n), w.resize(n);
    for (int i = 0; i < n; ++i) {
        double z = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5)), dp = 1;
        for (int it = 0; it < 100; ++it) {
            double p1 = 1, p2 = 0;
            for (int j = 0; j < n; ++j) {
                const double p3 = p2;
                p2 = p1;
                p1 = ((2 * j + 1) * z * p2 - j * p3) / (j + 1);
            }
            dp = n * (z * p1 - p2) / (z * z - 1);
            const double step = p1 / dp;
            z -= step;
            if (std::abs(step) < 1e-16) break;
        }
        x[i] = 0.5 * (1 - z);
        w[i] = 1.0 / ((1 - z * z) * dp * dp);
    }
}
} // namespace

SurfaceRule surfaceRule(const SurfaceMesh& mesh, int n, int split) {
    std::vector<double> x, w;
    gaussLegendre(n, x, w);
    SurfaceRule rule;
    const double h = 1.0 / split;
    for (const auto& t : mesh.triangles) {
        const Vec3 a = mesh.vertices[t[0]], b = mesh.vertices[t[1]], c = mesh.vertices[t[2]];
        const Vec3 twiceArea = (b - a).cross(c - a); // 2 A n
        auto at = [&](double u, double v) { return a + u * (b - a) + v * (c - a); };
        // split^2 sub-triangles: split (split + 1)/2 upright, the rest inverted.
        for (int i = 0; i < split; ++i)
            for (int j = 0; i + j < split; ++j)
                for (int inverted = 0; inverted < 2; ++inverted) {
                    if (inverted && i + j >= split - 1) continue;
                    const Vec3 p0 = inverted ? at((i + 1) * h, j * h) : at(i * h, j * h);
                    const Vec3 p1 = inverted ? at((i + 1) * h, (j + 1) * h) : at((i + 1) * h, j * h);
                    const Vec3 p2 = inverted ? at(i * h, (j + 1) * h) : at(i * h, (j + 1) * h);
                    // Collapsed square: u = x_k, v = x_l (1 - x_k), dA = 2 A h^2 (1 - x_k) du dv.
                    for (int k = 0; k < n; ++k)
                        for (int l = 0; l < n; ++l) {
                            const double u = x[k], v = x[l] * (1 - x[k]);
                            rule.points.push_back(p0 + u * (p1 - p0) + v * (p2 - p0));
                            rule.weightedNormals.push_back(w[k] * w[l] * (1 - x[k]) * h * h * twiceArea);
                        }
                }
    }
    return rule;
}

Vec3 volumeAverage(const std::vector<Vec3>& weightedNormals, const std::vector<Vec3>& A, double volume) {
    Vec3 sum = Vec3::Zero();
    for (std::size_t q = 0; q < A.size(); ++q) sum += weightedNormals[q].cross(A[q]);
    return sum / volume;
}

Mat3 demagTensor(const std::shared_ptr<const Shape>& shape, const FieldEvaluator& mbm, int n, int split) {
    const SurfaceRule rule = surfaceRule(shape->mesh, n, split);
    Body body;
    body.name = "demagnetization tensor";
    body.shape = shape;
    std::vector<Vec3> B(rule.points.size()), A(rule.points.size());
    Mat3 N;
    for (int k = 0; k < 3; ++k) {
        body.magnetizationBody = Vec3::Unit(k);
        mbm.evaluate(body, rule.points, B, A);
        N.col(k) = Vec3::Unit(k) - volumeAverage(rule.weightedNormals, A, shape->volume) / mu0;
    }
    return 0.5 * (N + N.transpose()); // symmetric exactly; the rule's asymmetry is below its error
}

} // namespace mag::demag
