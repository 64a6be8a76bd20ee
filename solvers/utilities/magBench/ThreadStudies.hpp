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

// Boundary samples that the evaluator of dictionary `field` takes on a target of
// `shape` close to another body of that shape (bounding spheres 0.1 radii deep
// in each other: a near pair for any switch): one interaction, read from the evaluator's "boundarySamples" counters
// (its own or its sub-models'); 0 when it samples no boundary.
inline std::size_t boundarySamples(const Dict& field, const std::shared_ptr<const Shape>& shape) {
    const auto evaluator = FieldEvaluator::New(field);
    Body source, target;
    for (Body* b : {&source, &target}) {
        b->shape = shape;
        b->material.density = 1;
        b->magnetizationBody = Vec3(0, 0, 1);
    }
    source.name = "source", target.name = "target";
    target.position = Vec3(1.9 * shape->boundingRadius, 0, 0);
    (void)evaluator->interaction(source, target);
    std::uint64_t n = 0;
    const std::string key = "boundarySamples";
    for (const auto& [name, count] : evaluator->stats().counts)
        if (name.size() >= key.size() && name.compare(name.size() - key.size(), key.size(), key) == 0) n += count;
    return static_cast<std::size_t>(n);
}

} // namespace mag::bench
