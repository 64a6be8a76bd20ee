// table2's whole scenes (`scenes:` in the table2 study): each case run from
// its start to its endTime as magFoam runs it (solver::run: its controlDict,
// magSchemes, rigidBody backend, adaptive steps and sleeping), at each thread
// count, on a scratch copy under postProcessing/table2/<case>/ (meshes made
// there by magMakeGeometry when the case has system/geometryDict.yaml). The
// figure of merit is the paper's Table 2 speed, simulated seconds per wall
// second, printed beside the paper's (Delta t / (T_m + T_r) of its Table 2):
//
//   table2:
//     scenes:                          # case (relative to this one): the paper's sim-s / wall-s
//       ../fig6-twoCubes: 4.5
//       ../fig7-stackedMagnets: 0.050
//     threads: [1, 0]
//
// Whole runs take minutes per scene: cases/benchmarks keeps them in
// system/benchDict.table2.yaml (magBench -dict benchDict.table2.yaml).
#include "BenchCommon.hpp"
#include "Studies.hpp"
#include "ThreadStudies.hpp"

#include <magFoam/Case.hpp>
#include <magFoam/Error.hpp>
#include <magFoam/Log.hpp>

#include <Solver.hpp>

#include <chrono>

namespace mag::bench {

namespace {

// Warnings only while it lives; the level before afterwards.
struct QuietLog {
    spdlog::level::level_enum level = spdlog::get_level();
    QuietLog() { spdlog::set_level(spdlog::level::warn); }
    ~QuietLog() { spdlog::set_level(level); }
    QuietLog(const QuietLog&) = delete;
    QuietLog& operator=(const QuietLog&) = delete;
};

} // namespace

void sceneRateStudy(const Dict& scenes, const std::vector<int>& counts, const std::filesystem::path& caseDir) {
    using clock = std::chrono::steady_clock;
    auto csv = openCsv(caseDir, "table2Scenes.csv",
                       "case,threads,simulatedSeconds,wallSeconds,steps,simulatedPerWall,paperSimulatedPerWall,ratio");
    for (const std::string& name : scenes.keys()) {
        const double paper = scenes.get<double>(name);
        if (!(paper > 0)) scenes.fail(name, "the paper's simulated seconds per wall second must be > 0");
        const std::filesystem::path src = caseDir / name;
        if (!std::filesystem::is_directory(src / "system"))
            scenes.fail(name, "no case folder " + src.string() + " (a path relative to " + caseDir.string() + ")");
        for (int t : counts) {
            const auto dir = scratchCase(
                src, caseDir / "postProcessing" / "table2" / (src.filename().string() + "-threads" + std::to_string(t)),
                "table2 scenes");
            Case c = Case::read(dir);
            setThreads(t);
            long steps = 0;
            solver::RunOptions options;
            options.onWrite = [&](const solver::WriteRecord& r) { steps = r.step; };
            const double simulated = c.control().endTime - c.control().startTime;
            double wall = 0;
            {
                const QuietLog quiet; // the run's own log: warnings only
                const auto t0 = clock::now();
                solver::run(c, options);
                wall = std::chrono::duration<double>(clock::now() - t0).count();
            }
            const double rate = simulated / wall;
            csv << '"' << name << "\"," << t << ',' << simulated << ',' << wall << ',' << steps << ',' << rate << ','
                << paper << ',' << rate / paper << '\n';
            spdlog::info("  {:<28} threads {}  {:g} s simulated in {:.1f} s, {} steps: {:.4g} simulated s per wall s "
                         "(paper {:g}: {:.2f}x)",
                         name, t, simulated, wall, steps, rate, paper, rate / paper);
        }
    }
}

} // namespace mag::bench
