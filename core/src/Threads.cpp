#include "magFoam/Threads.hpp"

#include "magFoam/ArgList.hpp"
#include "magFoam/Case.hpp"
#include "magFoam/Log.hpp"

#include <omp.h>

#include <algorithm>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <limits>

namespace mag {

namespace {

// One thread until an app sets the count (controlDict's default is 1), not
// OpenMP's all cores: a library call, a test or an accuracy timing then never
// spreads over the machine unasked. OMP_NUM_THREADS, if set, is kept.
const bool oneThreadByDefault = [] {
    if (!std::getenv("OMP_NUM_THREADS")) omp_set_num_threads(1);
    return true;
}();

} // namespace

int setThreads(int n) {
    if (n > maxThreads()) {
        spdlog::info("threads {} capped to {} ({} cores available to this process)", n, maxThreads(),
                     availableCores());
        n = maxThreads();
    }
    omp_set_num_threads(n > 0 ? n : availableCores());
    return threads();
}

int setThreads(const ArgList& args, const Case& c) {
    if (auto n = args.threads()) return setThreads(*n);
    // control() fails on a missing controlDict; magForces does not need one.
    const bool hasControl = std::filesystem::exists(c.dir() / "system/controlDict.yaml");
    return setThreads(hasControl ? c.control().threads : 1);
}

int threads() { return omp_get_max_threads(); }

int availableCores() { return omp_get_num_procs(); }
int maxThreads() { return std::max(availableCores(), 64); }

void parallelFor(std::size_t n, const std::function<void(std::size_t)>& body, std::size_t grain) {
    if (n < 2 || omp_get_max_threads() < 2 || omp_in_parallel()) {
        for (std::size_t i = 0; i < n; ++i) body(i);
        return;
    }
    // An exception must not leave an OpenMP region: keep the lowest index's,
    // so the error reported does not depend on the schedule.
    std::exception_ptr error;
    std::size_t errorIndex = std::numeric_limits<std::size_t>::max();
    const auto count = static_cast<long long>(n);
    const int chunk = static_cast<int>(std::clamp<std::size_t>(grain, 1, 1 << 20));
#pragma omp parallel for schedule(dynamic, chunk)
    for (long long i = 0; i < count; ++i) {
        try {
            body(static_cast<std::size_t>(i));
        } catch (...) {
#pragma omp critical(magParallelForError)
            if (static_cast<std::size_t>(i) < errorIndex) {
                errorIndex = static_cast<std::size_t>(i);
                error = std::current_exception();
            }
        }
    }
    if (error) std::rethrow_exception(error);
}

} // namespace mag
