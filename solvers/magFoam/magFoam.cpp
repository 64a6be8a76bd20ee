// magFoam: transient solver for rigid magnets (paper Algorithm 1 + a rigid-
// body backend). Per step: converge induced magnetizations, wrench on every
// body from all others, hand them to the backend, step it; write results at
// write times. Restart with `startFrom: latestTime`: the time folder holds
// the bodies and the models' own state, so a restart continues bit for bit;
// SIGINT/SIGTERM write the current state and exit 0; a NaN/inf stops the run
// with the body and step named, after writing the last good state. The loop
// itself: Solver.hpp (shared with the Python module); where the run starts,
// its time axis and its log statistics: TimeLoop.hpp.
#include <magFoam/ArgList.hpp>
#include <magFoam/Case.hpp>
#include <magFoam/Threads.hpp>

#include "Solver.hpp"

#include <csignal>

using namespace mag;

namespace {

volatile std::sig_atomic_t stopRequested = 0;
void onSignal(int) { stopRequested = 1; }

int run(const ArgList& args) {
    Case c = Case::read(args.caseDir(), args.schemesFile());
    setThreads(args, c);
    std::signal(SIGINT, onSignal);
    std::signal(SIGTERM, onSignal);
    solver::RunOptions options;
    options.strict = args.found("strict");
    options.stop = &stopRequested;
    solver::run(c, options);
    return 0;
}

} // namespace

int main(int argc, char** argv) {
    ArgList args("magFoam", "Transient solver: rigid magnets moving, colliding and sticking (paper Algorithm 1).");
    args.withThreads().withSchemes();
    args.option("strict", "", "stop the run when the energy and motion audit warns (controlDict audit.strict)");
    args.outputs(R"(  postProcessing/bodies.csv   one row per body and write time, world frame:
      time [s], body, x y z [m] (centre of mass), qw qx qy qz [-] (body to world),
      vx vy vz [m/s], wx wy wz [rad/s], Fx Fy Fz [N] magnetic force,
      Tx Ty Tz [N m] magnetic torque about the centre of mass (Eq. 17 + Eq. 18)
  postProcessing/energy.csv   time [s], kinetic, gravitational, magnetic, total [J]
  postProcessing/induction.csv (soft bodies) time [s], step, iterations, residual [-], converged (0/1)
  <time>/bodies.yaml          the state of every body (restart with startFrom: latestTime)
  <time>/timeStep.yaml        the last time step and the bodies' net accelerations (adjustTimeStep runs)
  VTK/bodies.pvd, VTK/bodies_N.vtp   surfaces per write time (ParaView), see README "Outputs"
)");
    if (!args.parse(argc, argv)) return args.exitCode();
    return runGuarded(args, run);
}
