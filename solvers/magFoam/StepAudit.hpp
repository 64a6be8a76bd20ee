// magFoam's per-step energy and motion audit (docs/dynamics.md#audit). A time
// step that is too large for the magnetic stiffness of touching magnets does
// not crash: it pumps energy into the bodies until they fly apart. The audit
// names it while it happens, cheaply (no extra field evaluation: the step's
// own wrenches carry the pair energies):
// - energy: kinetic + gravitational + magnetic at the start of each step. It
//   warns when the total rises above its start by more than
//   energyRise x (the peak kinetic energy so far) plus what the field's
//   tolerance allows (10 x tolerance x |magnetic energy|);
// - motion: each dynamic body's travel in the step, and the farthest its
//   surface moves by the step's turn (a corner of its body-frame bounding
//   box), against its smallest dimension (the smallest edge of that box); it
//   warns above `travel`.
// Each warning names the body, the step and a time step that would be safe:
// the smaller of stableDeltaT's criteria at the full `travel` and 1/20 of the
// period of the magnetic oscillation from the stiffness the last two steps
// show (change of force over change of position, of I^-1 torque over change
// of angle). Once per episode:
// a condition must stay clear for 100 steps before it warns again. With
// `strict` (controlDict audit.strict, magFoam -strict) check() returns the
// message as a stop instead. summary() logs the run's energy drift, how far
// the total rose above its start and above its lowest before (energy regained
// after it was lost), its highest speed and how many bodies are at rest at
// the end.
#pragma once

#include <magFoam/Body.hpp>
#include <magFoam/ControlDict.hpp>
#include <magFoam/Wrench.hpp>

#include <array>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace mag::solver {

// The adaptive step's proposal and what set it, for the log: the body (its
// index; none when nothing proposes) and the criterion ("travel", "turn",
// "force stiffness", "tilt stiffness").
struct StepProposal {
    double deltaT = std::numeric_limits<double>::infinity();
    std::size_t body = static_cast<std::size_t>(-1);
    std::string_view limit;
};

// A body's acceleration over the last step, contacts included (world frame).
struct NetAcceleration {
    Vec3 linear = Vec3::Zero();  // m/s^2
    Vec3 angular = Vec3::Zero(); // rad/s^2
};

// What the audit needs of a body's shape, once per run (body frame).
struct BodyGeometry {
    explicit BodyGeometry(const Body& body);
    double size = 0;                    // smallest bounding-box edge (m)
    std::array<Vec3, 8> corners{};      // bounding box about the centre of mass
    double smallestInertia = 0;         // kg m^2, principal
    Mat3 inverseInertia = Mat3::Zero(); // body frame
    // The largest eigenvalue of P I^-1 P, P the projection normal to the
    // moment: |U| times it is the squared tilt frequency (1 / I_min without a moment).
    double tiltCompliance(const Vec3& momentBody) const;
};

class StepAudit {
public:
    // fieldTolerance: FieldEvaluator::forceTolerance() (0: none promised).
    StepAudit(const std::vector<Body>& bodies, const AuditSettings& settings, double fieldTolerance,
              const Vec3& gravity);

    // After step `step` (ending at t) of length dt: `before` is the bodies'
    // state at its start, `bodies` at its end, `wrenches` those of the start
    // and `magnetic` the scene's magnetic energy from them (MagneticSystem).
    // Logs a warning per new episode; returns the message to stop with when
    // strict.
    std::optional<std::string> check(long step, double t, double dt, const std::vector<BodyState>& before,
                                     const std::vector<Body>& bodies, const std::vector<Wrench>& wrenches,
                                     double magnetic);

    // "Audit: ..." lines for the end of the run.
    void summary(const std::vector<Body>& bodies) const;

    // A step that resolves every dynamic body's motion and magnetic
    // oscillation in the state of `bodies` under `wrenches` (the adaptive
    // step's proposal, docs/dynamics.md#adaptive-time-step): per body the
    // smaller of the step in which the centre or the surface (its bounding
    // box's corners) would travel travel / 2 x size (v dt + a dt^2,
    // semi-implicit Euler, from the velocities, the magnetic force and
    // I^-1 torque; gravity and contacts are not counted) and 1/20 of
    // 2 pi / omega, with omega^2 = max(|U| lambda, |F| / (m size)) from the
    // body's magnetic energy U and force F (a moment tilts with stiffness |U|
    // about the axes normal to it, lambda = BodyGeometry::tiltCompliance; its
    // force changes on the scale of its size). Infinity when nothing moves or
    // pulls. With implicitTilt (magneticStiffness: implicit, ImplicitTorque.hpp)
    // the tilt term is left out (the backend integrates it implicitly).
    StepProposal stableDeltaT(const std::vector<Body>& bodies, const std::vector<Wrench>& wrenches,
                              bool implicitTilt = false) const;

    // Adaptive steps: the proposal takes a body's acceleration over the last
    // step (contacts included) where it is below the magnetic one, so it is
    // part of the restart state: timeStep.yaml lines ("netAcceleration:"),
    // and read back (TimeLoop.hpp Start::netAcceleration).
    std::string netAccelerationState(const std::vector<Body>& bodies) const;
    void restoreNetAcceleration(const std::vector<Body>& bodies,
                                const std::vector<std::pair<std::string, std::array<double, 6>>>& saved);

    // What the run saw (tests).
    int warnings() const { return warnings_; }
    double energyDrift() const; // (last - first total energy) / peak kinetic energy
    double energyRecovery() const { return highestRecovery_; } // J: most above the lowest total before

private:
    struct Track {
        explicit Track(const Body& body) : geometry(body) {}
        BodyGeometry geometry;
        bool havePrevious = false;
        bool haveNet = false;
        NetAcceleration net;
        Vec3 previousPosition = Vec3::Zero(), previousForce = Vec3::Zero(), previousTorque = Vec3::Zero();
        Quat previousOrientation = Quat::Identity();
        int quietSteps = 0;
        bool warned = false;
    };
    AuditSettings settings_;
    double tolerance_;
    Vec3 gravity_;
    std::vector<Track> tracks_;
    bool haveStart_ = false;
    double startEnergy_ = 0, lastEnergy_ = 0, peakKinetic_ = 0, highestRise_ = 0;
    double lowestEnergy_ = 0, highestRecovery_ = 0, recoveryTime_ = 0;
    double maxSpeed_ = 0;
    std::string fastest_;
    int energyQuiet_ = 0, warnings_ = 0;
    bool energyWarned_ = false;
};

} // namespace mag::solver
