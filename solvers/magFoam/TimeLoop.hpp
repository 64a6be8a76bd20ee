// The bookkeeping around magFoam's time loop, so that magFoam.cpp holds the
// paper's Algorithm 1 and the rigid-body step only (docs/architecture.md):
// - where the run starts: startTime, or (startFrom: latestTime) the newest
//   time folder, read back into the bodies and the models' own state
//   (<time>/induction.yaml, <time>/rigidBody.yaml: ResultsWriter.hpp);
// - the time axis: the steps of the run, their times, which are written;
// - the model state files written beside bodies.yaml;
// - the run statistics of the log: timings, induction sweeps and warnings,
//   progress lines, the end summary.
#pragma once

#include <magFoam/Body.hpp>
#include <magFoam/Case.hpp>
#include <magFoam/ControlDict.hpp>
#include <magFoam/InductionModel.hpp>
#include <magFoam/MagneticSystem.hpp>
#include <magFoam/ResultsWriter.hpp>
#include <magFoam/RigidBodyBackend.hpp>

#include <array>
#include <chrono>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace mag::solver {

// The state the run starts from: time and step number of the bodies' state,
// and the time folder it was read from (none at a fresh start).
struct Start {
    double time = 0;
    long step = 0;
    std::optional<std::filesystem::path> folder;
    double lastDeltaT = 0; // adaptive steps: the last step's length (0: none)
    // Adaptive steps: the bodies' accelerations over the last step, contacts
    // included (linear m/s^2, angular rad/s^2; StepAudit::restoreNetAcceleration).
    std::vector<std::pair<std::string, std::array<double, 6>>> netAcceleration;
};

// startTime, or with startFrom: latestTime the newest time folder: its
// bodies.yaml into `bodies`, backend.setState(bodies), then each model's
// file, where present, to its readState. Logs "Restarting from ...".
Start startRun(const Case& c, std::vector<Body>& bodies, MagneticSystem& magnets, RigidBodyBackend& backend);

// The models' restart files for ResultsWriter::write (empty text: no state),
// and with adaptive steps the last step's length and what the next proposal
// carries over (`proposalState`, StepAudit::netAccelerationState) in
// timeStep.yaml.
std::vector<StateFile> modelStates(const MagneticSystem& magnets, const RigidBodyBackend& backend,
                                   const std::vector<Body>& bodies, double lastDeltaT = 0,
                                   const std::string& proposalState = {});

// Steps are numbered from startTime (step 0) on, also across restarts.
// Fixed steps (the default): step n ends at time startTime + n deltaT, and is
// written when n is a multiple of writeInterval / deltaT, or the last step of
// the run. A restart whose time is not on that axis (deltaT or startTime
// changed) starts a new one at its time.
// Adaptive steps (adjustTimeStep: true, docs/dynamics.md#adaptive-time-step):
// each step's length is proposed by the solver from the bodies' motion and
// magnetic stiffness, limited to [minDeltaT, maxDeltaT] and shortened so that
// a step ends exactly on every write time (startTime + k writeInterval) and on
// endTime; the step before one is halved rather than leaving a sliver.
class TimeLoop {
public:
    TimeLoop(const ControlDict& control, const Start& start);

    bool adaptive() const { return adaptive_; }
    bool done() const;
    // Begin the next step and return its length: deltaT, or (adaptive) the
    // proposal limited as above.
    double begin(double proposal = 0);
    // The step begun is done: its number and end time become current.
    void end();
    double endOfStep() const;                 // the end time of the step begun
    long step() const { return step_; }       // the last step ended
    double time() const { return time_; }     // at the end of the last step ended
    double deltaT() const { return dt_; }     // of the step begun (or the last)
    bool isWriteTime() const { return write_; } // the step just ended is written
    double startTime() const { return startTime_; }
    double maxDeltaT() const { return maxDt_; }
    double endTime() const { return endTime_; }
    long fixedSteps() const { return lastStep_ - start_; } // fixed steps only

private:
    bool adaptive_;
    double dt_, startTime_, endTime_, baseTime_, time_, minDt_, maxDt_, axis0_, writeInterval_;
    long baseStep_, start_, lastStep_, writeEvery_, step_;
    bool write_ = false, onTarget_ = false;
    double target_ = 0;
};

// Timings, induction statistics and the log lines about the run's progress.
class RunStatistics {
public:
    enum class Phase { magnetic, rigidBody };
    RunStatistics(const TimeLoop& loop, bool softBodies);

    // Time the phases of a step: start(magnetic) ... start(rigidBody) ... stepDone().
    void start(Phase phase);
    void stepDone();
    // A step's induction report: summed for the log; warns when unconverged.
    void induction(long step, const InductionReport& report);
    // Every 5 s: "t = ... s  step ...  steps/s  ETA ... s" (+ the step's
    // length with adaptive steps and what set it, "(body: criterion)" or
    // "(growth)" etc., + induction sweeps per step).
    void progress(double t, long step, double deltaT = 0, std::string_view limitedBy = {},
                  std::string_view body = {});
    // "End: ... steps in ... s; ms per step: ..." and the induction summary;
    // with adaptive steps, how many steps (and how much simulated time) each
    // criterion set, and the body that set it most often.
    void summary() const;

private:
    using Clock = std::chrono::steady_clock;
    void stopTimer();

    const double startTime_, endTime_;
    const bool soft_;
    Clock::time_point start_, lastReport_, phaseStart_;
    std::optional<Phase> phase_;
    double magneticSeconds_ = 0, rigidSeconds_ = 0;
    long done_ = 0, unconvergedSteps_ = 0;
    long sweepsTotal_ = 0, sweepsSinceReport_ = 0, stepsSinceReport_ = 0;
    int sweepsMax_ = 0;
    // Adaptive steps: per criterion, steps, simulated time and steps per body.
    struct Limit {
        long steps = 0;
        double time = 0;
        std::map<std::string, long, std::less<>> bodies;
    };
    std::map<std::string, Limit, std::less<>> limits_;
};

} // namespace mag::solver
