// magBenchMBM: timing studies of the MBM module's kernel (the closed-form field
// of paper Eqs. 9-15), which the field evaluator interface does not reach.
// Reads system/benchMBMDict.yaml of the case, runs the studies it names (or
// the one given by -study), writes postProcessing/<study>.csv; the case's plot
// script turns them into PNG charts (cases/benchmarks).
//
//   studies:
//     kernel: {...}           ns per point of the MBM field kernel, reference vs fast
//
// -threads N sets the worker count (default 1).
#include "BenchMBM.hpp"

#include <magFoam/ArgList.hpp>
#include <magFoam/Error.hpp>
#include <magFoam/Log.hpp>
#include <magFoam/Threads.hpp>

#include <chrono>
#include <map>

using namespace mag;

namespace mag::bench {

double secondsPerCall(const std::function<void()>& f, double minSeconds) {
    using clock = std::chrono::steady_clock;
    f(); // warm-up
    long calls = 0;
    const auto t0 = clock::now();
    double elapsed = 0;
    do {
        f();
        ++calls;
        elapsed = std::chrono::duration<double>(clock::now() - t0).count();
    } while (elapsed < minSeconds);
    return elapsed / static_cast<double>(calls);
}

std::ofstream openCsv(const std::filesystem::path& caseDir, const std::string& file, const std::string& header) {
    const auto dir = caseDir / "postProcessing";
    std::filesystem::create_directories(dir);
    std::ofstream out(dir / file);
    if (!out) throw InputError((dir / file).string() + ": cannot write");
    out.precision(10);
    out << header << "\n";
    return out;
}

} // namespace mag::bench

namespace {

int run(const ArgList& args) {
    const auto dir = args.caseDir();
    setThreads(args.threads().value_or(1));
    const Dict dict = Dict::fromFile(dir / "system/benchMBMDict.yaml");
    const Dict studies = dict.sub("studies");
    dict.reportUnused();
    const std::map<std::string, void (*)(const Dict&, const std::filesystem::path&)> known = {
        {"kernel", bench::kernelStudy}};
    const std::string only = args.get("study");
    if (!only.empty() && !known.count(only)) {
        std::string valid;
        for (const auto& [k, f] : known) valid += " " + k;
        throw InputError("-study " + only + ": unknown study; valid:" + valid);
    }
    for (const auto& name : studies.keys()) {
        if (!known.count(name)) {
            std::string valid;
            for (const auto& [k, f] : known) valid += (valid.empty() ? "" : ", ") + k;
            studies.fail(name, "unknown study '" + name + "'; valid studies: " + valid);
        }
        if (!only.empty() && name != only) continue;
        spdlog::info("study {}", name);
        known.at(name)(studies.sub(name), dir);
    }
    return 0;
}

} // namespace

int main(int argc, char** argv) {
    ArgList args("magBenchMBM",
                 "Timing studies of the MBM kernel, system/benchMBMDict.yaml -> postProcessing/*.csv.");
    args.option("study", "NAME", "run only this study of benchMBMDict.yaml");
    if (!args.parse(argc, argv)) return args.exitCode();
    return runGuarded(args, run);
}
