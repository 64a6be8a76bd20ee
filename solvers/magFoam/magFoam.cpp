// magFoam: transient solver for rigid magnets (paper Algorithm 1 + a rigid-
// body backend). Per step: converge induced magnetizations, wrench on every
// body from all others, hand them to the backend, step it; write results at
// write times. Restart with `startFrom: latestTime`; SIGINT/SIGTERM write the
// current state and exit 0; a NaN/inf stops the run with the body and step
// named, after writing the last good state.
#include <magFoam/ArgList.hpp>
#include <magFoam/Case.hpp>
#include <magFoam/Error.hpp>
#include <magFoam/Log.hpp>
#include <magFoam/BodyOverlap.hpp>
#include <magFoam/MagneticSystem.hpp>
#include <magFoam/ResultsWriter.hpp>
#include <magFoam/RigidBodyBackend.hpp>
#include <magFoam/Threads.hpp>

#include <chrono>
#include <cmath>
#include <csignal>

using namespace mag;
using Clock = std::chrono::steady_clock;

namespace {

volatile std::sig_atomic_t stopRequested = 0;
void onSignal(int) { stopRequested = 1; }

double seconds(Clock::time_point since) { return std::chrono::duration<double>(Clock::now() - since).count(); }

// The first body whose state, or wrench if it can move, is not finite.
const Body* firstNonFinite(const std::vector<Body>& bodies, const std::vector<Wrench>* wrenches) {
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        const Body& b = bodies[i];
        bool ok = b.position.allFinite() && b.orientation.coeffs().allFinite() && b.velocity.allFinite() &&
                  b.angularVelocity.allFinite() && b.magnetizationBody.allFinite();
        if (wrenches && !b.fixed) {
            const Wrench& w = (*wrenches)[i];
            ok = ok && w.force.allFinite() && w.torque.allFinite() && w.mechanicalTorque.allFinite();
        }
        if (!ok) return &b;
    }
    return nullptr;
}

// Everything the writers need at a write time: full wrenches and energies.
void writeResults(ResultsWriter& writer, const MagneticSystem& magnets, const std::vector<Body>& bodies,
                  const Vec3& gravity, double t, long step) {
    const std::vector<Wrench> w = magnets.wrenches(bodies);
    double magnetic = 0;
    for (const auto& x : w) magnetic += 0.5 * x.energy;  // each pair is seen from both sides
    writer.write(t, step, bodies, w, bodyEnergies(bodies, gravity, magnetic));
}

// Bodies inside each other at the start: named, with how deep; the run goes on
// (MBM is defined there), but a contact solver will push them apart.
void warnOverlaps(const Case& c, const std::vector<Body>& bodies) {
    for (const BodyOverlap& o : findOverlaps(bodies)) {
        const std::string how = o.depth > 0 ? fmt::format("a vertex {:.3g} m deep", o.depth) : "edges through faces";
        spdlog::warn("bodies '{}' and '{}' overlap at the start ({}; {}): a contact solver pushes them apart, "
                     "adding kinetic energy; check their positions",
                     bodies[o.a].name, bodies[o.b].name, how, (c.dir() / "constant" / "bodies.yaml").string());
    }
}

