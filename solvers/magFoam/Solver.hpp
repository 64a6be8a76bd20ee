// magFoam's transient run (paper Algorithm 1 + a rigid-body backend) as a
// function, so that the magFoam app and the Python module run the same loop:
// per step converge induced magnetizations, wrench on every body from all
// others, hand them to the backend, step it; write results at write times
// (ResultsWriter.hpp). Restart with `startFrom: latestTime`; a NaN/inf stops
// the run with the body and step named (StateError), after writing the last
// good state. Where the run starts, its time axis and its log statistics:
// TimeLoop.hpp; the audit: StepAudit.hpp.
#pragma once

#include <magFoam/Body.hpp>
#include <magFoam/Case.hpp>
#include <magFoam/ResultsWriter.hpp>
#include <magFoam/Wrench.hpp>

#include <csignal>
#include <functional>
#include <optional>
#include <vector>

namespace mag::solver {

// What is written at one write time, for callers that keep results in memory.
struct WriteRecord {
    double time = 0;  // s
    long step = 0;
    const std::vector<Body>& bodies;
    const std::vector<Wrench>& wrenches;  // full wrenches (pairs of fixed bodies too)
    Energies energies;                    // J
};

struct RunOptions {
    bool strict = false;                             // stop on an audit warning (magFoam -strict)
    std::optional<double> endTime;                   // replaces controlDict endTime (s)
    const volatile std::sig_atomic_t* stop = nullptr; // when set: write the state and stop
    std::function<void(const WriteRecord&)> onWrite; // after each write time's files
};

// Run the case in `c` (its bodies end in the final state). Worker threads are
// the caller's (setThreads). Throws InputError on bad input, StateError when
// the run cannot go on.
void run(Case& c, const RunOptions& options = {});

} // namespace mag::solver
