#include "Solver.hpp"

#include <magFoam/BodyOverlap.hpp>
#include <magFoam/Error.hpp>
#include <magFoam/Log.hpp>
#include <magFoam/MagneticSystem.hpp>
#include <magFoam/RigidBodyBackend.hpp>
#include <magFoam/Threads.hpp>

#include "ImplicitTorque.hpp"
#include "Sleeping.hpp"
#include "StepAudit.hpp"
#include "TimeLoop.hpp"

#include <algorithm>
#include <limits>
#include <sstream>

namespace mag::solver {

namespace {

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

// Everything the writers need at a write time: full wrenches and energies,
// and (`states`) the models' restart files.
void writeResults(ResultsWriter& writer, MagneticSystem& magnets, const std::vector<Body>& bodies,
                  const Vec3& gravity, double t, long step, const std::vector<StateFile>& states,
                  const std::function<void(const WriteRecord&)>& onWrite, const std::vector<char>* asleep) {
    const std::vector<Wrench> w = magnets.wrenches(bodies);
    // A soft body's magnetization in the state is the one its last step was
    // taken with (converged at the step's start, and restarts continue from
    // it bit for bit); energy.csv counts the energy of the written pose, so
    // its magnetic energy is taken with the magnetizations converged there,
    // on a copy, and the induction model's own state (LLG's sub-magnetizations,
    // the next call's start) is put back exactly, so the run does not depend
    // on when it writes.
    double magnetic = 0;
    if (std::any_of(bodies.begin(), bodies.end(), [](const Body& b) { return b.soft(); })) {
        std::ostringstream saved;
        magnets.writeInductionState(saved, bodies);
        std::vector<Body> settled = bodies;
        magnets.converge(settled);
        magnetic = magnets.magneticEnergy(settled, magnets.wrenches(settled));
        if (!saved.str().empty())
            magnets.readInductionState(Dict::fromString(saved.str(), "induction state"), bodies);
    } else {
        magnetic = magnets.magneticEnergy(bodies, w);
    }
    // The surfaces' per-face fields: B of the other bodies at every face centre.
    std::vector<std::vector<Vec3>> faceB(bodies.size());
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        const std::vector<Vec3> centres = faceCentres(bodies[i]);
        faceB[i].assign(centres.size(), Vec3::Zero());
        magnets.field(bodies, centres, faceB[i], {}, {}, &bodies[i]);
    }
    const Energies energies = bodyEnergies(bodies, gravity, magnetic);
    writer.write(t, step, bodies, w, energies, states, faceB, asleep);
    if (onWrite) onWrite(WriteRecord{t, step, bodies, w, energies});
}

void describeRun(const Case& c, const MagneticSystem& magnets, const RigidBodyBackend& backend,
                 const TimeLoop& loop, int threads) {
    const ControlDict& ctl = c.control();
    if (loop.adaptive())
        spdlog::info("magFoam: {} bodies, adaptive steps from {} s (minDeltaT {} s, maxDeltaT {} s) from t = {} to {}, "
                     "{} thread(s)",
                     c.bodies().size(), loop.deltaT(), ctl.minDeltaT, ctl.maxDeltaT, loop.startTime(), loop.endTime(),
                     threads);
    else
        spdlog::info("magFoam: {} bodies, {} steps of {} s from t = {}, {} thread(s)", c.bodies().size(),
                     loop.fixedSteps(), loop.deltaT(), loop.startTime(), threads);
    spdlog::info("  field:      {}", magnets.fieldEvaluator().describe());
    spdlog::info("  induction:  {}", c.hasSoftBodies() ? magnets.inductionModel().describe() : "none (no soft bodies)");
    if (magnets.appliedField().active()) spdlog::info("  applied:    {}", magnets.appliedField().describe());
    spdlog::info("  rigid body: {}", backend.describe());
    if (ctl.implicitTorque)
        spdlog::info("  torque:     implicit in the tilt stiffness (magneticStiffness: implicit)");
}

// Adaptive steps: at most 20 % longer than the last one.
constexpr double kMaxGrowth = 1.2;

} // namespace

