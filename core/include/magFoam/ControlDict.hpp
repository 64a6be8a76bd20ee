// Run controls (system/controlDict.yaml):
//
//   startTime: 0          # s
//   endTime: 1.0          # s, > startTime
//   deltaT: 0.001         # s, > 0; fixed steps: divides endTime - startTime
//   writeInterval: 0.01   # simulated seconds between writes, > 0
//   startFrom: startTime  # or latestTime (restart from the newest time folder)
//   libs: []              # extra plugin libraries: bare names or paths
//   threads: 1            # worker threads for the pair wrenches (0 = all cores);
//                         # results are bit-identical for any count (Threads.hpp)
//   adjustTimeStep: false # magFoam chooses each step (docs/dynamics.md#adaptive-time-step):
//   maxDeltaT: 0.01       #   at most this (s), default deltaT x 100
//   minDeltaT: 1e-7       #   at least this (s), default deltaT / 1000
//                         #   deltaT is then the first step; write times are hit exactly
//   magneticStiffness: explicit # or implicit: each body's magnetic torque taken
//                         # at the end of the step, linearised in its tilt
//                         # stiffness and solved by the backend with the contacts
//                         # (docs/dynamics.md#implicit-tilt-stiffness); the adaptive
//                         # step drops its tilt-oscillation limit
//   audit:                # magFoam's per-step energy and motion audit (docs/dynamics.md)
//     energyRise: 0.05    # warn when the total energy exceeds its start by this
//                         # fraction of the peak kinetic energy (plus what the
//                         # field's tolerance allows)
//     travel: 0.1         # warn when a body moves (or its surface turns) by more
//                         # than this fraction of its smallest dimension in a step
//     strict: false       # stop the run instead (also: magFoam -strict)
#pragma once

#include "magFoam/Dictionary.hpp"

#include <string>
#include <vector>

namespace mag {

struct AuditSettings {
    double energyRise = 0.05;
    double travel = 0.1;
    bool strict = false;
};

struct ControlDict {
    double startTime = 0;
    double endTime = 1;
    double deltaT = 1e-3;
    double writeInterval = 0.01;
    std::string startFrom = "startTime";
    std::vector<std::string> libs;
    int threads = 1;
    AuditSettings audit;
    bool adjustTimeStep = false;
    double maxDeltaT = 0, minDeltaT = 0;
    bool implicitTorque = false; // magneticStiffness: implicit

    // Reads and checks (InputError naming the key): deltaT > 0, endTime not
    // before startTime, at most maxSteps steps of deltaT to the largest time,
    // and with fixed steps deltaT dividing endTime - startTime (the message
    // proposes the nearest deltaT and endTime that do).
    static ControlDict read(const Dict& dict);
    static constexpr double maxSteps = 1e12;
};

} // namespace mag
