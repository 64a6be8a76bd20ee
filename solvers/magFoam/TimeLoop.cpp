#include "TimeLoop.hpp"

#include <magFoam/Dictionary.hpp>
#include <magFoam/Error.hpp>
#include <magFoam/Log.hpp>
#include <magFoam/Parts.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

namespace mag::solver {

namespace {

// The models' files in a time folder (ResultsWriter.hpp).
constexpr const char* kInductionFile = "induction.yaml";
constexpr const char* kRigidBodyFile = "rigidBody.yaml";
constexpr const char* kTimeStepFile = "timeStep.yaml";

template <class Clock> double seconds(typename Clock::time_point since) {
    return std::chrono::duration<double>(Clock::now() - since).count();
}

// A time folder a restart can continue from: its bodies.yaml (read into a
// copy of the bodies) is of the folder's own time, and the model files beside
// it read as dictionaries. Throws InputError saying what is wrong.
RestartState checkTimeFolder(const std::filesystem::path& folder, std::vector<Body> bodies) {
    const RestartState r = readState(folder / "bodies.yaml", bodies);
    if (timeName(r.time) != folder.filename().string())
        throw InputError((folder / "bodies.yaml").string() + ": holds the state of t = " + formatExact(r.time) +
                         " s, not of its folder's time");
    // Every other state file beside it (the models', timeStep.yaml, sleep.yaml).
    std::vector<std::filesystem::path> files;
    for (const auto& entry : std::filesystem::directory_iterator(folder))
        if (entry.path().extension() == ".yaml" && entry.path().filename() != "bodies.yaml") files.push_back(entry);
    std::sort(files.begin(), files.end());
    for (const auto& file : files) {
        std::error_code ec;
        if (std::filesystem::file_size(file, ec) == 0 && !ec)
            throw InputError(file.string() + ": the file is empty (a write that was cut off?)");
        (void)Dict::fromFile(file);
    }
    return r;
}

} // namespace

Start startRun(const Case& c, std::vector<Body>& bodies, MagneticSystem& magnets, RigidBodyBackend& backend) {
    const ControlDict& control = c.control();
    Start s;
    s.time = control.startTime;
    if (control.startFrom != "latestTime") return s;
    // The newest time folder that is complete and readable; the ones skipped
    // are named with the reason (a run cut by a crash or a full disk).
    std::optional<std::filesystem::path> folder;
    std::string skipped;
    for (const auto& candidate : timeFolders(c.dir())) {
        try {
            checkTimeFolder(candidate, bodies);
            folder = candidate;
            break;
        } catch (const InputError& e) {
            spdlog::warn("Restart: skipping time folder {}/: {}", candidate.filename().string(), e.what());
            skipped += "\n  " + candidate.filename().string() + "/: " + e.what();
        }
    }
    if (!folder && !skipped.empty())
        throw InputError((c.dir() / "system/controlDict.yaml").string() +
                         ": startFrom: latestTime, but no time folder can be restarted from:" + skipped +
                         "\n(remove them, or set startFrom: startTime to start anew)");
    if (!folder) return s;
    // Permanent magnetizations come from the dictionaries, read anew as in
    // OpenFOAM (a changed Br or direction takes effect); the state's value is
    // what the run had, so an unchanged case continues bit for bit.
    const std::vector<Body> fromDictionaries = bodies;
    const RestartState r = readState(*folder / "bodies.yaml", bodies);
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        if (const auto& compound = bodies[i].compound) {
            // Each permanent part's from constant/, each soft part's from the state.
            for (std::size_t k = 0; k < compound->parts.size(); ++k) {
                if (compound->parts[k].material.soft()) continue;
                const Vec3 dict = fromDictionaries[i].partMagnetization[k];
                if (bodies[i].partMagnetization[k] != dict)
                    spdlog::info("Restart: part {} of body '{}' takes its magnetization from constant/ ({} A/m, part "
                                 "frame), not the state's ({} A/m)",
                                 k, bodies[i].name, formatExact(dict), formatExact(bodies[i].partMagnetization[k]));
                bodies[i].partMagnetization[k] = dict;
            }
            bodies[i].magnetizationBody = meanMagnetization(*compound, bodies[i].partMagnetization);
            continue;
        }
        if (bodies[i].soft()) continue;
        const Vec3 dict = fromDictionaries[i].magnetizationBody;
        if (bodies[i].magnetizationBody != dict)
            spdlog::info("Restart: body '{}' takes its magnetization from constant/ ({} A/m, body frame), not the "
                         "state's ({} A/m)",
                         bodies[i].name, formatExact(dict), formatExact(bodies[i].magnetizationBody));
        bodies[i].magnetizationBody = dict;
    }
    s.time = r.time, s.step = r.step, s.folder = folder;
    spdlog::info("Restarting from {} (step {})", folder->string(), s.step);
    // The bodies were set from outside; then what the models carried.
    backend.setState(bodies);
    if (const auto file = *folder / kInductionFile; std::filesystem::exists(file))
        magnets.readInductionState(Dict::fromFile(file), bodies);
    if (const auto file = *folder / kRigidBodyFile; std::filesystem::exists(file))
        backend.readState(Dict::fromFile(file), bodies);
    if (const auto file = *folder / kTimeStepFile; std::filesystem::exists(file)) {
        const Dict d = Dict::fromFile(file);
        s.lastDeltaT = d.get<double>("deltaT");
        if (!(s.lastDeltaT > 0)) d.fail("deltaT", "the last step's length must be > 0 (seconds)");
        if (d.has("netAcceleration")) {
            const Dict n = d.sub("netAcceleration");
            for (const std::string& name : n.keys()) {
                if (std::none_of(bodies.begin(), bodies.end(), [&](const Body& b) { return b.name == name; }))
                    n.fail(name, "no body of that name in constant/bodies.yaml");
                const auto v = n.get<std::vector<double>>(name);
                if (v.size() != 6 || !std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); }))
                    n.fail(name, "6 finite numbers expected: the body's acceleration (m/s^2) and angular "
                                 "acceleration (rad/s^2) over the last step");
                s.netAcceleration.push_back({name, {v[0], v[1], v[2], v[3], v[4], v[5]}});
            }
        }
        d.reportUnused();
    }
    return s;
}

