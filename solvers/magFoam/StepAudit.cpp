#include "StepAudit.hpp"

#include <magFoam/Log.hpp>
#include <magFoam/ResultsWriter.hpp>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace mag::solver {

namespace {

constexpr int kQuietSteps = 100;       // a condition clear this long ends its episode
constexpr double kRestSpeed = 1e-3;    // m/s: at rest below (surface speed too)
constexpr double kRoundingFloor = 1e-9; // of |energies| in play: what the audit cannot tell from rounding
// The adaptive step aims at half the travel the audit warns at: at the full
// travel, a 6 mm cube spinning up in free fall gained 6 % of its kinetic energy
// (dropMagnet tutorial), at half 3e-4 of the peak.
constexpr double kProposalTravel = 0.5;
constexpr double kStepsPerPeriod = 20; // safe step: this many per magnetic oscillation

double angleBetween(const Quat& a, const Quat& b) {
    const double c = std::min(1.0, std::abs(a.dot(b)));
    return 2.0 * std::acos(c);
}

// The largest distance of a point of the body from an axis through its centre
// of mass along `axis` (body frame), times |axis|: the surface speed of a spin
// `axis`, or the surface acceleration of an angular acceleration `axis`. The
// distance from an axis is convex, so the body-frame bounding box's corners
// bound it.
double surfaceRate(const std::array<Vec3, 8>& corners, const Vec3& axis) {
    double r = 0;
    for (const Vec3& c : corners) r = std::max(r, axis.cross(c).norm());
    return r;
}

// stableDeltaT for one body (see the header); `limit` names the criterion that set it.
double bodyStableDeltaT(const Body& b, const BodyGeometry& g, const Wrench& w, double travel,
                        bool implicitTilt = false, const char** limit = nullptr, const NetAcceleration* net = nullptr) {
    double dt = std::numeric_limits<double>::infinity();
    const char* why = "";
    auto take = [&](double candidate, const char* name) {
        if (candidate < dt) dt = candidate, why = name;
    };
    // Travel of the centre and of the surface in a step: v dt + a dt^2 <= travel size
    // (the backends' semi-implicit Euler moves by the new velocity, v + a dt).
    auto within = [&](double v, double a) {
        const double d = travel * g.size;
        if (a > 0) return 2.0 * d / (v + std::sqrt(v * v + 4.0 * a * d));
        return v > 0 ? d / v : std::numeric_limits<double>::infinity();
    };
    // A body that contacts hold moves by less than its magnetic force says:
    // the net acceleration of the last step, where known, bounds it.
    double a = w.force.norm() / b.mass();
    if (net) a = std::min(a, net->linear.norm());
    take(within(b.velocity.norm(), a), "travel");
    // The surface's speed and acceleration from the spin and the magnetic
    // torque (I^-1 tau: a clip's torque about its long axis meets its smallest
    // inertia, about its normal its largest), in the body frame.
    const Quat toBody = b.orientation.conjugate();
    const Vec3 spin = toBody * b.angularVelocity;
    const Vec3 alpha = g.inverseInertia * (toBody * w.totalTorque());
    double surfaceAcceleration = surfaceRate(g.corners, alpha);
    if (net) surfaceAcceleration = std::min(surfaceAcceleration, surfaceRate(g.corners, toBody * net->angular));
    take(within(surfaceRate(g.corners, spin), surfaceAcceleration), "turn");
    const double twoPi = 2.0 * pi;
    const double forceOmega2 = w.force.norm() / (b.mass() * g.size);
    if (forceOmega2 > 0) take(twoPi / std::sqrt(forceOmega2) / kStepsPerPeriod, "force stiffness");
    if (!implicitTilt) {
        // A moment m in a field tilts with stiffness |U| about the axes normal
        // to m (ImplicitTorque.hpp): omega^2 = |U| x the largest eigenvalue of
        // P I^-1 P, P the projection normal to m.
        const double tiltOmega2 = std::abs(w.bodyEnergy()) * g.tiltCompliance(toBody * b.magneticMoment());
        if (tiltOmega2 > 0) take(twoPi / std::sqrt(tiltOmega2) / kStepsPerPeriod, "tilt stiffness");
    }
    if (limit) *limit = why;
    return dt;
}

std::string seconds(double dt) { return std::isfinite(dt) ? fmt::format("{:.2g} s", dt) : "unknown"; }

} // namespace

