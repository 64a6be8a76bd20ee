// scaling: cost of the wrenches of one step against the number of magnets, for the
// hybrid (near MBM, far EDM, dipole pairs found by a grid and summed in bulk), in one
// or more settings side by side.
// N 1 cm cubes, 1 T, random orientations, placed at random (fixed seed) in a cube
// whose edge grows as N^(1/3), so the number density stays constant (one magnet per
// spacing^3) and most pairs of a large scene are far; no two bounding spheres overlap.
//
//   scaling:
//     bodies: [2, 5, 10, 20, 50, 100, 200, 500, 1000, 2000, 5000, 10000, 20000]
//     spacing: 0.03                    # m, box edge = spacing N^(1/3)
//     fields:                          # label: field (YAML); the CSV's `field` column
//       ratio8: "{type: hybrid, near: {type: MBM, quadrature: {type: gauss, n: 6}}}"
//       tolerance1e-3: "{type: hybrid, near: {...}, dipoleTolerance: 1e-3}"
//     farField: "{method: auto}"       # how dipole pairs are summed (the hybrid's farField:)
//     threads: [1, 0]                  # 0 = all cores
//     minSeconds: 0.05                 # timing per run (at least one call); the best
//     repeats: 2                       #   of `repeats` runs
//     seed: 1
#include "BenchCommon.hpp"
#include "Studies.hpp"
#include "ThreadStudies.hpp"

#include <magFoam/Error.hpp>
#include <magFoam/InductionModel.hpp>
#include <magFoam/Log.hpp>
#include <magFoam/MagneticSystem.hpp>

#include <yaml-cpp/yaml.h>

#include <limits>
#include <random>

namespace mag::bench {

namespace {

std::vector<Body> scatteredCubes(int n, double spacing, unsigned seed) {
    const double edge = 0.01;
    const double minDistance = 1.05 * edge * std::sqrt(3.0);  // bounding spheres apart
    const double box = spacing * std::cbrt(static_cast<double>(n));
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-0.5, 0.5);
    std::normal_distribution<double> g;
    std::vector<Body> out;
    for (int i = 0, tries = 0; i < n; ++tries) {
        if (tries > 1000 * n) throw InputError(fmt::format("scaling: cannot place {} cubes; raise spacing", n));
        const Vec3 p = box * Vec3(u(rng), u(rng), u(rng));
        bool free = true;
        for (const Body& b : out) free = free && (b.position - p).norm() > minDistance;
        if (!free) continue;
        const Quat q = Quat(g(rng), g(rng), g(rng), g(rng)).normalized();  // uniform random rotation
        out.push_back(cube(fmt::format("m{}", i++), edge, 1.0, p, q));
    }
    return out;
}

// Pair decisions of one wrenches call, from the hybrid's counters.
struct PairCounts {
    long nearPairs = -1, farPairs = -1, dipolePairs = -1;
};
PairCounts pairCounts(const FieldEvaluator& f) {
    const FieldStats s = f.stats();
    auto c = [&](const char* name) { return static_cast<long>(s.count(name)); };
    return {c("nearPairs"), c("farPairs"), c("dipolePairs")};
}

// The field (YAML) with the hybrid's `farField:` set.
std::string withFarField(const std::string& field, const std::string& farField, const std::string& where) {
    YAML::Node n = Dict::fromString(field, where).node();
    n["farField"] = Dict::fromString(farField, where).node();
    YAML::Emitter out;
    out << YAML::Flow << n;
    return out.c_str();
}

// Best time per call (s) of the whole wrenches call and of its dipole sum alone
// (the hybrid's dipoleSumNanoseconds counter), over `repeats` runs of at least
// minSeconds each.
struct StepTimes {
    double step = 0, dipoleSum = 0;
};
StepTimes timeStep(const MagneticSystem& system, const std::vector<Body>& bodies, double minSeconds, int repeats) {
    double bestSum = std::numeric_limits<double>::infinity();
    auto counter = [&] { return system.fieldEvaluator().stats().count("dipoleSumNanoseconds"); };
    StepTimes t;
    t.step = bestSecondsPerCall(
        [&] {
            const std::uint64_t before = counter();
            (void)system.wrenches(bodies, true);
            bestSum = std::min(bestSum, 1e-9 * static_cast<double>(counter() - before));
        },
        minSeconds, repeats);
    t.dipoleSum = bestSum;
    return t;
}

} // namespace