void run(Case& c, const RunOptions& options) {
    const int threads = mag::threads();
    MagneticSystem magnets(c);
    std::unique_ptr<RigidBodyBackend> backend = RigidBodyBackend::New(c.rigidBody());
    const Vec3 gravity = c.rigidBody().get<Vec3>("gravity", Vec3::Zero());
    const bool soft = c.hasSoftBodies();
    std::vector<Body>& bodies = c.bodies();
    backend->setup(bodies);

    // Start: from startTime, or from the newest time folder (bodies and models).
    const Start start = startRun(c, bodies, magnets, *backend);
    // Bodies inside each other at the start: named, with how deep; the run goes
    // on (MBM is defined there), but a contact solver will push them apart.
    if (!start.folder)
        warnOverlaps(bodies, (c.dir() / "constant" / "bodies.yaml").string(),
                     "a contact solver pushes them apart at the start, adding kinetic energy");
    if (c.control().implicitTorque && !backend->setTiltStiffness({}))
        throw InputError((c.dir() / "system/controlDict.yaml").string() +
                         ": magneticStiffness: implicit: the rigid-body backend '" + backend->describe() +
                         "' cannot integrate a tilt stiffness; use ODE, or free with integrator: symplecticEuler");
    Sleeping sleeping(c.sleep(), bodies, gravity, magnets.appliedField().timeDependent());
    if (sleeping.enabled() && !backend->canSleep())
        throw InputError((c.dir() / "constant/rigidBody.yaml").string() + ": sleep: the rigid-body backend '" +
                         backend->describe() + "' cannot hold bodies still; remove sleep: or use ODE or free");
    if (start.folder) {
        if (const auto file = *start.folder / "sleep.yaml"; std::filesystem::exists(file))
            sleeping.readState(Dict::fromFile(file), bodies, *backend);
    }
    ControlDict control = c.control();
    if (options.endTime) control.endTime = *options.endTime;
    TimeLoop loop(control, start);
    ResultsWriter writer(c.dir(), start.folder ? std::optional<double>(start.time) : std::nullopt,
                         sleeping.enabled());
    AuditSettings auditSettings = c.control().audit;
    auditSettings.strict = auditSettings.strict || options.strict;
    if (magnets.appliedField().timeDependent()) {
        // A field that changes in time does work on the bodies: their energy may rise.
        spdlog::info("  audit: the applied field changes in time (table:), so the energy check is off");
        auditSettings.energyRise = std::numeric_limits<double>::infinity();
    }
    double lastDeltaT = start.lastDeltaT > 0 ? start.lastDeltaT : c.control().deltaT;
    StepAudit audit(bodies, auditSettings, magnets.fieldEvaluator().forceTolerance(), gravity);
    audit.restoreNetAcceleration(bodies, start.netAcceleration);
    auto write = [&](const std::vector<Body>& state, double t, long step, bool withModels) {
        magnets.setTime(t);
        std::vector<StateFile> states;
        if (withModels) {
            states = loop.adaptive() ? modelStates(magnets, *backend, state, lastDeltaT, audit.netAccelerationState(state))
                                     : modelStates(magnets, *backend, state);
            states.push_back({"sleep.yaml", sleeping.stateText(state)});
        }
        writeResults(writer, magnets, state, gravity, t, step, states, options.onWrite,
                     sleeping.enabled() ? &sleeping.asleep() : nullptr);
    };
    describeRun(c, magnets, *backend, loop, threads);
    if (!start.folder) write(bodies, loop.time(), loop.step(), true);

    auto stopRequested = [&] { return options.stop && *options.stop; };
    RunStatistics stats(loop, soft);
    // The last good per-step state (poses, velocities, magnetizations), to write
    // on a non-finite one; the bodies' fixed models are not copied every step.
    std::vector<BodyState> lastGood(bodies.size());
    while (!loop.done()) {
        std::copy(bodies.begin(), bodies.end(), lastGood.begin());
        const double before = loop.time();
        const long step = loop.step() + 1;

        // Algorithm 1: induction loop (only with soft bodies), then wrenches.
        stats.start(RunStatistics::Phase::magnetic);
        magnets.setTime(before);
        const MagneticSystem::Step magnetic = sleeping.magnetic(magnets, bodies);
        const std::vector<Wrench>& wrenches = magnetic.wrenches;
        // Sleeping bodies whose surroundings changed wake before the step.
        sleeping.wakeBeforeStep(bodies, wrenches, *backend, step, before);
        // The step's length: fixed, or what the motion and stiffness of the
        // awake bodies allow now.
        double proposal = 0.0;
        std::string_view limitedBy, limitingBody; // what set the step, for the progress line
        if (loop.adaptive()) {
            const StepProposal stable =
                sleeping.anyAsleep() ? audit.stableDeltaT(sleeping.awakeView(bodies), wrenches, control.implicitTorque)
                                     : audit.stableDeltaT(bodies, wrenches, control.implicitTorque);
            proposal = std::min(kMaxGrowth * lastDeltaT, stable.deltaT);
            if (stable.deltaT > proposal) limitedBy = "growth";
            else limitedBy = stable.limit, limitingBody = bodies[stable.body].name;
        }
        const double dt = loop.begin(proposal);
        if (loop.adaptive() && dt != proposal) {
            limitingBody = {};
            limitedBy = dt > proposal ? "minDeltaT" : dt >= loop.maxDeltaT() ? "maxDeltaT" : "write time";
        }
        const double t = loop.endOfStep();
        if (soft) writer.writeInduction(t, step, magnetic.induction);
        stats.induction(step, magnetic.induction);

        // The rigid-body step under those wrenches.
        stats.start(RunStatistics::Phase::rigidBody);
        // The last good state (before this step), written for a look and a
        // restart when the step fails; the models hold the bad step's state:
        // bodies.yaml alone. With a non-finite wrench the good state's results
        // cannot be written either (nothing non-finite is), but its restart
        // state can.
        auto writeLastGood = [&] {
            std::vector<Body> good = bodies;
            for (std::size_t i = 0; i < good.size(); ++i) static_cast<BodyState&>(good[i]) = lastGood[i];
            std::string written = "last good state written to " + timeName(before) + "/";
            try {
                write(good, before, step - 1, false);
            } catch (const StateError&) {
                writer.writeStateOnly(before, step - 1, good);
                written += " (its state only: its wrench is not finite)";
            }
            return written;
        };
        if (!firstNonFinite(bodies, &wrenches)) {
            if (control.implicitTorque) backend->setTiltStiffness(tiltStiffnesses(bodies, wrenches));
            try {
                backend->step(bodies, wrenches, dt);
            } catch (const StateError& e) {
                // The engine gave up (ODE's internal checks throw): the bodies
                // may hold part of the step.
                const std::string written = writeLastGood();
                throw StateError(fmt::format("the rigid-body step {} (t = {:.9g} to {:.9g} s) failed: {}; {}", step,
                                             before, t, e.what(), written));
            }
        }
        stats.stepDone();

        if (const Body* bad = firstNonFinite(bodies, &wrenches)) {
            const std::string written = writeLastGood();
            throw StateError("non-finite state or wrench of body '" + bad->name + "' in step " +
                             std::to_string(step) + " (t = " + formatExact(t) + " s); " + written);
        }
        loop.end();
        lastDeltaT = dt;
        sleeping.sleepAfterStep(bodies, wrenches, *backend, dt, step, t);
        if (const auto stop = audit.check(step, t, dt, lastGood, bodies, wrenches, magnets.magneticEnergy(bodies, wrenches))) {
            write(bodies, t, step, true);
            throw StateError(*stop + " (audit.strict; state written to " + timeName(t) + "/)");
        }
        if (loop.isWriteTime() || stopRequested()) write(bodies, t, step, true);
        if (stopRequested()) {
            spdlog::info("Stopped by signal at t = {}; state written to {}/", t, timeName(t));
            break;
        }
        stats.progress(t, step, loop.adaptive() ? dt : 0.0, limitedBy, limitingBody);
    }
    stats.summary();
    audit.summary(bodies);
    sleeping.summary();
    spdlog::info("  rigid body: {}", backend->describe());
    spdlog::info("  field: {}", magnets.fieldEvaluator().describe());
    if (const FieldStats fs = magnets.fieldEvaluator().stats(); !fs.counts.empty()) {
        spdlog::info("  field counters: {}", fs.format());
        for (const std::string& line : fs.pairSampleLines()) spdlog::info("  {}", line);
    }
}

} // namespace mag::solver