std::vector<StateFile> modelStates(const MagneticSystem& magnets, const RigidBodyBackend& backend,
                                   const std::vector<Body>& bodies, double lastDeltaT,
                                   const std::string& proposalState) {
    std::ostringstream ind, rb;
    magnets.writeInductionState(ind, bodies);
    backend.writeState(rb, bodies);
    const std::string dt = lastDeltaT > 0 ? "# adaptive steps: the last step's length (s)\ndeltaT: " +
                                                formatExact(lastDeltaT) + "\n" + proposalState
                                          : std::string();
    return {{kInductionFile, ind.str()}, {kRigidBodyFile, rb.str()}, {kTimeStepFile, dt}};
}

TimeLoop::TimeLoop(const ControlDict& control, const Start& start)
    : adaptive_(control.adjustTimeStep), dt_(control.deltaT), startTime_(start.time), endTime_(control.endTime),
      time_(start.time), minDt_(control.minDeltaT), maxDt_(control.maxDeltaT), axis0_(control.startTime),
      writeInterval_(control.writeInterval), start_(start.step), step_(start.step) {
    if (adaptive_ && start.lastDeltaT > 0) dt_ = start.lastDeltaT;
    // On the axis of startTime (a fresh start, or a restart with the same
    // startTime and deltaT): the same times, bit for bit, as one long run.
    if (control.startTime + static_cast<double>(start.step) * dt_ == start.time)
        baseTime_ = control.startTime, baseStep_ = 0;
    else
        baseTime_ = start.time, baseStep_ = start.step;
    // controlDict bounds the run to ControlDict::maxSteps steps; a restart
    // time is read from its folder and must keep to the same bound.
    const double steps = (control.endTime - start.time) / dt_;
    if (!adaptive_ && !(std::abs(steps) <= ControlDict::maxSteps))
        throw InputError(fmt::format("restart time {} s is {:.6g} steps of {} s from endTime {} s; at most 1e12",
                                     start.time, steps, dt_, control.endTime));
    const long n = std::max(0L, std::lround(std::clamp(steps, -1e15, 1e15)));
    lastStep_ = start.step + n;
    // Writing less often than once in 1e15 steps is never writing but at the end.
    writeEvery_ = std::max(1L, std::lround(std::min(control.writeInterval / dt_, 1e15)));
}

