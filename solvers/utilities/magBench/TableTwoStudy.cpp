// table2: cost per step of whole cases, split as magFoam reports it: magnetic
// (induction + wrenches, MagneticSystem::step) and rigid body (the backend's
// step). Each case is set up as magFoam sets it up (its magSchemes, its
// rigidBody backend, its deltaT, its magneticStiffness where the backend takes
// it) and run from its initial state for `steps`
// steps at each thread count; nothing is written to the case.
//
//   table2:
//     cases: [../fig6-twoCubes, ../fig7-stackedMagnets]   # relative to this case
//     steps: 20
//     repeats: 2                                          # the best run is reported
//     threads: [1, 0]                                     # 0 = all cores
//     backends: [ODE, Bullet]                             # default: each case's own
//     scenes: {../fig6-twoCubes: 4.5}                     # whole runs (SceneRateStudy.cpp)
//
// A backend other than the case's runs the case's own file for it when it
// ships one (constant/rigidBody.<type in lower case>.yaml, e.g.
// rigidBody.bullet.yaml); otherwise it gets the case's rigidBody.yaml keys
// that both backends read alike (gravity, ground, contact friction,
// restitution and bounceVelocity, subSteps, maxTravel, maxSubSteps) and its
// own defaults. table2 steps without sleeping. Each case runs from a scratch
// copy in postProcessing/table2Cases/<case>/ (its meshes made there where
// magMakeGeometry makes them).
#include "BenchCommon.hpp"
#include "Studies.hpp"
#include "ThreadStudies.hpp"

#include <magFoam/Case.hpp>
#include <magFoam/Log.hpp>
#include <magFoam/MagneticSystem.hpp>
#include <magFoam/RigidBodyBackend.hpp>
#include <magFoam/SleepSettings.hpp>

#include <ImplicitTorque.hpp>

#include <yaml-cpp/yaml.h>

#include <cctype>
#include <chrono>
#include <limits>
#include <optional>

