// divergence: force against the face gap from full overlap to 2 cm for each
// method (paper Figs. 4b, 4d) beside the exact Akoun-Yonnet force, and the
// relative errors (Fig. 4c). Shows where dipole sampling blows up.
//
//   divergence: {from: -0.01, to: 0.02, steps: 301, methods: [...]}
#include "BenchCommon.hpp"
#include "Studies.hpp"

#include <magFoam/Log.hpp>

#include <cmath>

namespace mag::bench {

void divergenceStudy(const Dict& study, const std::filesystem::path& caseDir) {
    const double from = study.get<double>("from", -0.01), to = study.get<double>("to", 0.02);
    const int steps = study.get<int>("steps", 301);
    if (steps < 2) study.fail("steps", "need at least 2 steps");
    const auto methods = readMethods(study);
    study.reportUnused();
    auto csv = openCsv(caseDir, "divergence.csv", "method,n,gap,Fz,exactFz,relError,finite");
    for (const auto& m : methods) {
        std::vector<double> values = m.values.empty() ? std::vector<double>{0} : m.values;
        for (double v : values) {
            auto field = evaluator(substitute(m.field, "n", v));
            int nonFinite = 0;
            double worst = 0;
            for (int k = 0; k < steps; ++k) {
                const double gap = from + (to - from) * k / (steps - 1);
                const auto pair = cubePair(gap);
                const Wrench w = field->interaction(pair[0], pair[1]);
                const double exact = exactCubeForce(pair[0], pair[1]).z();
                const bool finite = std::isfinite(w.force.z());
                nonFinite += finite ? 0 : 1;
                const double err = std::abs(w.force.z() - exact) / std::max(std::abs(exact), 1e-3);
                if (gap > 0) worst = std::max(worst, err);
                csv << '"' << m.label << "\"," << v << ',' << gap << ',' << w.force.z() << ',' << exact << ',' << err
                    << ',' << (finite ? 1 : 0) << '\n';
            }
            spdlog::info("  {:<14} n={:<3} worst error for d > 0: {:9.2e}; non-finite values: {}", m.label, v, worst,
                         nonFinite);
        }
    }
}

} // namespace mag::bench
