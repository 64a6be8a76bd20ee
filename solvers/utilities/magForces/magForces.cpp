// magForces: magnetic forces and torques of a case's configuration, with the
// induced magnetizations converged first (as in the solver's step), and an
// optional sweep of one body (system/forcesDict.yaml), either along a
// direction or about an axis (the evaluations: ForceSweep.hpp, shared with
// the Python module).
//
// Writes postProcessing/forces.csv (world frame; torque about each body's
// centre of mass = magnetic (Eq. 17) + mechanical (Eq. 18); energy = the
// body's interaction energy with all others, so that F = -grad U and, for a
// rotation about a, T.a = -dU/dangle) with step,offset (m) or step,angle
// (degrees) first in a sweep, and prints a table; after it, the magnetization
// of every soft body (world frame, A/m, and mu0 |M| in T).
#include <magFoam/ArgList.hpp>
#include <magFoam/BodyOverlap.hpp>
#include <magFoam/Case.hpp>
#include <magFoam/Error.hpp>
#include <magFoam/Log.hpp>
#include <magFoam/MagneticSystem.hpp>
#include <magFoam/OutputFile.hpp>
#include <magFoam/Parts.hpp>
#include <magFoam/Threads.hpp>

#include "ForceSweep.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

using namespace mag;

namespace {

// One line per soft body (a compound's: per soft part, "<body>/<k>"): its
// converged (induced) magnetization.
void printSoftBodies(const std::vector<Body>& bodies) {
    for (const Body& b : PartBodies(bodies).parts) {
        if (!b.soft()) continue;
        const Vec3 M = b.magnetization();
        spdlog::info("  soft {:<12} M = ({:.6g}, {:.6g}, {:.6g}) A/m (world), |M| = {:.6g} A/m, mu0|M| = {:.4g} T",
                     b.name, M.x(), M.y(), M.z(), M.norm(), mu0 * M.norm());
    }
}

void writeRow(std::string& csv, const std::string& prefix, const Body& b, const Wrench& w) {
    const Vec3 T = w.totalTorque();
    char line[512];
    std::snprintf(line, sizeof line, "%s%s,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g\n",
                  prefix.c_str(), b.name.c_str(), w.force.x(), w.force.y(), w.force.z(), T.x(), T.y(), T.z(),
                  w.torque.x(), w.torque.y(), w.torque.z(), w.bodyEnergy());
    csv += line;
}

int run(const ArgList& args) {
    Case c = Case::read(args.caseDir(), args.schemesFile());
    const int threads = setThreads(args, c);
    MagneticSystem system(c);
    spdlog::info("magForces: case {}, {} bodies, {} thread(s), field: {}", args.caseDir().string(), c.bodies().size(),
                 threads, system.fieldEvaluator().describe());

    warnOverlaps(c.bodies(), (c.dir() / "constant" / "bodies.yaml").string(),
                 "their forces follow the overlap model (docs/physics.md#overlap-models), not a contact");
    const std::optional<forces::Sweep> sweep = forces::readForcesDict(c);

    // Rows are written as they come (checked: a full disk stops the run
    // naming the file, OutputFile.hpp).
    const auto csvPath = c.dir() / "postProcessing/forces.csv";
    const std::string columns = "body,Fx,Fy,Fz,Tx,Ty,Tz,TmagX,TmagY,TmagZ,energy";
    AppendedFile csv(csvPath, (sweep ? (sweep->rotate ? "step,angle," : "step,offset,") : "") + columns, false);

    const int steps = sweep ? sweep->steps : 1;
    const double seconds = forces::evaluate(c.bodies(), system, sweep, [&](const forces::Evaluation& e) {
        const int k = e.step;
        const double offset = e.offset;
        const std::vector<Body>& bodies = e.bodies;
        const std::vector<Wrench>& w = e.wrenches;
        std::string prefix;
        if (sweep) {
            char angle[64];
            std::snprintf(angle, sizeof angle, "%.10g", offset);
            prefix = std::to_string(k) + "," + (sweep->rotate ? std::string(angle) : std::to_string(offset)) + ",";
        }
        std::string rows;
        for (std::size_t i = 0; i < bodies.size(); ++i) writeRow(rows, prefix, bodies[i], w[i]);
        csv.append(rows);
        if (!sweep || steps <= 20 || k % (steps / 10) == 0 || k == steps - 1) {
            if (sweep && sweep->rotate)
                spdlog::info("step {} angle {:+.6g} deg", k, offset);
            else if (sweep)
                spdlog::info("step {} offset {:+.6g} m", k, offset);
            spdlog::info("  {:<12} {:>13} {:>13} {:>13} {:>13} {:>13} {:>13}", "body", "Fx [N]", "Fy [N]", "Fz [N]",
                         "Tx [N m]", "Ty [N m]", "Tz [N m]");
            for (std::size_t i = 0; i < bodies.size(); ++i) {
                const Vec3 T = w[i].totalTorque();
                spdlog::info("  {:<12} {:>13.6g} {:>13.6g} {:>13.6g} {:>13.6g} {:>13.6g} {:>13.6g}", bodies[i].name,
                             w[i].force.x(), w[i].force.y(), w[i].force.z(), T.x(), T.y(), T.z());
            }
            printSoftBodies(bodies);
        }
    });
    spdlog::info("{} evaluation(s), {:.3f} ms each; wrote {}", steps, 1e3 * seconds / steps, csvPath.string());
    spdlog::info("field: {}", system.fieldEvaluator().describe());
    for (const std::string& line : system.fieldEvaluator().stats().pairSampleLines()) spdlog::info("{}", line);
    return 0;
}

} // namespace

int main(int argc, char** argv) {
    ArgList args("magForces", "Forces and torques on every body of a case (optional translation or rotation sweep of one body in "
                   "system/forcesDict.yaml); the magnetization of soft bodies.");
    args.withThreads().withSchemes();
    args.outputs(R"(  postProcessing/forces.csv   one row per body (and sweep point), world frame:
      [step, offset [m] | angle [deg] (sweeps)], body, Fx Fy Fz [N],
      Tx Ty Tz [N m] torque about the centre of mass (magnetic Eq. 17 + mechanical Eq. 18),
      TmagX TmagY TmagZ [N m] the magnetic part (Eq. 17), energy [J] interaction energy
)");
    if (!args.parse(argc, argv)) return args.exitCode();
    return runGuarded(args, run);
}
