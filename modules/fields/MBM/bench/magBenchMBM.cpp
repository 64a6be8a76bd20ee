// magBenchMBM: timing studies of the MBM module's kernel (the closed-form field
// of paper Eqs. 9-15), which the field evaluator interface does not reach.
// Reads system/benchMBMDict.yaml of the case, runs the studies it names (or
// the one given by -study), writes postProcessing/<study>.csv; the case's plot
// script turns them into PNG charts (cases/benchmarks).
//
//   studies:
//     kernel: {...}           ns per point of the MBM field kernel, reference vs fast
//     tolerance: {...}        adaptive quadrature: requested vs achieved error, cost vs gauss, regular
//
// -threads N sets the worker count (default 1).
#include "BenchMBM.hpp"

#include <magFoam/ArgList.hpp>
#include <magFoam/BenchHarness.hpp>
#include <magFoam/Error.hpp>

using namespace mag;

namespace {

int run(const ArgList& args) { return bench::runStudies(args, "benchMBMDict.yaml", {{"kernel", bench::kernelStudy}, {"tolerance", bench::toleranceStudy}}); }

} // namespace

int main(int argc, char** argv) {
    ArgList args("magBenchMBM",
                 "Timing studies of the MBM kernel, system/benchMBMDict.yaml -> postProcessing/*.csv.");
    args.option("study", "NAME", "run only this study of benchMBMDict.yaml");
    if (!args.parse(argc, argv)) return args.exitCode();
    return runGuarded(args, run);
}
