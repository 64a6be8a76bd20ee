// Shared pieces of the timing studies table1, table2 and scaling: the thread
// counts to time, the thread count restored afterwards, robust timing, the
// boundary sample count.
#pragma once

#include "BenchCommon.hpp"

#include <magFoam/Body.hpp>
#include <magFoam/Dictionary.hpp>
#include <magFoam/FieldEvaluator.hpp>
#include <magFoam/Threads.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <vector>

namespace mag::bench {

// `threads: [1, 0]` of the study (0 = all cores), each count once, in order.
inline std::vector<int> threadCounts(const Dict& study) {
    std::vector<int> out;
    for (double t : study.get<std::vector<double>>("threads", {1, 0})) {
        if (!(t >= 0) || t != std::floor(t))
            study.fail("threads", "thread counts must be integers >= 0 (0 = all cores)");
        const int n = t == 0 ? availableCores() : static_cast<int>(t);
        if (std::find(out.begin(), out.end(), n) == out.end()) out.push_back(n);
    }
    return out;
}

// The studies change the thread count; the next study gets the app's back.
struct RestoreThreads {
    int n = threads();
    ~RestoreThreads() { setThreads(n); }
};

// Boundary samples the evaluator of dictionary `field` takes on `shape` (a
// hybrid's: its near model's, MBM by default); 0 when it samples no boundary
// (FieldEvaluator::boundarySamples).
inline std::size_t mbmSamples(const Dict& field, const Shape& shape) {
    const std::string type = field.get<std::string>("type");
    if (type == "hybrid") {
        const Dict near = field.has("near") ? field.sub("near") : Dict::fromString("type: MBM\n", "hybrid near");
        return mbmSamples(near, shape);
    }
    return FieldEvaluator::New(field)->boundarySamples(shape);
}

} // namespace mag::bench
