// magForces: magnetic forces and torques of a case's configuration, with the
// induced magnetizations converged first (as in the solver's step), and an
// optional sweep of one body (system/forcesDict.yaml), either along a
// direction or about an axis:
//
//   sweep: {body: top, direction: [0, 0, 1], from: -0.01, to: 0.02, steps: 61}
//   sweep: {body: top, rotate: {axis: [0, 0, 1], from: 0, to: 90, steps: 19}}
//
// Translation: offsets from..to (m) along the direction from the body's
// position. Rotation: angles from..to (degrees, as orientations in
// bodies.yaml) about the world-frame axis through the body's centre of mass,
// applied to its orientation in bodies.yaml; only the orientation changes.
// steps is the number of evaluations, from and to included (1: from only).
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
#include <magFoam/InputFile.hpp>
#include <magFoam/Log.hpp>
#include <magFoam/MagneticSystem.hpp>
#include <magFoam/Threads.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

using namespace mag;

namespace {

struct Sweep {
    std::size_t body = 0;
    bool rotate = false;
    Vec3 direction = Vec3::UnitZ();  // translation: direction; rotation: axis (unit)
    double from = 0, to = 0;         // m, or degrees
    int steps = 1;
};

void readRange(const Dict& d, Sweep& s) {
    s.from = d.get<double>("from");
    s.to = d.get<double>("to");
    s.steps = d.get<int>("steps");
    if (s.steps < 1) d.fail("steps", "steps (the number of evaluations, from and to included) must be >= 1");
    // As for orientation.angle in bodies.yaml (docs/case-reference.md#plausibility).
    for (const char* key : {"from", "to"}) {
        const double angle = d.get<double>(key), k = angle / (pi / 12);
        if (s.rotate && angle != std::round(angle) && std::abs(angle) <= 2 * pi + 1e-9 && std::round(k) != 0 &&
            std::abs(k - std::round(k)) < 1e-3 * std::abs(k))
            d.warn(key, fmt::format("{:g} looks like radians ({:g} rad = {:g} deg); angles here are in degrees",
                                    angle, angle, angle * 180 / pi));
    }
}

Sweep readSweep(const Case& c, const Dict& dict) {
    Sweep s;
    const Dict d = dict.sub("sweep");
    s.body = c.bodyIndex(d.get<std::string>("body"), d.where("body") + ": sweep.body");
    const std::string forms = "a translation {body, direction, from, to, steps} or a rotation "
                              "{body, rotate: {axis, from, to, steps}}";
    std::string translationKey;
    for (const char* k : {"direction", "from", "to", "steps"})
        if (translationKey.empty() && d.has(k)) translationKey = k;
    s.rotate = d.has("rotate");
    if (s.rotate && !translationKey.empty())
        d.fail(translationKey, "a sweep is " + forms + ", not both; with rotate, from, to and steps go inside it");
    if (!s.rotate && translationKey.empty()) d.failHere("expected " + forms);
    const Dict r = s.rotate ? d.sub("rotate") : d;
    const std::string dirKey = s.rotate ? "axis" : "direction";
    s.direction = r.get<Vec3>(dirKey);
    if (!(s.direction.stableNorm() > 0)) r.fail(dirKey, "sweep " + dirKey + " has zero length");
    s.direction.stableNormalize();
    readRange(r, s);
    r.reportUnused();
    d.reportUnused();
    dict.reportUnused();
    return s;
}

// One line per soft body: its converged (induced) magnetization.
void printSoftBodies(const std::vector<Body>& bodies) {
    for (const Body& b : bodies) {
        if (!b.soft()) continue;
        const Vec3 M = b.magnetization();
        spdlog::info("  soft {:<12} M = ({:.6g}, {:.6g}, {:.6g}) A/m (world), |M| = {:.6g} A/m, mu0|M| = {:.4g} T",
                     b.name, M.x(), M.y(), M.z(), M.norm(), mu0 * M.norm());
    }
}

void writeRow(std::ofstream& csv, const std::string& prefix, const Body& b, const Wrench& w) {
    const Vec3 T = w.totalTorque();
    char line[512];
    std::snprintf(line, sizeof line, "%s%s,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g\n",
                  prefix.c_str(), b.name.c_str(), w.force.x(), w.force.y(), w.force.z(), T.x(), T.y(), T.z(),
                  w.torque.x(), w.torque.y(), w.torque.z(), w.bodyEnergy());
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
    if (inputPresent(forcesFile)) sweep = readSweep(c, Dict::fromFile(forcesFile));

    std::filesystem::create_directories(c.dir() / "postProcessing");
    const auto csvPath = c.dir() / "postProcessing/forces.csv";
    std::ofstream csv(csvPath);
    if (!csv) throw InputError(csvPath.string() + ": cannot write");
    const std::string columns = "body,Fx,Fy,Fz,Tx,Ty,Tz,TmagX,TmagY,TmagZ,energy\n";
    csv << (sweep ? (sweep->rotate ? "step,angle," : "step,offset,") : "") << columns;

    std::vector<Body>& bodies = c.bodies();
    const int steps = sweep ? sweep->steps : 1;
    const Vec3 start = sweep ? bodies[sweep->body].position : Vec3::Zero();
    const Quat startOrientation = sweep ? bodies[sweep->body].orientation : Quat::Identity();
    double seconds = 0;
    for (int k = 0; k < steps; ++k) {
        double offset = 0;  // m, or degrees for a rotation
        if (sweep) {
            offset = steps == 1 ? sweep->from : sweep->from + (sweep->to - sweep->from) * k / (steps - 1);
            Body& b = bodies[sweep->body];
            if (sweep->rotate)  // about the world axis through the centre of mass: the position stays
                b.orientation =
                    (Quat(Eigen::AngleAxisd(offset * pi / 180.0, sweep->direction)) * startOrientation).normalized();
            else
                b.position = start + offset * sweep->direction;
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

        std::string prefix;
        if (sweep) {
            char angle[64];
            std::snprintf(angle, sizeof angle, "%.10g", offset);
            prefix = std::to_string(k) + "," + (sweep->rotate ? std::string(angle) : std::to_string(offset)) + ",";
        }
        for (std::size_t i = 0; i < bodies.size(); ++i) writeRow(csv, prefix, bodies[i], w[i]);
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
    }
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
