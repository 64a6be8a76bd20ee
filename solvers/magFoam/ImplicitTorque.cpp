#include "ImplicitTorque.hpp"

#include <Eigen/Dense>

namespace mag::solver {

Mat3 tiltStiffness(const Body& body, const Wrench& wrench) {
    const double k = -wrench.bodyEnergy(); // m . B for an aligned moment
    if (!(k > 0)) return Mat3::Zero();
    const Vec3 m = body.magneticMoment();
    const double mm = m.squaredNorm();
    // Without a net moment (a compound whose parts cancel) every axis is taken
    // as stiff: the estimate errs towards damping, never towards instability.
    if (!(mm > 0)) return k * Mat3::Identity();
    return k * (Mat3::Identity() - m * m.transpose() / mm);
}

std::vector<Wrench> implicitTorques(const std::vector<Body>& bodies, const std::vector<Wrench>& wrenches,
                                    double dt) {
    std::vector<Wrench> out = wrenches;
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        const Body& b = bodies[i];
        if (b.fixed) continue;
        const Mat3 S = tiltStiffness(b, wrenches[i]);
        if (S.isZero(0.0)) continue;
        const Mat3 I = b.inertiaWorld();
        const Vec3 tau = wrenches[i].totalTorque();
        const Vec3 w = b.angularVelocity;
        const Vec3 wEnd = (I + dt * dt * S).ldlt().solve(I * w + dt * tau);
        out[i].mechanicalTorque += I * (wEnd - w) / dt - tau;
    }
    return out;
}

} // namespace mag::solver
