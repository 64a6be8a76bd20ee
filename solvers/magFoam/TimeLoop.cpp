#include "TimeLoop.hpp"

#include <magFoam/Dictionary.hpp>
#include <magFoam/Log.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

namespace mag::solver {

namespace {

// The models' files in a time folder (ResultsWriter.hpp).
constexpr const char* kInductionFile = "induction.yaml";
constexpr const char* kRigidBodyFile = "rigidBody.yaml";

template <class Clock> double seconds(typename Clock::time_point since) {
    return std::chrono::duration<double>(Clock::now() - since).count();
}

} // namespace

Start startRun(const Case& c, std::vector<Body>& bodies, InductionModel& induction, RigidBodyBackend& backend) {
    const ControlDict& control = c.control();
    Start s;
    s.time = control.startTime;
    if (control.startFrom != "latestTime") return s;
    const auto folder = latestTimeFolder(c.dir());
    if (!folder) return s;
    const RestartState r = readState(*folder / "bodies.yaml", bodies);
    s.time = r.time, s.step = r.step, s.folder = folder;
    spdlog::info("Restarting from {} (step {})", folder->string(), s.step);
    // The bodies were set from outside; then what the models carried.
    backend.setState(bodies);
    if (const auto file = *folder / kInductionFile; std::filesystem::exists(file))
        induction.readState(Dict::fromFile(file), bodies);
    if (const auto file = *folder / kRigidBodyFile; std::filesystem::exists(file))
        backend.readState(Dict::fromFile(file), bodies);
    return s;
}

std::vector<StateFile> modelStates(const InductionModel& induction, const RigidBodyBackend& backend,
                                   const std::vector<Body>& bodies) {
    std::ostringstream ind, rb;
    induction.writeState(ind, bodies);
    backend.writeState(rb, bodies);
    return {{kInductionFile, ind.str()}, {kRigidBodyFile, rb.str()}};
}

TimeLoop::TimeLoop(const ControlDict& control, const Start& start)
    : dt_(control.deltaT), startTime_(start.time) {
    // On the axis of startTime (a fresh start, or a restart with the same
    // startTime and deltaT): the same times, bit for bit, as one long run.
    if (control.startTime + static_cast<double>(start.step) * dt_ == start.time)
        baseTime_ = control.startTime, baseStep_ = 0;
    else
        baseTime_ = start.time, baseStep_ = start.step;
    const long n = std::max(0L, std::lround((control.endTime - start.time) / dt_));
    firstStep_ = start.step + 1;
    lastStep_ = start.step + n;
    writeEvery_ = std::max(1L, std::lround(control.writeInterval / dt_));
}

RunStatistics::RunStatistics(const TimeLoop& loop, bool softBodies)
    : steps_(loop.steps()), soft_(softBodies), start_(Clock::now()), lastReport_(start_) {}

void RunStatistics::stopTimer() {
    if (!phase_) return;
    (*phase_ == Phase::magnetic ? magneticSeconds_ : rigidSeconds_) += seconds<Clock>(phaseStart_);
    phase_.reset();
}

void RunStatistics::start(Phase phase) {
    stopTimer();
    phase_ = phase;
    phaseStart_ = Clock::now();
}

void RunStatistics::stepDone() {
    stopTimer();
    ++done_;
}

void RunStatistics::induction(long step, const InductionReport& ind) {
    if (soft_) {
        sweepsTotal_ += ind.iterations, sweepsSinceReport_ += ind.iterations, ++stepsSinceReport_;
        sweepsMax_ = std::max(sweepsMax_, ind.iterations);
    }
    if (!ind.converged) {
        ++unconvergedSteps_;
        std::string names;
        for (const auto& n : ind.unconverged) names += " " + n;
        spdlog::warn("step {}: induction not converged after {} iterations (residual {:.3g}):{}", step,
                     ind.iterations, ind.residual, names);
    }
}

void RunStatistics::progress(double t, long step) {
    if (seconds<Clock>(lastReport_) <= 5.0) return;
    lastReport_ = Clock::now();
    const double rate = done_ / seconds<Clock>(start_);
    std::string induction;
    if (soft_ && stepsSinceReport_ > 0)
        induction = fmt::format("  induction {:.1f} sweeps/step", double(sweepsSinceReport_) / stepsSinceReport_);
    sweepsSinceReport_ = stepsSinceReport_ = 0;
    spdlog::info("t = {:.6g} s  step {}  {:.1f} steps/s  ETA {:.0f} s{}", t, step, rate, (steps_ - done_) / rate,
                 induction);
}

void RunStatistics::summary() const {
    if (done_ == 0) return;
    spdlog::info("End: {} steps in {:.2f} s; ms per step: magnetic {:.3f}, rigid body {:.3f}{}", done_,
                 seconds<Clock>(start_), 1e3 * magneticSeconds_ / done_, 1e3 * rigidSeconds_ / done_,
                 unconvergedSteps_ ? "; induction unconverged in " + std::to_string(unconvergedSteps_) + " steps"
                                   : std::string());
    if (soft_)
        spdlog::info("  induction: {:.2f} sweeps per step on average, {} at most (postProcessing/induction.csv)",
                     double(sweepsTotal_) / done_, sweepsMax_);
}

} // namespace mag::solver
