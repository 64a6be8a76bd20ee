// Sleeping bodies' settings (docs/dynamics.md#sleeping): `sleep:` in
// constant/rigidBody.yaml, the solver's key beside the backend's own. Case
// reads it with the case, so that every app that builds a backend from that
// dictionary finds it checked and set aside.
#pragma once

#include "magFoam/Dictionary.hpp"

namespace mag {

struct SleepSettings {
    bool enabled = false;
    double speed = 1e-3;         // m/s: calm below (centre and surface)
    double time = 0.02;          // s: calm this long before sleeping
    double wrenchChange = 1e-3;  // relative change of the magnetic wrench (and magnetization)
    // Who sleeps together: bodies the backend found touching in the last step
    // (contacts, as Bullet's and ODE's islands), or bodies whose bounding
    // spheres come within `margin` (boundingSpheres; also the fallback of a
    // backend that cannot report its contacts).
    enum class Islands { contacts, boundingSpheres };
    Islands islands = Islands::contacts;
    double margin = 0.1;         // boundingSpheres: closer than margin x the smaller radius

    // `sleep:` of constant/rigidBody.yaml (absent: disabled; `sleep: {}`: the
    // defaults); InputError naming the key for a bad value.
    static SleepSettings read(const Dict& rigidBody);
};

} // namespace mag