int run(const ArgList& args) {
    Case c = Case::read(args.caseDir(), args.schemesFile());
    const ControlDict& control = c.control();
    const int threads = setThreads(args, c);
    MagneticSystem magnets(c);
    std::unique_ptr<RigidBodyBackend> backend = RigidBodyBackend::New(c.rigidBody());
    const Vec3 gravity = c.rigidBody().get<Vec3>("gravity", Vec3::Zero());
    std::vector<Body>& bodies = c.bodies();

    // Start: from startTime, or from the newest time folder.
    double t0 = control.startTime;
    long step0 = 0;
    std::optional<double> restartTime;
    if (control.startFrom == "latestTime") {
        if (auto folder = latestTimeFolder(c.dir())) {
            const RestartState s = readState(*folder / "bodies.yaml", bodies);
            t0 = s.time, step0 = s.step, restartTime = s.time;
            spdlog::info("Restarting from {} (step {})", folder->string(), step0);
        }
    }
    if (!restartTime) warnOverlaps(c, bodies);
    backend->setup(bodies);
    ResultsWriter writer(c.dir(), restartTime);

    const double dt = control.deltaT;
    const long nSteps = std::max(0L, std::lround((control.endTime - t0) / dt));
    const long writeEvery = std::max(1L, std::lround(control.writeInterval / dt));
    spdlog::info("magFoam: {} bodies, {} steps of {} s from t = {}, {} thread(s)", bodies.size(), nSteps, dt, t0,
                 threads);
    spdlog::info("  field:      {}", magnets.fieldEvaluator().describe());
    spdlog::info("  dipole sum: {}", magnets.farField().describe());
    spdlog::info("  induction:  {}", c.hasSoftBodies() ? magnets.inductionModel().describe() : "none (no soft bodies)");
    spdlog::info("  rigid body: {}", backend->describe());
    if (!restartTime) writeResults(writer, magnets, bodies, gravity, t0, step0);

    std::signal(SIGINT, onSignal);
    std::signal(SIGTERM, onSignal);
    const auto start = Clock::now();
    auto lastReport = start;
    double magneticSeconds = 0, rigidSeconds = 0;
    long unconvergedSteps = 0, k = 0;
    // Induction statistics: per step to induction.csv, summed for the log lines.
    const bool soft = c.hasSoftBodies();
    long sweepsTotal = 0, sweepsSinceReport = 0, stepsSinceReport = 0;
    int sweepsMax = 0;
    std::vector<Body> lastGood;  // kept to write on a non-finite state; reused storage
    for (k = 1; k <= nSteps; ++k) {
        const long step = step0 + k;
        lastGood = bodies;

        // Algorithm 1: induction loop (only with soft bodies), then wrenches.
        const auto tm = Clock::now();
        const MagneticSystem::Step magnetic = magnets.step(bodies);
        const InductionReport& ind = magnetic.induction;
        if (soft) {
            writer.writeInduction(t0 + k * dt, step, ind);
            sweepsTotal += ind.iterations, sweepsSinceReport += ind.iterations, ++stepsSinceReport;
            sweepsMax = std::max(sweepsMax, ind.iterations);
        }
        if (!ind.converged) {
            ++unconvergedSteps;
            std::string names;
            for (const auto& n : ind.unconverged) names += " " + n;
            spdlog::warn("step {}: induction not converged after {} iterations (residual {:.3g}):{}", step,
                         ind.iterations, ind.residual, names);
        }
        const std::vector<Wrench>& wrenches = magnetic.wrenches;
        magneticSeconds += seconds(tm);

        const auto tr = Clock::now();
        if (!firstNonFinite(bodies, &wrenches)) backend->step(bodies, wrenches, dt);
        rigidSeconds += seconds(tr);

        if (const Body* bad = firstNonFinite(bodies, &wrenches)) {
            const double tGood = t0 + (k - 1) * dt;
            writeResults(writer, magnets, lastGood, gravity, tGood, step - 1);
            throw StateError("non-finite state or wrench of body '" + bad->name + "' in step " +
                             std::to_string(step) + " (t = " + std::to_string(t0 + k * dt) +
                             " s); last good state written to " + timeName(tGood) + "/");
        }

        const double t = t0 + k * dt;
        if (k % writeEvery == 0 || k == nSteps || stopRequested) writeResults(writer, magnets, bodies, gravity, t, step);
        if (stopRequested) {
            spdlog::info("Stopped by signal at t = {}; state written to {}/", t, timeName(t));
            break;
        }
        if (seconds(lastReport) > 5.0) {
            lastReport = Clock::now();
            const double rate = k / seconds(start);
            std::string induction;
            if (soft && stepsSinceReport > 0)
                induction = fmt::format("  induction {:.1f} sweeps/step", double(sweepsSinceReport) / stepsSinceReport);
            sweepsSinceReport = stepsSinceReport = 0;
            spdlog::info("t = {:.6g} s  step {}  {:.1f} steps/s  ETA {:.0f} s{}", t, step, rate, (nSteps - k) / rate,
                         induction);
        }
    }
    const long done = std::min(k, nSteps);
    if (done > 0)
        spdlog::info("End: {} steps in {:.2f} s; ms per step: magnetic {:.3f}, rigid body {:.3f}{}", done,
                     seconds(start), 1e3 * magneticSeconds / done, 1e3 * rigidSeconds / done,
                     unconvergedSteps ? "; induction unconverged in " + std::to_string(unconvergedSteps) + " steps"
                                      : std::string());
    if (soft && done > 0)
        spdlog::info("  induction: {:.2f} sweeps per step on average, {} at most (postProcessing/induction.csv)",
                     double(sweepsTotal) / done, sweepsMax);
    spdlog::info("  field: {}", magnets.fieldEvaluator().describe());
    return 0;
}

} // namespace

int main(int argc, char** argv) {
    ArgList args("magFoam", "Transient solver: rigid magnets moving, colliding and sticking (paper Algorithm 1).");
    if (!args.parse(argc, argv)) return args.exitCode();
    return runGuarded(args, run);
}
