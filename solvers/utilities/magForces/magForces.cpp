// magForces: magnetic forces and torques of a case's configuration, with the
// induced magnetizations converged first (as in the solver's step), and an
// optional sweep of one body along a direction (system/forcesDict.yaml):
//
//   sweep: {body: top, direction: [0, 0, 1], from: -0.01, to: 0.02, steps: 61}
//
// Writes postProcessing/forces.csv (world frame; torque about each body's
// centre of mass = magnetic (Eq. 17) + mechanical (Eq. 18)) and prints a table.
#include <magFoam/ArgList.hpp>
#include <magFoam/BodyOverlap.hpp>
#include <magFoam/Case.hpp>
#include <magFoam/Error.hpp>
#include <magFoam/Log.hpp>
#include <magFoam/MagneticSystem.hpp>
#include <magFoam/Threads.hpp>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>

using namespace mag;

namespace {

struct Sweep {
    std::size_t body = 0;
    Vec3 direction = Vec3::UnitZ();
    double from = 0, to = 0;
    int steps = 1;
};

Sweep readSweep(const Case& c, const Dict& dict) {
    Sweep s;
    const Dict d = dict.sub("sweep");
    s.body = c.bodyIndex(d.get<std::string>("body"), d.where("body") + ": sweep.body");
    s.direction = d.get<Vec3>("direction");
    if (s.direction.norm() == 0) d.fail("direction", "sweep direction has zero length");
    s.direction.normalize();
    s.from = d.get<double>("from");
    s.to = d.get<double>("to");
    s.steps = d.get<int>("steps");
    if (s.steps < 1) d.fail("steps", "steps must be >= 1");
    d.reportUnused();
    dict.reportUnused();
    return s;
}

void writeRow(std::ofstream& csv, const std::string& prefix, const Body& b, const Wrench& w) {
    const Vec3 T = w.totalTorque();
    char line[512];
    std::snprintf(line, sizeof line, "%s%s,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g\n",
                  prefix.c_str(), b.name.c_str(), w.force.x(), w.force.y(), w.force.z(), T.x(), T.y(), T.z(),
                  w.torque.x(), w.torque.y(), w.torque.z(), w.energy);
    csv << line;
}

int run(const ArgList& args) {
    Case c = Case::read(args.caseDir(), args.schemesFile());
    const int threads = setThreads(args, c);
    MagneticSystem system(c);
    spdlog::info("magForces: case {}, {} bodies, {} thread(s), field: {}", args.caseDir().string(), c.bodies().size(),
                 threads, system.fieldEvaluator().describe());

    warnOverlaps(c.bodies(), (c.dir() / "constant" / "bodies.yaml").string(),
                 "their forces follow the overlap model (docs/physics.md#overlap-models), not a contact");
    const auto forcesFile = c.dir() / "system/forcesDict.yaml";
    std::optional<Sweep> sweep;
    if (std::filesystem::exists(forcesFile)) sweep = readSweep(c, Dict::fromFile(forcesFile));

    std::filesystem::create_directories(c.dir() / "postProcessing");
    const auto csvPath = c.dir() / "postProcessing/forces.csv";
    std::ofstream csv(csvPath);
    if (!csv) throw InputError(csvPath.string() + ": cannot write");
    const std::string columns = "body,Fx,Fy,Fz,Tx,Ty,Tz,TmagX,TmagY,TmagZ,energy\n";
    csv << (sweep ? "step,offset," : "") << columns;

    std::vector<Body>& bodies = c.bodies();
    const int steps = sweep ? sweep->steps : 1;
    const Vec3 start = sweep ? bodies[sweep->body].position : Vec3::Zero();
    double seconds = 0;
    for (int k = 0; k < steps; ++k) {
        double offset = 0;
        if (sweep) {
            offset = steps == 1 ? sweep->from : sweep->from + (sweep->to - sweep->from) * k / (steps - 1);
            bodies[sweep->body].position = start + offset * sweep->direction;
        }
        const auto t0 = std::chrono::steady_clock::now();
        const InductionReport ind = system.converge(bodies);
        if (!ind.converged) {
            std::string names;
            for (const auto& n : ind.unconverged) names += " " + n;
            spdlog::warn("induction did not converge ({} iterations, residual {:.3g}):{}", ind.iterations,
                         ind.residual, names);
        }
        const std::vector<Wrench> w = system.wrenches(bodies);
        seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

        const std::string prefix = sweep ? std::to_string(k) + "," + std::to_string(offset) + "," : "";
        for (std::size_t i = 0; i < bodies.size(); ++i) writeRow(csv, prefix, bodies[i], w[i]);
        if (!sweep || steps <= 20 || k % (steps / 10) == 0 || k == steps - 1) {
            if (sweep) spdlog::info("step {} offset {:+.6g} m", k, offset);
            spdlog::info("  {:<12} {:>13} {:>13} {:>13} {:>13} {:>13} {:>13}", "body", "Fx [N]", "Fy [N]", "Fz [N]",
                         "Tx [N m]", "Ty [N m]", "Tz [N m]");
            for (std::size_t i = 0; i < bodies.size(); ++i) {
                const Vec3 T = w[i].totalTorque();
                spdlog::info("  {:<12} {:>13.6g} {:>13.6g} {:>13.6g} {:>13.6g} {:>13.6g} {:>13.6g}", bodies[i].name,
                             w[i].force.x(), w[i].force.y(), w[i].force.z(), T.x(), T.y(), T.z());
            }
        }
    }
    spdlog::info("{} evaluation(s), {:.3f} ms each; wrote {}", steps, 1e3 * seconds / steps, csvPath.string());
    spdlog::info("field: {}", system.fieldEvaluator().describe());
    for (const std::string& line : system.fieldEvaluator().stats().pairSampleLines()) spdlog::info("{}", line);
    return 0;
}

} // namespace

int main(int argc, char** argv) {
    ArgList args("magForces", "Forces and torques on every body of a case (optional sweep in system/forcesDict.yaml).");
    args.withThreads().withSchemes();
    args.outputs(R"(  postProcessing/forces.csv   one row per body (and sweep point), world frame:
      [step, offset [m] | angle [deg] (sweeps)], body, Fx Fy Fz [N],
      Tx Ty Tz [N m] torque about the centre of mass (magnetic Eq. 17 + mechanical Eq. 18),
      TmagX TmagY TmagZ [N m] the magnetic part (Eq. 17), energy [J] interaction energy
)");
    if (!args.parse(argc, argv)) return args.exitCode();
    return runGuarded(args, run);
}