BodyGeometry::BodyGeometry(const Body& body) {
    const SurfaceMesh& m = body.shape->mesh;
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (const Vec3& v : m.vertices) {
        lo = lo.cwiseMin(v);
        hi = hi.cwiseMax(v);
    }
    if (m.vertices.empty()) lo = hi = Vec3::Zero();
    size = (hi - lo).minCoeff();
    for (int c = 0; c < 8; ++c)
        corners[c] = Vec3(c & 1 ? hi.x() : lo.x(), c & 2 ? hi.y() : lo.y(), c & 4 ? hi.z() : lo.z());
    const Mat3 I = body.inertiaBody();
    smallestInertia = Eigen::SelfAdjointEigenSolver<Mat3>(I).eigenvalues().minCoeff();
    if (smallestInertia > 0) inverseInertia = I.inverse();
}

double BodyGeometry::tiltCompliance(const Vec3& momentBody) const {
    if (!(smallestInertia > 0)) return 0.0;
    const double mm = momentBody.squaredNorm();
    if (!(mm > 0)) return 1.0 / smallestInertia; // no moment: every axis counts
    const Mat3 P = Mat3::Identity() - momentBody * momentBody.transpose() / mm;
    const Mat3 C = P * inverseInertia * P;
    return Eigen::SelfAdjointEigenSolver<Mat3>(0.5 * (C + C.transpose())).eigenvalues().maxCoeff();
}

StepAudit::StepAudit(const std::vector<Body>& bodies, const AuditSettings& settings, double fieldTolerance,
                     const Vec3& gravity)
    : settings_(settings), tolerance_(fieldTolerance), gravity_(gravity) {
    tracks_.reserve(bodies.size());
    for (const Body& b : bodies) tracks_.emplace_back(b);
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
    if (!haveStart_) startEnergy_ = lowestEnergy_ = total, haveStart_ = true;
    lastEnergy_ = total;
    // A passive scene does not regain what it has lost: a rise above the
    // lowest total so far is energy made after the start's margin was spent,
    // which the comparison with the start no longer sees. Reported, not
    // warned: a contact solver pushing penetrated magnets apart against their
    // pull counts too (docs/dynamics.md#audit).
    if (total - lowestEnergy_ > highestRecovery_) highestRecovery_ = total - lowestEnergy_, recoveryTime_ = t - dt;
    lowestEnergy_ = std::min(lowestEnergy_, total);
    peakKinetic_ = std::max(peakKinetic_, kin);
    const double rise = total - startEnergy_;
    highestRise_ = std::max(highestRise_, rise);
    // Plus the rounding of the sum: 1e-9 of the energies in play (a body at rest
    // on a magnet has no kinetic energy to measure against, and its total moved
    // by 3e-16 J of 1.4e-4 J was a warning).
    const double allowed = settings_.energyRise * peakKinetic_ + 10.0 * tolerance_ * std::abs(mag) +
                           kRoundingFloor * (kin + std::abs(grav) + std::abs(mag));

    // Motion in the step, and a safe step per body.
    std::size_t worst = bodies.size();
    double worstSafe = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        const Body& b = bodies[i];
        Track& k = tracks_[i];
        if (b.fixed || k.geometry.size <= 0) continue;
        const double speed = b.velocity.norm(), spin = b.angularVelocity.norm();
        if (speed > maxSpeed_) maxSpeed_ = speed, fastest_ = b.name;
        const double travel = (b.position - before[i].position).norm();
        // The surface's largest displacement by the step's turn (a box corner's).
        double arc = 0;
        for (const Vec3& c : k.geometry.corners)
            arc = std::max(arc, (b.orientation * c - before[i].orientation * c).norm());
        const double moved = std::max(travel, arc) / k.geometry.size;

        // Safe step: the proposal's criteria at the full travel, and 1/20 of
        // the magnetic oscillation's period from the stiffness between the last
        // two steps' starts.
        double safe = bodyStableDeltaT(b, k.geometry, wrenches[i], settings_.travel);
        const Vec3& F = wrenches[i].force;
        const Vec3 T = wrenches[i].totalTorque();
        if (k.havePrevious) {
            double omega2 = 0;
            const double dx = (before[i].position - k.previousPosition).norm();
            if (dx > 0) omega2 = std::max(omega2, (F - k.previousForce).norm() / dx / b.mass());
            const double dtheta = angleBetween(before[i].orientation, k.previousOrientation);
            if (dtheta > 0)
                omega2 = std::max(omega2, (k.geometry.inverseInertia * (b.orientation.conjugate() * (T - k.previousTorque)))
                                              .norm() / dtheta);
            if (omega2 > 0) safe = std::min(safe, 2.0 * pi / std::sqrt(omega2) / kStepsPerPeriod);
        }
        k.net.linear = (b.velocity - before[i].velocity) / dt;
        k.net.angular = (b.angularVelocity - before[i].angularVelocity) / dt;
        k.haveNet = std::isfinite(k.net.linear.norm() + k.net.angular.norm());
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
                                   step, t, b.name, moved, k.geometry.size, speed, spin, seconds(dt), seconds(safe)));
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

