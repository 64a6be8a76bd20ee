#include "DemagTensor.hpp"

#include <cmath>
#include <numbers>

#include "SurfaceQuadrature.hpp" // mbm::gaussLegendre

namespace mag::demag {

namespace {
// Gauss-Legendre on [0, 1], from the MBM kernel's rule on [-1, 1].
void gaussLegendre01(int n, std::vector<double>& x, std::vector<double>& w) {
    mbm::gaussLegendre(n, x, w);
    for (int i = 0; i < n; ++i) x[i] = 0.5 * (1 + x[i]), w[i] *= 0.5;
}

// Fully symmetric rules on a triangle (Strang-Fix degree 2, Dunavant degree 4,
// Radon degree 5): barycentric points, weights summing to 1.
struct SymmetricPoint {
    Vec3 bary;
    double weight;
};
std::vector<SymmetricPoint> symmetricRule(int points) {
    std::vector<SymmetricPoint> r;
    auto orbit = [&](double a, double w) { // (a, b, b) and its permutations
        const double b = (1 - a) / 2;
        r.push_back({Vec3(a, b, b), w}), r.push_back({Vec3(b, a, b), w}), r.push_back({Vec3(b, b, a), w});
    };
    if (points == 3) orbit(2.0 / 3, 1.0 / 3);
    if (points == 6) orbit(0.108103018168070, 0.223381589678011), orbit(0.816847572980459, 0.109951743655322);
    if (points == 7) {
        r.push_back({Vec3::Constant(1.0 / 3), 0.225});
        orbit(0.059715871789770, 0.132394152788506), orbit(0.797426985353087, 0.125939180544827);
    }
    return r;
}
} // namespace

int tensorRulePoints(int order) { return order <= 0 ? -order : 3 * order * order; }

SurfaceRule tensorRule(const SurfaceMesh& mesh, int order) {
    SurfaceRule rule;
    if (order <= 0) { // a symmetric rule of -order points
        const auto pts = symmetricRule(-order);
        for (const auto& t : mesh.triangles) {
            const Vec3 a = mesh.vertices[t[0]], b = mesh.vertices[t[1]], c = mesh.vertices[t[2]];
            const Vec3 twiceArea = (b - a).cross(c - a);
            for (const auto& p : pts) {
                rule.points.push_back(p.bary[0] * a + p.bary[1] * b + p.bary[2] * c);
                rule.weightedNormals.push_back(0.5 * p.weight * twiceArea);
            }
        }
        return rule;
    }
    // The centroid fan: three pieces (centroid, edge), each the Duffy square
    // x = c + t ((1 - s) P + s Q - c), dA = t |(Q - P) x (P - c)| ds dt, the
    // collapse at the centroid (where the integrand is smooth) and the edge at
    // t = 1. A's gradient is log-singular on the edge and worst at its ends, so
    // t is graded toward 1 (t = 1 - (1 - tau)^g) and, from order 10 on, s
    // toward both ends (s = u^2 / (u^2 + (1 - u)^2)); the weights of each piece
    // are scaled to its exact area (constants exact; with the symmetry, linear
    // functions too).
    std::vector<double> x, w;
    gaussLegendre01(order, x, w);
    const double g = order >= 10 ? 3 : 2;
    const bool gradeS = order >= 10;
    std::vector<double> tx(order), tw(order), sx(order), sw(order);
    for (int i = 0; i < order; ++i) {
        tx[i] = 1 - std::pow(1 - x[i], g), tw[i] = w[i] * g * std::pow(1 - x[i], g - 1);
        if (gradeS) {
            const double u = x[i], d = u * u + (1 - u) * (1 - u);
            sx[i] = u * u / d, sw[i] = w[i] * 2 * u * (1 - u) / (d * d);
        } else {
            sx[i] = x[i], sw[i] = w[i];
        }
    }
    double unit = 0; // the Duffy piece's rule applied to 1, exact 1/2
    for (int k = 0; k < order; ++k)
        for (int l = 0; l < order; ++l) unit += sw[k] * tw[l] * tx[l];
    for (const auto& t : mesh.triangles) {
        const Vec3 p[3] = {mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]};
        const Vec3 c = (p[0] + p[1] + p[2]) / 3;
        const Vec3 pieceNormal = (p[1] - p[0]).cross(p[2] - p[0]) / 6 / unit; // (A / 3) n / unit
        for (int e = 0; e < 3; ++e) {
            const Vec3 P = p[e], Q = p[(e + 1) % 3];
            for (int k = 0; k < order; ++k)
                for (int l = 0; l < order; ++l) {
                    rule.points.push_back(c + tx[l] * ((1 - sx[k]) * P + sx[k] * Q - c));
                    rule.weightedNormals.push_back(sw[k] * tw[l] * tx[l] * pieceNormal);
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

Mat3 demagTensor(const std::shared_ptr<const Shape>& shape, const FieldEvaluator& mbm, int order) {
    const SurfaceRule rule = tensorRule(shape->mesh, order);
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
