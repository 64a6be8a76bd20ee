// RigidBodyBackend: moves the bodies under the magnetic wrenches, gravity and
// contacts. Selected by constant/rigidBody.yaml `type:` (ODE, free).
#pragma once

#include "magFoam/Body.hpp"
#include "magFoam/Dictionary.hpp"
#include "magFoam/FieldEvaluator.hpp"
#include "magFoam/Registry.hpp"

#include <iosfwd>
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace mag {

class RigidBodyBackend {
public:
    virtual ~RigidBodyBackend() = default;

    // Called once with the bodies of the case before the first step.
    virtual void setup(const std::vector<Body>& bodies) = 0;

    // Advance by dt with the given external wrench per body (world frame,
    // torques about each COM) and write the new state back into `bodies`.
    // Between steps the backend continues from its own state: it does not
    // look for changes of the bodies (see setState).
    virtual void step(std::vector<Body>& bodies, std::span<const Wrench> wrenches, double dt) = 0;

    // The bodies' poses or velocities were set from outside (a restart, a
    // script, a test): take them over as they are, exactly, and forget what
    // was carried from the last step. Called by whoever changed them (the
    // solver at a restart), never detected by the backend.
    virtual void setState(const std::vector<Body>& bodies) = 0;

    // Restart state (docs/architecture.md): what a step carries to the next
    // beyond the bodies' state, written at every write time as
    // <time>/rigidBody.yaml and handed back at a restart after setState, so
    // that the restarted run continues bit for bit. Same contract as
    // InductionModel::writeState: YAML beginning with `type: <backend>`,
    // numbers exact (formatExact, ResultsWriter.hpp); nothing written (the
    // default) means no state and no file.
    virtual void writeState(std::ostream& /*yaml*/, const std::vector<Body>& /*bodies*/) const {}
    virtual void readState(const Dict& /*state*/, const std::vector<Body>& /*bodies*/) {}

    // Sleeping bodies (docs/dynamics.md#sleeping; the solver decides who
    // sleeps): from now on the bodies with asleep[i] != 0 rest where they are,
    // with zero velocity (written into `bodies`), until a later call wakes
    // them; the others move on. A backend whose contacts can wake a sleeping
    // body (touched by a moving one) reports it in sleeping(). The default
    // supports no sleeping.
    virtual bool canSleep() const { return false; }
    virtual void setSleeping(std::vector<Body>& /*bodies*/, const std::vector<char>& /*asleep*/) {}
    // Which bodies rest now (empty: none, or no sleeping).
    virtual std::vector<char> sleeping() const { return {}; }
    // The pairs of dynamic bodies (indices into `bodies`, i < j, each once)
    // that touched in the last step(), for islands of touching bodies
    // (`sleep: {islands: contacts}`). Only for a backend whose contact with a
    // moving body wakes a sleeping one (reported by sleeping()); false (the
    // default): islands by bounding spheres instead.
    virtual bool touching(std::vector<std::pair<std::size_t, std::size_t>>& /*pairs*/) const { return false; }

    // Implicit magnetic tilt stiffness (controlDict magneticStiffness:
    // implicit, docs/dynamics.md#large-steps): for the next step() only, each
    // body's rotational stiffness S (world frame, N m / rad, symmetric and
    // positive semi-definite; zero for none). The backend integrates the spin
    // as backward Euler of the torque tau - S dtheta, contacts included:
    // (I + h^2 S) w' = I w + h (tau - S phi + contact torques) per (sub-)step
    // of h, phi the turn since the step began (sub-steps keep the step's
    // linearisation), so a torque balanced by a contact stays balanced. Returns false when the
    // backend cannot (the default); the solver then refuses the setting.
    virtual bool setTiltStiffness(std::span<const Mat3> /*stiffness*/) { return false; }

    virtual std::string describe() const = 0;

    using Registry = mag::Registry<RigidBodyBackend>;
    static Registry& registry();
    static std::unique_ptr<RigidBodyBackend> New(const Dict& dict);

    template <class T> struct Add {
        explicit Add(const std::string& name, TypeDoc doc = {}) {
            noteModelLayout(sizeof(Body), alignof(Quat));
            registry().add(
                name, [](const Dict& d) { return std::unique_ptr<RigidBodyBackend>(new T(d)); }, std::move(doc));
        }
    };
};

} // namespace mag
