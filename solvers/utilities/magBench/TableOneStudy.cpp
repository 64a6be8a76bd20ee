// table1: the paper's Table 1 — cost of one step's magnetic part for the Fig. 6
// pair (two 1 cm cubes, one fixed) with MBM and the paper's regular rule, n x n
// samples per face. Times MagneticSystem::step (induction: none; wrenches with
// the fixed-fixed pairs skipped, as magFoam steps), one pair, at each thread count.
//
//   table1:
//     case: ../fig6-twoCubes            # bodies from this case (relative to this one)
//     field: "{type: MBM, quadrature: {type: regular, n: $n}}"
//     n: [2, 5, 10, 20]
//     paperMs: [0.12, 0.36, 0.89, 3.32] # paper, one core
//     threads: [1, 0]                   # 0 = all cores
//     minSeconds: 0.03                  # timing per run; the best of `repeats` runs
//     repeats: 3
#include "BenchCommon.hpp"
#include "Studies.hpp"
#include "ThreadStudies.hpp"

#include <magFoam/Case.hpp>
#include <magFoam/InductionModel.hpp>
#include <magFoam/Log.hpp>
#include <magFoam/MagneticSystem.hpp>

namespace mag::bench {

void tableOneStudy(const Dict& study, const std::filesystem::path& caseDir) {
    const auto casePath = caseDir / study.get<std::string>("case", "../fig6-twoCubes");
    const std::string field = study.get<std::string>("field", "{type: MBM, quadrature: {type: regular, n: $n}}");
    const auto ns = study.get<std::vector<double>>("n", {2, 5, 10, 20});
    const auto paper = study.get<std::vector<double>>("paperMs", {});
    const auto counts = threadCounts(study);
    const double minSeconds = study.get<double>("minSeconds", 0.03);
    const int repeats = study.get<int>("repeats", 3);
    if (!paper.empty() && paper.size() != ns.size()) study.fail("paperMs", "one paper time per n expected");
    if (repeats < 1) study.fail("repeats", "repeats must be >= 1");
    study.reportUnused();

    const RestoreThreads restore;
    const Case c = Case::read(casePath);
    auto csv = openCsv(caseDir, "table1.csv", "n,samples,threads,msPerStep,paperMs");
    for (std::size_t i = 0; i < ns.size(); ++i) {
        const std::string yaml = substitute(field, "n", ns[i]);
        const MagneticSystem system(evaluator(yaml), InductionModel::New(Dict::fromString("type: none\n", "table1")));
        std::vector<Body> bodies = c.bodies();
        std::size_t samples = 0;  // on the sampled (moving) body of each pair
        for (const Body& b : bodies)
            if (!b.fixed) samples += boundarySamples(Dict::fromString(yaml, "table1"), b.shape);
        const double paperMs = paper.empty() ? 0.0 : paper[i];
        for (int t : counts) {
            setThreads(t);
            const double ms = 1e3 * bestSecondsPerCall([&] { (void)system.step(bodies); }, minSeconds, repeats);
            csv << ns[i] << ',' << samples << ',' << t << ',' << ms << ',' << paperMs << '\n';
            spdlog::info("  n={:<3} samples {:5}  threads {}  {:8.4f} ms per step  (paper {} ms)", ns[i], samples, t,
                         ms, paperMs);
        }
    }
}

} // namespace mag::bench
