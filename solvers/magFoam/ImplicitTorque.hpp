// Linearly implicit magnetic torque (controlDict `magneticStiffness: implicit`,
// docs/dynamics.md#large-steps). A magnet tilted in another's field swings
// about its alignment at omega = sqrt(|U| / I); the backends' semi-implicit
// Euler step is stable only for omega dt < 2 and gains energy as (omega dt)^2
// below that. Here each dynamic body's torque is taken at the end of the step
// in its linearised form,
//   tau(theta + dt w') ~ tau - S dt w',   S = (m . B) 1 - m B^T,
// the rotational stiffness of a moment m in a uniform field B, and the step's
// end spin solved for: (I + dt^2 S) w' = I w + dt tau. The backend is handed
// the torque that gives that spin, tau' = I (w' - w) / dt. This is the
// backward Euler step of the tilt oscillation: stable at any dt, damping it
// by 1 / (1 + (omega dt)^2) per step, consistent to first order in dt (the
// change vanishes as dt -> 0). Contacts, gravity and forces stay as they were.
//
// B is not known per body; the body's wrench carries its magnetic energy U
// (pairs and applied field), and for a moment aligned with its field
// S = -U (1 - m^ m^T): the same estimate as the adaptive step's (|U| / I).
// Unstable alignments (U > 0) get no implicit part: a stiffness below zero is
// clipped to zero. One body at a time: the neighbours' coupling stays
// explicit, which is stable when the estimate is at least half the true
// self-stiffness (the Jury condition of the block-Jacobi split).
#pragma once

#include <magFoam/Body.hpp>
#include <magFoam/Wrench.hpp>

#include <vector>

namespace mag::solver {

// S for one body (world frame, N m / rad): symmetric, positive semi-definite.
Mat3 tiltStiffness(const Body& body, const Wrench& wrench);

// The wrenches to hand the backend for a step of dt: `wrenches` with each
// awake dynamic body's torque replaced as above (the change is added to
// mechanicalTorque, so energy and force are untouched).
std::vector<Wrench> implicitTorques(const std::vector<Body>& bodies, const std::vector<Wrench>& wrenches,
                                    double dt);

} // namespace mag::solver