bool TimeLoop::done() const { return adaptive_ ? !(time_ < endTime_) : step_ >= lastStep_; }

double TimeLoop::begin(double proposal) {
    if (!adaptive_) return dt_;
    // The next write time on the axis startTime + k writeInterval after now
    // (a time within 1e-9 of a step of one counts as on it), or endTime.
    const double k = std::floor((time_ - axis0_) / writeInterval_ + 1e-9) + 1.0;
    target_ = std::min(axis0_ + k * writeInterval_, endTime_);
    const double remaining = target_ - time_;
    dt_ = std::clamp(proposal > 0 ? proposal : dt_, minDt_, maxDt_);
    onTarget_ = dt_ >= remaining * (1.0 - 1e-9);
    if (onTarget_) dt_ = remaining;
    else if (dt_ > 0.5 * remaining) dt_ = 0.5 * remaining; // no sliver before the write time
    return dt_;
}

double TimeLoop::endOfStep() const {
    if (!adaptive_) return baseTime_ + static_cast<double>(step_ + 1 - baseStep_) * dt_;
    return onTarget_ ? target_ : time_ + dt_;
}

void TimeLoop::end() {
    ++step_;
    if (!adaptive_) {
        time_ = baseTime_ + static_cast<double>(step_ - baseStep_) * dt_;
        write_ = step_ % writeEvery_ == 0 || step_ == lastStep_;
        return;
    }
    time_ = onTarget_ ? target_ : time_ + dt_;
    write_ = onTarget_;
}

RunStatistics::RunStatistics(const TimeLoop& loop, bool softBodies)
    : startTime_(loop.startTime()), endTime_(loop.endTime()), soft_(softBodies), start_(Clock::now()),
      lastReport_(start_) {}

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

void RunStatistics::progress(double t, long step, double deltaT, std::string_view limitedBy,
                             std::string_view body) {
    if (deltaT > 0 && !limitedBy.empty()) {
        auto it = limits_.find(limitedBy);
        if (it == limits_.end()) it = limits_.emplace(std::string(limitedBy), Limit{}).first;
        ++it->second.steps;
        it->second.time += deltaT;
        if (!body.empty()) {
            // Found without a copy of the name: no allocation per step.
            auto& bodies = it->second.bodies;
            auto b = bodies.find(body);
            if (b == bodies.end()) b = bodies.emplace(std::string(body), 0).first;
            ++b->second;
        }
    }
    if (seconds<Clock>(lastReport_) <= 5.0) return;
    lastReport_ = Clock::now();
    const double wall = seconds<Clock>(start_), rate = done_ / wall;
    const double eta = t > startTime_ ? (endTime_ - t) * wall / (t - startTime_) : 0.0;
    std::string induction;
    if (soft_ && stepsSinceReport_ > 0)
        induction = fmt::format("  induction {:.1f} sweeps/step", double(sweepsSinceReport_) / stepsSinceReport_);
    sweepsSinceReport_ = stepsSinceReport_ = 0;
    std::string dt = deltaT > 0 ? fmt::format("  deltaT {:.3g} s", deltaT) : std::string();
    if (deltaT > 0 && !limitedBy.empty())
        dt += body.empty() ? fmt::format(" ({})", limitedBy) : fmt::format(" ({}: {})", body, limitedBy);
    spdlog::info("t = {:.6g} s  step {}{}  {:.1f} steps/s  ETA {:.0f} s{}", t, step, dt, rate, eta, induction);
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
    if (limits_.empty()) return;
    // Most steps first; each with the body that set it most often.
    std::vector<std::pair<std::string, const Limit*>> order;
    for (const auto& [name, limit] : limits_) order.emplace_back(name, &limit);
    std::stable_sort(order.begin(), order.end(),
                     [](const auto& a, const auto& b) { return a.second->steps > b.second->steps; });
    std::string line;
    for (const auto& [name, limit] : order) {
        std::string most;
        long mostSteps = 0;
        for (const auto& [body, n] : limit->bodies)
            if (n > mostSteps) most = body, mostSteps = n;
        line += fmt::format("{}{} {} ({:.3g} s{})", line.empty() ? "" : ", ", name, limit->steps, limit->time,
                            most.empty() ? "" : fmt::format("; {} in {}", most, mostSteps));
    }
    spdlog::info("  steps set by: {}", line);
}

} // namespace mag::solver
