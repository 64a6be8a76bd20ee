// Wrench: what one body exerts on another (or the sum over all others), in one
// type for every model. `torque` is the magnetic torque (paper Eq. 17, or a
// model's counterpart), `mechanicalTorque` the torque of the force density about
// the target's centre of mass (Eq. 18); the body turns under their sum.
#pragma once

#include "magFoam/Types.hpp"

namespace mag {

struct Wrench {
    Vec3 force = Vec3::Zero();            // N (Eq. 16)
    Vec3 torque = Vec3::Zero();           // magnetic torque, N m (Eq. 17)
    Vec3 mechanicalTorque = Vec3::Zero(); // about the target's centre of mass, N m (Eq. 18)
    double energy = 0;                    // interaction energy with other bodies, J (each pair
                                          // is in both bodies' wrenches)
    double ownEnergy = 0;                 // energy in an applied field, J (this body's alone)
    // -d energy / d M_t (T m^3): the target-volume integral of the field its
    // energy sees (B, or mu0 H for the charge model in overlap), set by
    // evaluators' interaction() (FieldEvaluator::fieldIntegral); the
    // reactions addPairWrenches adds to the sources do not carry it.
    Vec3 fieldIntegral = Vec3::Zero();

    Vec3 totalTorque() const { return torque + mechanicalTorque; }
    // This body's magnetic energy: with the other bodies and in the applied field.
    double bodyEnergy() const { return energy + ownEnergy; }
    Wrench& operator+=(const Wrench& o) {
        force += o.force, torque += o.torque, mechanicalTorque += o.mechanicalTorque, energy += o.energy;
        ownEnergy += o.ownEnergy, fieldIntegral += o.fieldIntegral;
        return *this;
    }
};

// The magnetic energy of a scene from its bodies' wrenches: every pair once,
// plus each body's energy in the applied field, less half of every soft
// body's: a linear induced moment m = K B has the energy -1/2 m . B in the
// field B of the permanent sources, and the soft-soft pairs are part of it
// (docs/physics.md#energy). `soft(i)` says whether body i is soft.
template <class Wrenches, class IsSoft> double sceneMagneticEnergy(const Wrenches& wrenches, IsSoft soft) {
    double e = 0;
    for (std::size_t i = 0; i < wrenches.size(); ++i) {
        const Wrench& w = wrenches[i];
        e += 0.5 * w.energy + w.ownEnergy;
        if (soft(i)) e -= 0.5 * w.bodyEnergy();
    }
    return e;
}

} // namespace mag
