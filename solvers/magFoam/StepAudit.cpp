#include "StepAudit.hpp"

#include <magFoam/Log.hpp>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <limits>

namespace mag::solver {

namespace {

constexpr int kQuietSteps = 100;       // a condition clear this long ends its episode
constexpr double kRestSpeed = 1e-3;    // m/s: at rest below (surface speed too)
// The adaptive step aims at half the travel the audit warns at: at the full
// travel, a 6 mm cube spinning up in free fall gained 6 % of its kinetic energy
// (dropMagnet tutorial), at half 3e-4 of the peak.
constexpr double kProposalTravel = 0.5;
constexpr double kStepsPerPeriod = 20; // safe step: this many per magnetic oscillation

double angleBetween(const Quat& a, const Quat& b) {
    const double c = std::min(1.0, std::abs(a.dot(b)));
    return 2.0 * std::acos(c);
}

// stableDeltaT for one body (see the header).
double bodyStableDeltaT(const Body& b, double size, double radius, double smallestInertia, const Wrench& w,
                        double travel, bool implicitTilt = false) {
    double dt = std::numeric_limits<double>::infinity();
    // Travel of the centre and of the surface in a step: v dt + a dt^2 <= travel size
    // (the backends' semi-implicit Euler moves by the new velocity, v + a dt).
    auto within = [&](double v, double a) {
        const double d = travel * size;
        if (a > 0) return 2.0 * d / (v + std::sqrt(v * v + 4.0 * a * d));
        return v > 0 ? d / v : std::numeric_limits<double>::infinity();
    };
    dt = std::min(within(b.velocity.norm(), w.force.norm() / b.mass()),
                  within(b.angularVelocity.norm() * radius,
                         smallestInertia > 0 ? w.totalTorque().norm() / smallestInertia * radius : 0.0));
    double omega2 = w.force.norm() / (b.mass() * size);
    if (smallestInertia > 0 && !implicitTilt) omega2 = std::max(omega2, std::abs(w.bodyEnergy()) / smallestInertia);
    if (omega2 > 0) dt = std::min(dt, 2.0 * std::acos(-1.0) / std::sqrt(omega2) / kStepsPerPeriod);
    return dt;
}

std::string seconds(double dt) { return std::isfinite(dt) ? fmt::format("{:.2g} s", dt) : "unknown"; }

} // namespace

StepAudit::StepAudit(const std::vector<Body>& bodies, const AuditSettings& settings, double fieldTolerance,
                     const Vec3& gravity)
    : settings_(settings), tolerance_(fieldTolerance), gravity_(gravity), tracks_(bodies.size()) {
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        const SurfaceMesh& m = bodies[i].shape->mesh;
        Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
        for (const Vec3& v : m.vertices) {
            lo = lo.cwiseMin(v);
            hi = hi.cwiseMax(v);
        }
        tracks_[i].size = m.vertices.empty() ? 0.0 : (hi - lo).minCoeff();
        tracks_[i].radius = bodies[i].shape->boundingRadius;
        tracks_[i].smallestInertia = Eigen::SelfAdjointEigenSolver<Mat3>(bodies[i].inertiaBody()).eigenvalues().minCoeff();
    }
}

