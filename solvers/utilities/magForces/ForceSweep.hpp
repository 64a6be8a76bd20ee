// magForces' evaluations as functions, so that the magForces app and the
// Python module (Case.forces) compute the same numbers: the case's
// configuration, with the induced magnetizations converged first, or an
// optional sweep of one body (system/forcesDict.yaml), either along a
// direction or about an axis:
//
//   sweep: {body: top, direction: [0, 0, 1], from: -0.01, to: 0.02, steps: 61}
//   sweep: {body: top, rotate: {axis: [0, 0, 1], from: 0, to: 90, steps: 19}}
//
// Translation: offsets from..to (m) along the direction from the body's
// position. Rotation: angles from..to (degrees, as orientations in
// bodies.yaml) about the world-frame axis through the body's centre of mass,
// applied to its orientation in bodies.yaml; only the orientation changes.
// steps is the number of evaluations, from and to included (1: from only).
#pragma once

#include <magFoam/Body.hpp>
#include <magFoam/Case.hpp>
#include <magFoam/MagneticSystem.hpp>
#include <magFoam/Wrench.hpp>

#include <functional>
#include <optional>
#include <vector>

namespace mag::forces {

struct Sweep {
    std::size_t body = 0;
    bool rotate = false;
    Vec3 direction = Vec3::UnitZ();  // translation: direction; rotation: axis (unit)
    double from = 0, to = 0;         // m, or degrees
    int steps = 1;
};

// system/forcesDict.yaml of the case when it exists (InputError naming the key
// on bad input), else none.
std::optional<Sweep> readForcesDict(const Case& c);

// One evaluation: the sweep step, its offset (m) or angle (degrees), and every
// body's wrench from all others (indexed like `bodies`).
struct Evaluation {
    int step = 0;
    double offset = 0;
    const std::vector<Body>& bodies;
    const std::vector<Wrench>& wrenches;
};

// Evaluate the configuration of `bodies` (one evaluation, offset 0) or each
// step of `sweep` in order, calling `onEvaluation` after each; the swept body
// is left at the last step. Returns the seconds spent converging and in the
// wrenches (the timing magForces prints).
double evaluate(std::vector<Body>& bodies, const MagneticSystem& system, const std::optional<Sweep>& sweep,
                const std::function<void(const Evaluation&)>& onEvaluation);

} // namespace mag::forces
