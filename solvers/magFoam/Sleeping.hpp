// Sleeping bodies (docs/dynamics.md#sleeping), as Bullet's and ODE's
// auto-disable do it, for the magnetic part too. A dynamic body is calm while
// its speed (and the speed its surface turns at) stays below `speed` and its
// magnetic wrench stays within `wrenchChange` of what it was when the calm
// began. Islands of bodies fall asleep together, once every member has been
// calm for `time` seconds: their velocities are set to zero and the
// rigid-body backend holds them still. An island is what touched in the last
// step (`islands: contacts`, the default, where the backend reports its
// contacts and a contact wakes a sleeping body: ODE), or what lies near
// (bounding spheres within `margin` of touching: `boundingSpheres`, and the
// other backends).
//
// The magnetic cost: pairs of two sleeping bodies, or of a sleeping and a
// fixed one, keep the wrench they had when the set of sleeping bodies last
// changed (cached, computed once per change); the step evaluates only pairs
// with an awake body. A sleeping body wakes, with its island, when
// - its wrench (the cached part plus the pairs with awake bodies, evaluated
//   every step) moves more than `wrenchChange` away from its value at the
//   moment it fell asleep (a neighbour moves, comes or goes),
// - its magnetization changes by more than `wrenchChange` (soft bodies),
// - an awake body comes within `margin` of its island (contact ahead;
//   boundingSpheres only), or
// - the backend reports that a contact woke it.
// With an applied field that changes in time nothing sleeps.
//
// Settings: constant/rigidBody.yaml `sleep: {enabled, speed, time,
// wrenchChange, islands, margin}` (SleepSettings.hpp, read with the case;
// docs/case-reference.md#rigidbody). The state (who
// sleeps, calm times, reference wrenches) is written to <time>/sleep.yaml so
// that a restart continues bit for bit.
#pragma once

#include <magFoam/Body.hpp>
#include <magFoam/Dictionary.hpp>
#include <magFoam/MagneticSystem.hpp>
#include <magFoam/RigidBodyBackend.hpp>
#include <magFoam/SleepSettings.hpp>
#include <magFoam/Wrench.hpp>

#include <iosfwd>
#include <string>
#include <vector>

namespace mag::solver {

class Sleeping {
public:
    Sleeping(const SleepSettings& settings, const std::vector<Body>& bodies, const Vec3& gravity,
             bool timeDependentField);

    bool enabled() const { return settings_.enabled; }
    // Who sleeps now (one flag per body), for bodies.csv.
    const std::vector<char>& asleep() const { return asleep_; }
    bool anyAsleep() const;
    // The bodies with the sleeping ones marked fixed (what the awake part of
    // a step sees: the pairs to evaluate, the adaptive step's proposal).
    const std::vector<Body>& awakeView(const std::vector<Body>& bodies);

    // The magnetic part of a step: MagneticSystem::step when nobody sleeps;
    // otherwise converge, then the pairs with an awake body evaluated and the
    // cached pairs of sleeping and fixed bodies added.
    MagneticSystem::Step magnetic(const MagneticSystem& magnets, std::vector<Body>& bodies);

    // Before the rigid-body step, with that step's wrenches: wake the islands
    // whose wrench or magnetization moved, or that an awake body comes near.
    void wakeBeforeStep(std::vector<Body>& bodies, const std::vector<Wrench>& wrenches, RigidBodyBackend& backend,
                        long step, double t);
    // After it (the bodies at the step's end): wake what the backend woke,
    // track calm times, and put calm islands to sleep.
    void sleepAfterStep(std::vector<Body>& bodies, const std::vector<Wrench>& wrenches, RigidBodyBackend& backend,
                        double dt, long step, double t);

    // Restart state (<time>/sleep.yaml): empty when disabled.
    std::string stateText(const std::vector<Body>& bodies) const;
    void readState(const Dict& d, std::vector<Body>& bodies, RigidBodyBackend& backend);

    // "sleeping: ..." lines for the end of the run.
    void summary() const;

private:
    struct Calm {
        double seconds = 0;        // calm this long
        Wrench reference;          // wrench when the calm began, or when it fell asleep
        Vec3 magnetization = Vec3::Zero();  // body frame, when it fell asleep
    };
    struct Sets;
    // Islands of dynamic bodies: touching in the backend's last step
    // (byContacts), or with bounding spheres within `margin`.
    bool byContacts(const RigidBodyBackend& backend);
    std::vector<std::vector<std::size_t>> islands(const std::vector<Body>& bodies, bool byContacts) const;
    static std::vector<std::vector<std::size_t>> groups(const std::vector<Body>& bodies, Sets& sets);
    // The change of body i's wrench from its reference, relative to the
    // larger of the reference and m g (force) or m g R (torque).
    double wrenchChange(std::size_t i, const Wrench& w) const;
    bool wrenchMoved(std::size_t i, const Wrench& w) const;
    // Why sleeping body i wakes (its wrench or magnetization moved), or empty.
    std::string wakeReason(std::size_t i, const std::vector<Body>& bodies, const Wrench& w) const;
    void wake(const std::vector<std::size_t>& island, std::vector<Body>& bodies, const std::string& why, long step,
              double t);

    SleepSettings settings_;
    std::vector<char> asleep_;
    std::vector<Calm> calm_;
    std::vector<double> forceScale_, torqueScale_;  // m g and m g R (N, N m): a floor for the wrench tests
    std::vector<Body> view_;      // awakeView's bodies, kept between steps
    std::vector<Wrench> frozen_;  // cached pairs among sleeping and fixed bodies
    bool frozenValid_ = false;
    bool changed_ = false;        // who sleeps changed: tell the backend
    std::vector<std::pair<std::size_t, std::size_t>> touching_;  // the backend's touching pairs
    bool fallbackNoted_ = false;
    long sleepEvents_ = 0, wakeEvents_ = 0, pairsSkipped_ = 0, pairsEvaluated_ = 0;
};

} // namespace mag::solver
