// Run controls (system/controlDict.yaml):
//
//   startTime: 0          # s
//   endTime: 1.0          # s, > startTime
//   deltaT: 0.001         # s, > 0
//   writeInterval: 0.01   # simulated seconds between writes, > 0
//   startFrom: startTime  # or latestTime (restart from the newest time folder)
//   libs: []              # extra plugin libraries: bare names or paths
//   threads: 1            # worker threads for the pair wrenches (0 = all cores);
//                         # results are bit-identical for any count (Threads.hpp)
#pragma once

#include "magFoam/Dictionary.hpp"

#include <string>
#include <vector>

namespace mag {

struct ControlDict {
    double startTime = 0;
    double endTime = 1;
    double deltaT = 1e-3;
    double writeInterval = 0.01;
    std::string startFrom = "startTime";
    std::vector<std::string> libs;
    int threads = 1;

    static ControlDict read(const Dict& dict);
};

} // namespace mag
