// Worker threads (OpenMP inside libmagCore; plugins and apps need no OpenMP
// flags of their own).
//
//   threads: 1              # system/controlDict.yaml; 0 = all cores
//   magFoam -threads 4      # overrides the controlDict
//
// Every parallel loop has a fixed work partition and reduces its partial
// results in a fixed order, so results are bit-identical for any thread count.
#pragma once

#include <cstddef>
#include <functional>

namespace mag {

class ArgList;
class Case;

// Set the worker count for parallelFor (0 = all cores); returns the count now
// in effect. A count above maxThreads() is capped to it, with a note in the
// log: tens of thousands of threads exhaust what OpenMP can start (their
// stacks, the process's thread limit) and crash it. Until it is called the count is 1 (or OMP_NUM_THREADS).
int setThreads(int n);

// -threads N if given, else the case's controlDict `threads` (1 without a
// controlDict); sets it and returns the count in effect.
int setThreads(const ArgList& args, const Case& c);

// Worker count in effect, and the cores this process may use.
int threads();
int availableCores();
// The most setThreads allows: the cores, or 64 where there are fewer (a few
// threads beyond the cores are harmless, and the tests of bit-identical
// results use 3 on any machine).
int maxThreads();

// Run body(i) for every i in [0, n). In parallel (dynamic schedule, `grain`
// indices at a time) unless n < 2, one thread is set, or the caller already
// runs inside a parallel loop (nested loops run serially in their worker). The
// first exception by index is rethrown after all indices ran.
void parallelFor(std::size_t n, const std::function<void(std::size_t)>& body, std::size_t grain = 1);

} // namespace mag
