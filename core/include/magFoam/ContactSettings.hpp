// The constant/rigidBody.yaml keys that the contact backends (ODE, Bullet)
// read alike (docs/rigid-bodies.md#backends), and the sub-step rule they
// share. Each backend reads its own keys beside these and reports unused ones.
#pragma once

#include "magFoam/Dictionary.hpp"
#include "magFoam/Types.hpp"

#include <optional>

namespace mag {

struct ContactSettings {
    Vec3 gravity = Vec3::Zero();          // m/s^2
    std::optional<double> groundHeight;   // the plane z = height, if any
    double friction = 0.5;                // Coulomb mu of every pair
    // Resistance to rolling (about the contact's tangents) and to spinning
    // (about its normal), as lengths: a contact carrying the normal force N
    // resists with a torque up to rollingFriction x N and spinningFriction x N.
    // A rigid point contact has neither, so a body rocking on an edge or a
    // pendulum hanging from a magnet swings for ever; a real contact is a
    // patch that has both (docs/rigid-bodies.md#rolling-and-spinning-friction).
    double rollingFriction = 0;           // m
    double spinningFriction = 0;          // m
    double restitution = 0.1;
    double bounceVelocity = 0.1;          // m/s: slower impacts do not bounce
    double erp = 0.2;                     // share of the penetration corrected per sub-step
    double surfaceLayer = 1e-6;           // m of penetration left uncorrected
    int subSteps = 1, maxSubSteps = 1000;
    double maxTravel = 0.1;               // of the bounding radius per sub-step; 0: always subSteps

    // From the backend's dictionary `d` and its `contact:` mapping `contact`.
    static ContactSettings read(const Dict& d, const Dict& contact);

    // Sub-steps for one step in which the body that travels farthest, for its
    // size, goes `worstTravel` bounding radii (velocity, spin and acceleration
    // at the step's start; contacts ignored, so conservative).
    int subStepsFor(double worstTravel) const;
};

} // namespace mag