StepProposal StepAudit::stableDeltaT(const std::vector<Body>& bodies, const std::vector<Wrench>& wrenches,
                                     bool implicitTilt) const {
    StepProposal p;
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        const Track& k = tracks_[i];
        if (bodies[i].fixed || k.geometry.size <= 0) continue;
        const char* limit = "";
        // Only a body at rest (every point below 1 mm/s) proposes from its
        // net acceleration: two clips pressed together while they moved took
        // a step that the released magnetic pull between them blew up in
        // (Fig. 8: clip2 thrown at 1.6 m/s, 2.2e-4 J made).
        const Body& b = bodies[i];
        const bool resting = b.velocity.norm() + surfaceRate(k.geometry.corners, b.orientation.conjugate() *
                                                                                     b.angularVelocity) < kRestSpeed;
        const double dt = bodyStableDeltaT(b, k.geometry, wrenches[i], kProposalTravel * settings_.travel,
                                           implicitTilt, &limit, k.haveNet && resting ? &k.net : nullptr);
        if (dt < p.deltaT) p.deltaT = dt, p.body = i, p.limit = limit;
    }
    return p;
}

std::string StepAudit::netAccelerationState(const std::vector<Body>& bodies) const {
    std::string out;
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        const Track& k = tracks_[i];
        if (bodies[i].fixed || !k.haveNet) continue;
        if (out.empty())
            out = "# each body's acceleration over the last step, contacts included (m/s^2, rad/s^2):\n"
                  "# the next step's proposal (docs/dynamics.md#adaptive-time-step)\nnetAcceleration:\n";
        const Vec3& a = k.net.linear;
        const Vec3& w = k.net.angular;
        out += "  " + bodies[i].name + ": [" + formatExact(a.x()) + ", " + formatExact(a.y()) + ", " +
               formatExact(a.z()) + ", " + formatExact(w.x()) + ", " + formatExact(w.y()) + ", " +
               formatExact(w.z()) + "]\n";
    }
    return out;
}

void StepAudit::restoreNetAcceleration(const std::vector<Body>& bodies,
                                       const std::vector<std::pair<std::string, std::array<double, 6>>>& saved) {
    for (const auto& [name, v] : saved)
        for (std::size_t i = 0; i < bodies.size(); ++i)
            if (bodies[i].name == name) {
                tracks_[i].net.linear = Vec3(v[0], v[1], v[2]);
                tracks_[i].net.angular = Vec3(v[3], v[4], v[5]);
                tracks_[i].haveNet = true;
            }
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
        const double surface =
            std::max(bodies[i].velocity.norm(),
                     surfaceRate(tracks_[i].geometry.corners, bodies[i].orientation.conjugate() * bodies[i].angularVelocity));
        if (surface < kRestSpeed) ++resting;
    }
    spdlog::info("Audit: total energy {:.6g} J at the start, {:.6g} J at the last step, drift {:.3g} of the peak "
                 "kinetic energy {:.3g} J; at most {:.3g} J above the start, {:.3g} J above its lowest before{}",
                 startEnergy_, lastEnergy_, energyDrift(), peakKinetic_, std::max(0.0, highestRise_),
                 highestRecovery_, highestRecovery_ > 0 ? fmt::format(" (t = {:.4g} s)", recoveryTime_) : "");
    spdlog::info("  highest speed {:.3g} m/s{}; {} of {} dynamic bodies at rest at the end (< 1 mm/s); {} "
                 "warning(s)",
                 maxSpeed_, fastest_.empty() ? "" : " (body '" + fastest_ + "')", resting, dynamic, warnings_);
}

} // namespace mag::solver