std::optional<std::string> StepAudit::check(long step, double t, double dt, const std::vector<BodyState>& before,
                                            const std::vector<Body>& bodies, const std::vector<Wrench>& wrenches,
                                            double magnetic) {
    std::optional<std::string> stop;
    auto report = [&](const std::string& message) {
        ++warnings_;
        if (settings_.strict) {
            if (!stop) stop = message;
        } else {
            spdlog::warn("{}", message);
        }
    };

    // Energy at the start of the step (the wrenches' pair energies belong there).
    double kin = 0, grav = 0, mag = 0;
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        kin += kineticEnergy(bodies[i], before[i]);
        if (!bodies[i].fixed) grav -= bodies[i].mass() * gravity_.dot(before[i].position);
    }
    mag = magnetic;
    const double total = kin + grav + mag;
    if (!haveStart_) startEnergy_ = total, haveStart_ = true;
    lastEnergy_ = total;
    peakKinetic_ = std::max(peakKinetic_, kin);
    const double rise = total - startEnergy_;
    highestRise_ = std::max(highestRise_, rise);
    const double allowed = settings_.energyRise * peakKinetic_ + 10.0 * tolerance_ * std::abs(mag);

    // Motion in the step, and a safe step per body.
    std::size_t worst = bodies.size();
    double worstSafe = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        const Body& b = bodies[i];
        Track& k = tracks_[i];
        if (b.fixed || k.size <= 0) continue;
        const double speed = b.velocity.norm(), spin = b.angularVelocity.norm();
        if (speed > maxSpeed_) maxSpeed_ = speed, fastest_ = b.name;
        const double travel = (b.position - before[i].position).norm();
        const double arc = angleBetween(b.orientation, before[i].orientation) * k.radius;
        const double moved = std::max(travel, arc) / k.size;

        // Safe step: the motion criterion, and 1/20 of the magnetic oscillation's
        // period from the stiffness between the last two steps' starts.
        const double surfaceSpeed = std::max(speed, spin * k.radius);
        double safe = surfaceSpeed > 0 ? settings_.travel * k.size / surfaceSpeed
                                       : std::numeric_limits<double>::infinity();
        const Vec3& F = wrenches[i].force;
        const Vec3 T = wrenches[i].totalTorque();
        if (k.havePrevious) {
            double omega2 = 0;
            const double dx = (before[i].position - k.previousPosition).norm();
            if (dx > 0) omega2 = std::max(omega2, (F - k.previousForce).norm() / dx / b.mass());
            const double dtheta = angleBetween(before[i].orientation, k.previousOrientation);
            const double Imin = k.smallestInertia;
            if (dtheta > 0 && Imin > 0) omega2 = std::max(omega2, (T - k.previousTorque).norm() / dtheta / Imin);
            if (omega2 > 0) safe = std::min(safe, 2.0 * std::acos(-1.0) / std::sqrt(omega2) / kStepsPerPeriod);
        }
        safe = std::min(safe, bodyStableDeltaT(b, k.size, k.radius, k.smallestInertia, wrenches[i], settings_.travel));
        k.havePrevious = true;
        k.previousPosition = before[i].position;
        k.previousOrientation = before[i].orientation;
        k.previousForce = F;
        k.previousTorque = T;
        if (safe < worstSafe) worstSafe = safe, worst = i;

        if (moved > settings_.travel) {
            k.quietSteps = 0;
            if (!k.warned) {
                k.warned = true;
                report(fmt::format("step {} (t = {:.6g} s): body '{}' moved {:.2g} of its smallest dimension "
                                   "({:.3g} m) in one step (speed {:.3g} m/s, spin {:.3g} rad/s); deltaT {} is too "
                                   "large, a safe one is ~{}",
                                   step, t, b.name, moved, k.size, speed, spin, seconds(dt), seconds(safe)));
            }
        } else if (k.warned && ++k.quietSteps >= kQuietSteps) {
            k.warned = false;
        }
    }

    if (rise > allowed && rise > 0) {
        energyQuiet_ = 0;
        if (!energyWarned_) {
            energyWarned_ = true;
            std::string who = worst < bodies.size()
                                  ? fmt::format("; the stiffest motion is body '{}': a safe deltaT is ~{}",
                                                bodies[worst].name, seconds(worstSafe))
                                  : std::string();
            report(fmt::format("step {} (t = {:.6g} s): the total energy {:.4g} J rose {:.3g} J above its start "
                               "({:.3g} of the peak kinetic energy {:.3g} J; allowed {:.3g} J) with deltaT {}{}",
                               step, t, total, rise, peakKinetic_ > 0 ? rise / peakKinetic_ : 0.0, peakKinetic_,
                               allowed, seconds(dt), who));
        }
    } else if (energyWarned_ && ++energyQuiet_ >= kQuietSteps) {
        energyWarned_ = false;
    }
    return stop;
}

double StepAudit::stableDeltaT(const std::vector<Body>& bodies, const std::vector<Wrench>& wrenches,
                               bool implicitTilt) const {
    double dt = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        const Track& k = tracks_[i];
        if (bodies[i].fixed || k.size <= 0) continue;
        dt = std::min(dt, bodyStableDeltaT(bodies[i], k.size, k.radius, k.smallestInertia, wrenches[i],
                                           kProposalTravel * settings_.travel, implicitTilt));
    }
    return dt;
}

double StepAudit::energyDrift() const {
    return peakKinetic_ > 0 ? (lastEnergy_ - startEnergy_) / peakKinetic_ : 0.0;
}

void StepAudit::summary(const std::vector<Body>& bodies) const {
    if (!haveStart_) return;
    int dynamic = 0, resting = 0;
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        if (bodies[i].fixed) continue;
        ++dynamic;
        const double surface = std::max(bodies[i].velocity.norm(),
                                        bodies[i].angularVelocity.norm() * tracks_[i].radius);
        if (surface < kRestSpeed) ++resting;
    }
    spdlog::info("Audit: total energy {:.6g} J at the start, {:.6g} J at the last step, drift {:.3g} of the peak "
                 "kinetic energy {:.3g} J; at most {:.3g} J above the start",
                 startEnergy_, lastEnergy_, energyDrift(), peakKinetic_, std::max(0.0, highestRise_));
    spdlog::info("  highest speed {:.3g} m/s{}; {} of {} dynamic bodies at rest at the end (< 1 mm/s); {} "
                 "warning(s)",
                 maxSpeed_, fastest_.empty() ? "" : " (body '" + fastest_ + "')", resting, dynamic, warnings_);
}

} // namespace mag::solver
