// switchError: error and cost of the hybrid evaluator against its switch
// threshold (a factor of the bounding radius, docs/physics.md#hybrid-switch), over the gaps of
// the Fig. 4 sweep.
//
//   switchError:
//     thresholds: [0, 0.25, 0.5, 1, 2, 3]
//     gaps: [0.0002, 0.001, 0.005, 0.01, 0.02, 0.05]
//     field: "{type: hybrid, switch: {type: boundingSphere, threshold: $t}}"
#include "BenchCommon.hpp"
#include "Studies.hpp"

#include <magFoam/Log.hpp>

namespace mag::bench {

void switchErrorStudy(const Dict& study, const std::filesystem::path& caseDir) {
    const auto thresholds = study.get<std::vector<double>>("thresholds");
    const auto gaps = study.get<std::vector<double>>("gaps");
    const std::string field = study.get<std::string>("field");
    const double minSeconds = study.get<double>("minSeconds", 0.02);
    study.reportUnused();
    auto csv = openCsv(caseDir, "switchError.csv", "threshold,gap,seconds,relError");
    for (double t : thresholds) {
        auto f = evaluator(substitute(field, "t", t));
        double worst = 0;
        for (double gap : gaps) {
            const auto pair = cubePair(gap);
            Wrench w;
            const double s = secondsPerCall([&] { w = f->interaction(pair[0], pair[1]); }, minSeconds);
            const Vec3 exact = exactCubeForce(pair[0], pair[1]);
            const double err = (w.force - exact).norm() / exact.norm();
            worst = std::max(worst, err);
            csv << t << ',' << gap << ',' << s << ',' << err << '\n';
        }
        spdlog::info("  threshold {:5.2f}: worst error {:9.2e}", t, worst);
    }
}

} // namespace mag::bench
