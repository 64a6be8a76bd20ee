// The tilt stiffness of each body for the implicit magnetic torque
// (controlDict `magneticStiffness: implicit`, docs/dynamics.md#large-steps;
// RigidBodyBackend::setTiltStiffness integrates it). A magnet tilted in
// another's field swings about its alignment at omega = sqrt(|U| / I); the
// backends' semi-implicit Euler step is stable only for omega dt < 2 and gains
// energy as (omega dt)^2 below that. Linearised,
//   tau(theta + dt w') ~ tau - S dt w',   S = (m . B) 1 - m B^T,
// the rotational stiffness of a moment m in a uniform field B; the backend
// solves (I + h^2 S) w' = I w + h (tau - S phi + contact torques) in each
// sub-step h of the step, phi the turn since the step began: backward Euler
// of the free swing, stable at any dt, damping it by 1 / sqrt(1 + (omega dt)^2)
// per step, consistent to first order in dt. A torque a contact balances
// stays balanced (the contact holds w' = 0, the torque is applied in full).
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

// S of every body (zero for fixed ones), for RigidBodyBackend::setTiltStiffness.
std::vector<Mat3> tiltStiffnesses(const std::vector<Body>& bodies, const std::vector<Wrench>& wrenches);

} // namespace mag::solver
