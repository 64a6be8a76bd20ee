#include "magFoam/BenchHarness.hpp"

#include "magFoam/Error.hpp"
#include "magFoam/Log.hpp"
#include "magFoam/Threads.hpp"

#include <algorithm>
#include <chrono>
#include <limits>

namespace mag::bench {

double secondsPerCall(const std::function<void()>& f, double minSeconds) {
    return bestSecondsPerCall(f, minSeconds, 1);
}

double bestSecondsPerCall(const std::function<void()>& f, double minSeconds, int repeats) {
    using clock = std::chrono::steady_clock;
    f();  // warm-up: builds the per-shape tables
    double best = std::numeric_limits<double>::infinity();
    for (int r = 0; r < std::max(repeats, 1); ++r) {
        long calls = 0;
        const auto t0 = clock::now();
        double elapsed = 0;
        do {
            f();
            ++calls;
            elapsed = std::chrono::duration<double>(clock::now() - t0).count();
        } while (elapsed < minSeconds);
        best = std::min(best, elapsed / static_cast<double>(calls));
    }
    return best;
}

CsvFile::CsvFile(const std::filesystem::path& file, const std::string& header) : file_(file, header, false) {
    buffer_.precision(10);
}

void CsvFile::writeLines() {
    const std::string text = buffer_.str();
    const std::size_t end = text.rfind('\n');
    if (end == std::string::npos) return;
    file_.append(std::string_view(text).substr(0, end + 1));
    buffer_.str(text.substr(end + 1));
    buffer_.seekp(0, std::ios::end);
}

CsvFile openCsv(const std::filesystem::path& caseDir, const std::string& file, const std::string& header) {
    return CsvFile(caseDir / "postProcessing" / file, header);
}

int runStudies(const ArgList& args, const std::string& dictFile, const std::map<std::string, Study>& known) {
    const auto dir = args.caseDir();
    setThreads(args.threads().value_or(1));
    const Dict dict = Dict::fromFile(dir / "system" / dictFile);
    const Dict studies = dict.sub("studies");
    dict.reportUnused();
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

} // namespace mag::bench
