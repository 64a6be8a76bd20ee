// magBench: speed-versus-accuracy and stability studies (docs/case-reference.md#benchdict).
// Reads system/benchDict.yaml of the case (or -dict FILE), runs the studies it
// names (or the one given by -study), writes postProcessing/<study>.csv; the case's plot
// script turns them into PNG charts.
//
//   studies:
//     accuracyCost: {...}     error vs CPU time per force evaluation
//     divergence: {...}       force and error vs gap through overlap
//     switchError: {...}      hybrid error vs switch threshold
//     table1: {...}           paper Table 1: ms per step, MBM regular n, 1 and all threads
//     table2: {...}           ms per step (magnetic, rigid) of whole cases; with
//                             scenes: whole runs, simulated s per wall s beside the paper's
//     scaling: {...}          ms per step of the wrenches vs the number of magnets
//
// Models are reached through the registries only; the MBM kernel's own timing
// (kernel) is the MBM module's magBenchMBM (modules/fields/MBM/bench).
//
// -threads N sets the worker count of the studies that do not list their own
// (default 1: the accuracy studies time one core).
#include "BenchCommon.hpp"
#include "Studies.hpp"

#include <magFoam/ArgList.hpp>
#include <magFoam/Error.hpp>
#include <magFoam/Log.hpp>
#include <magFoam/Threads.hpp>

#include <cmath>
#include <cstdio>
#include <map>

using namespace mag;

namespace mag::bench {

std::string substitute(const std::string& text, const std::string& var, double value) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.10g", value);
    std::string out = text;
    const std::string key = "$" + var;
    for (std::size_t p; (p = out.find(key)) != std::string::npos;) out.replace(p, key.size(), buf);
    return out;
}

std::vector<Method> readMethods(const Dict& study, const std::string& valueKey) {
    std::vector<Method> out;
    for (const Dict& d : study.list("methods")) {
        Method m{d.get<std::string>("label"), d.get<std::string>("field"), d.get<std::vector<double>>(valueKey, {})};
        d.reportUnused();
        out.push_back(m);
    }
    return out;
}

} // namespace mag::bench

namespace {

int run(const ArgList& args) {
    const std::string dict = args.get("dict");
    return bench::runStudies(args, dict.empty() ? "benchDict.yaml" : dict,
                             {{"accuracyCost", bench::accuracyCostStudy},
                              {"divergence", bench::divergenceStudy},
                              {"switchError", bench::switchErrorStudy},
                              {"table1", bench::tableOneStudy},
                              {"table2", bench::tableTwoStudy},
                              {"scaling", bench::scalingStudy}});
}

} // namespace

int main(int argc, char** argv) {
    ArgList args("magBench", "Speed-versus-accuracy and stability studies of system/benchDict.yaml -> postProcessing/*.csv.");
    args.withThreads();
    args.outputs("  postProcessing/<study>.csv   one file per study of system/benchDict.yaml; columns per study:\n"
                 "      cases/benchmarks/README.md (the column names carry the units, e.g. ms per step)\n");
    args.option("study", "NAME", "run only this study of benchDict.yaml");
    args.option("dict", "FILE", "read system/FILE instead of system/benchDict.yaml");
    if (!args.parse(argc, argv)) return args.exitCode();
    return runGuarded(args, run);
}
