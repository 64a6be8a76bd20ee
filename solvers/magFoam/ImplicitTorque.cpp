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

std::vector<Mat3> tiltStiffnesses(const std::vector<Body>& bodies, const std::vector<Wrench>& wrenches) {
    std::vector<Mat3> out(bodies.size(), Mat3::Zero());
    for (std::size_t i = 0; i < bodies.size(); ++i)
        if (!bodies[i].fixed) out[i] = tiltStiffness(bodies[i], wrenches[i]);
    return out;
}

} // namespace mag::solver