namespace mag::bench {

namespace {

// The case's rigid-body dictionary for `type` (its own when it is that type).
Dict rigidBodyAs(const Dict& own, const std::string& type) {
    if (own.get<std::string>("type") == type) return own;
    YAML::Node n;
    n["type"] = type;
    const YAML::Node& src = own.node();
    for (const char* key : {"gravity", "ground", "subSteps", "maxTravel", "maxSubSteps"})
        if (src[key]) n[key] = YAML::Clone(src[key]);
    if (src["contact"])
        for (const char* key : {"friction", "restitution", "bounceVelocity"})
            if (src["contact"][key]) n["contact"][key] = YAML::Clone(src["contact"][key]);
    return Dict::fromNode(n, own.file() + " (as " + type + ")");
}

// The backend dictionary `type` runs the case in `dir` with: the case's own,
// its variant file for that type, or the shared keys (rigidBodyAs).
Dict rigidBodyFor(const Case& c, const std::filesystem::path& dir, const std::string& type) {
    if (c.rigidBody().get<std::string>("type") == type) return c.rigidBody();
    std::string lower = type;
    for (char& ch : lower) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    const auto variant = dir / "constant" / ("rigidBody." + lower + ".yaml");
    if (!std::filesystem::exists(variant)) return rigidBodyAs(c.rigidBody(), type);
    Dict d = Dict::fromFile(variant);
    if (d.get<std::string>("type") != type)
        d.fail("type", "the table2 variant for " + type + " must be of that type");
    (void)SleepSettings::read(d);  // the solver's key: table2 steps without sleeping
    spdlog::info("  {}: {} from constant/{}", c.dir().filename().string(), type, variant.filename().string());
    return d;
}

} // namespace

void tableTwoStudy(const Dict& study, const std::filesystem::path& caseDir) {
    const auto cases = study.get<std::vector<std::string>>("cases", {});
    const int steps = study.get<int>("steps", 20);
    const int repeats = study.get<int>("repeats", 2);
    const auto counts = threadCounts(study);
    const auto backends = study.get<std::vector<std::string>>("backends", {});
    if (steps < 1) study.fail("steps", "steps must be >= 1");
    if (repeats < 1) study.fail("repeats", "repeats must be >= 1");
    if (cases.empty() && !study.has("scenes"))
        study.fail("cases", "table2 needs cases: (ms per step) or scenes: (whole runs), or both");
    const std::optional<Dict> scenes = study.has("scenes") ? std::optional<Dict>(study.sub("scenes")) : std::nullopt;
    study.reportUnused();
    if (scenes) {
        const RestoreThreads restore;
        sceneRateStudy(*scenes, counts, caseDir);
    }
    if (cases.empty()) return;

    using clock = std::chrono::steady_clock;
    auto since = [](clock::time_point t0) { return std::chrono::duration<double>(clock::now() - t0).count(); };
    const RestoreThreads restore;
    auto csv = openCsv(caseDir, "table2.csv", "case,bodies,samples,threads,msMagnetic,msRigid,backend");
    for (const std::string& name : cases) {
        const std::filesystem::path src = caseDir / name;
        const std::filesystem::path dir =
            scratchCase(src, caseDir / "postProcessing" / "table2Cases" / src.filename(), "table2");
        const Case c = Case::read(dir);
        const MagneticSystem magnets(c);
        const double dt = c.control().deltaT;
        // Samples: on every body that MBM would sample (near pairs), per body.
        std::size_t samples = 0;
        std::string perBody;
        for (const Body& b : c.bodies()) {
            const std::size_t n = boundarySamples(c.fieldDict(), b.shape);
            samples += n;
            if (!perBody.empty()) perBody += ' ';
            perBody += std::to_string(n);
        }
        spdlog::info("  {}: {} bodies, MBM samples per body: {}; field: {}", name, c.bodies().size(), perBody,
                     magnets.fieldEvaluator().describe());
        {
            std::vector<Body> warm = c.bodies();  // builds the per-shape tables outside the timing
            (void)magnets.step(warm);
        }
        std::vector<Dict> rigidBodies;
        if (backends.empty()) rigidBodies.push_back(c.rigidBody());
        for (const std::string& type : backends) rigidBodies.push_back(rigidBodyFor(c, dir, type));
        for (const Dict& rigidBody : rigidBodies) {
            for (int t : counts) {
                setThreads(t);
                const std::string type = rigidBody.get<std::string>("type");
                // A fresh backend and the initial state per run: every run takes the same
                // steps. The best of `repeats` runs (other jobs only ever add time).
                double magnetic = std::numeric_limits<double>::infinity(), rigid = magnetic;
                for (int r = 0; r < repeats; ++r) {
                    std::vector<Body> bodies = c.bodies();
                    const auto backend = RigidBodyBackend::New(rigidBody);
                    backend->setup(bodies);
                    double m = 0, b = 0;
                    for (int k = 0; k < steps; ++k) {
                        const auto tm = clock::now();
                        const MagneticSystem::Step s = magnets.step(bodies);
                        m += since(tm);
                        const auto tr = clock::now();
                        // As magFoam steps it: the tilt stiffness where the case
                        // integrates it implicitly and the backend can.
                        if (c.control().implicitTorque)
                            backend->setTiltStiffness(solver::tiltStiffnesses(bodies, s.wrenches));
                        backend->step(bodies, s.wrenches, dt);
                        b += since(tr);
                    }
                    magnetic = std::min(magnetic, m), rigid = std::min(rigid, b);
                }
                const double msMagnetic = 1e3 * magnetic / steps, msRigid = 1e3 * rigid / steps;
                csv << '"' << name << "\"," << c.bodies().size() << ',' << samples << ',' << t << ',' << msMagnetic << ','
                    << msRigid << ',' << type << '\n';
                spdlog::info("  {:<28} bodies {:3}  samples {:6}  threads {}  ms per step: magnetic {:8.4f}  rigid {:8.4f} ({})",
                             name, c.bodies().size(), samples, t, msMagnetic, msRigid, type);
            }
        }
    }
}

} // namespace mag::bench
