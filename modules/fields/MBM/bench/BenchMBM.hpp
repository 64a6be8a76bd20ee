// magBenchMBM: the studies that time the MBM kernel itself (module internals,
// no plugin in between); timing and CSV output come from BenchHarness.hpp.
#pragma once

#include <magFoam/BenchHarness.hpp>
#include <magFoam/Dictionary.hpp>

#include <filesystem>

namespace mag::bench {

void kernelStudy(const Dict& study, const std::filesystem::path& caseDir);
void toleranceStudy(const Dict& study, const std::filesystem::path& caseDir);

} // namespace mag::bench
