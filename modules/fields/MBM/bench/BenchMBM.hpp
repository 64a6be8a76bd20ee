// magBenchMBM: the studies that time the MBM kernel itself (module internals,
// no plugin in between); the helpers they share with magBench's studies.
#pragma once

#include <magFoam/Dictionary.hpp>

#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

namespace mag::bench {

// Seconds per call of f (after one warm-up call), repeated until at least
// minSeconds have passed.
double secondsPerCall(const std::function<void()>& f, double minSeconds = 0.05);

// Open postProcessing/<file> under the case, with a header row.
std::ofstream openCsv(const std::filesystem::path& caseDir, const std::string& file, const std::string& header);

void kernelStudy(const Dict& study, const std::filesystem::path& caseDir);

} // namespace mag::bench