void scalingStudy(const Dict& study, const std::filesystem::path& caseDir) {
    const auto ns = study.get<std::vector<double>>("bodies", {2, 5, 10, 20, 50, 100, 200, 500, 1000, 2000, 5000, 10000, 20000});
    const double spacing = study.get<double>("spacing", 0.03);
    std::vector<std::pair<std::string, std::string>> fields;
    if (study.has("fields")) {
        const Dict f = study.sub("fields");
        for (const auto& label : f.keys()) fields.emplace_back(label, f.get<std::string>(label));
        if (fields.empty()) study.fail("fields", "give at least one `label: field` entry");
    } else {
        fields = {{"ratio8", "{type: hybrid, near: {type: MBM, quadrature: {type: gauss, n: 6}}}"},
                  {"tolerance1e-3",
                   "{type: hybrid, near: {type: MBM, quadrature: {type: gauss, n: 6}}, dipoleTolerance: 1e-3}"}};
    }
    const std::string farField = study.get<std::string>("farField", "{}");
    const auto counts = threadCounts(study);
    const double minSeconds = study.get<double>("minSeconds", 0.05);
    const int repeats = study.get<int>("repeats", 2);
    const int seed = study.get<int>("seed", 1);
    if (!(spacing >= 0.02)) study.fail("spacing", "spacing must be >= 0.02 m (the cubes are 1 cm)");
    if (repeats < 1) study.fail("repeats", "repeats must be >= 1");
    study.reportUnused();

    const RestoreThreads restore;
    auto csv = openCsv(caseDir, "scaling.csv",
                       "field,bodies,threads,msPerStep,farFieldMs,directFarFieldMs,dipoleSum,nearPairs,farPairs,dipolePairs");
    for (const auto& [label, field] : fields) {
        spdlog::info("  {}: {}", label, field);
        const std::string asSet = withFarField(field, farField, study.keyPath("fields." + label));
        const std::string direct = withFarField(field, "{method: direct}", study.keyPath("fields." + label));
        for (double nd : ns) {
            const int n = static_cast<int>(nd);
            const std::vector<Body> bodies = scatteredCubes(n, spacing, static_cast<unsigned>(seed));
            // Counts from a fresh evaluator's first call; that call also builds the tables.
            const auto none = [] { return InductionModel::New(Dict::fromString("type: none\n", "scaling")); };
            MagneticSystem system(evaluator(asSet), none());
            (void)system.wrenches(bodies, true);
            const PairCounts pc = pairCounts(system.fieldEvaluator());
            const bool multipole = system.fieldEvaluator().stats().count("multipoleSums") > 0;
            const char* sum = multipole ? "multipole" : "direct";
            // The dipole sum alone (its part of the step; the rest is the near and
            // EDM pairs, found by the grid), as set and by the direct O(N^2) sum.
            MagneticSystem directSystem(evaluator(direct), none());
            if (multipole) (void)directSystem.wrenches(bodies, true);
            for (int t : counts) {
                setThreads(t);
                const StepTimes st = timeStep(system, bodies, minSeconds, repeats);
                const double ms = 1e3 * st.step, farMs = 1e3 * st.dipoleSum;
                const double directMs =
                    multipole ? 1e3 * timeStep(directSystem, bodies, minSeconds, repeats).dipoleSum : farMs;
                csv << label << ',' << n << ',' << t << ',' << ms << ',' << farMs << ',' << directMs << ',' << sum << ','
                    << pc.nearPairs << ',' << pc.farPairs << ',' << pc.dipolePairs << '\n';
                spdlog::info("  {:<14} N={:<5} threads {}  {:10.4f} ms per step (dipole sum {:.4f}, {}; direct {:.4f})  "
                             "pairs near {} far {} dipole {}",
                             label, n, t, ms, farMs, sum, directMs, pc.nearPairs, pc.farPairs, pc.dipolePairs);
            }
        }
    }
}

} // namespace mag::bench
