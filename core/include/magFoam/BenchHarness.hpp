// The harness of the benchmark apps (magBench, and the studies a module keeps
// of its own internals, e.g. the MBM module's magBenchMBM): timing by whole
// calls, CSV output under the case, and studies selected by name from a
// dictionary `studies:` (docs/case-reference.md#benchdict).
#pragma once

#include "magFoam/ArgList.hpp"
#include "magFoam/Dictionary.hpp"
#include "magFoam/OutputFile.hpp"

#include <filesystem>
#include <functional>
#include <map>
#include <sstream>
#include <string>

namespace mag::bench {

// Seconds per call of f: the best of `repeats` runs of at least minSeconds each
// (after one warm-up call). The best, not the mean: on a machine shared with other
// jobs, slices lost to them only ever add time.
double bestSecondsPerCall(const std::function<void()>& f, double minSeconds, int repeats);
// One run of at least minSeconds.
double secondsPerCall(const std::function<void()>& f, double minSeconds = 0.05);

// A study's CSV: values formatted as a stream formats them (10 significant
// digits), each line written through as it ends, every write checked
// (OutputFile.hpp: a full disk stops the app naming the file).
class CsvFile {
public:
    CsvFile(const std::filesystem::path& file, const std::string& header);
    template <class T> CsvFile& operator<<(const T& value) {
        buffer_ << value;
        writeLines();
        return *this;
    }

private:
    void writeLines();
    AppendedFile file_;
    std::ostringstream buffer_;
};

// Open postProcessing/<file> under the case, with a header row.
CsvFile openCsv(const std::filesystem::path& caseDir, const std::string& file, const std::string& header);

// A study: its sub-dictionary and the case folder.
using Study = void (*)(const Dict& study, const std::filesystem::path& caseDir);

// Runs the studies that system/<dictFile> lists under `studies:` (only the one
// of -study when given), in the file's order, on the worker threads of
// -threads (default 1). A study name not in `known` is an error listing them.
int runStudies(const ArgList& args, const std::string& dictFile, const std::map<std::string, Study>& known);

} // namespace mag::bench
