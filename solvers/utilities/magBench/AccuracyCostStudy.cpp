// accuracyCost: error of the force against the exact value versus CPU time
// per force evaluation, for every method and sampling rate, on the paper's
// cube pair at several gaps and on an offset pair and a rotated pair.
//
//   accuracyCost:
//     gaps: [0.0002, 0.001, 0.005, 0.02]        # m, coaxial Fig. 4 cubes
//     methods: [{label: ..., field: "...$n...", n: [...]}, ...]
#include "BenchCommon.hpp"
#include "Studies.hpp"

#include "oracles/chargeQuadrature.hpp"

#include <magFoam/Log.hpp>

namespace mag::bench {

namespace {

// Exact force on the second body of a cuboid pair by the independent charge
// quadrature (any orientation); converged to ~1e-10 for gaps >= 1 mm.
Vec3 quadratureForce(const Body& source, const Body& target) {
    auto cuboid = [](const Body& b) {
        oracle::Cuboid c;
        c.centre = b.position;
        c.halfSize = Vec3::Constant(0.5 * std::cbrt(b.shape->volume));
        c.R = b.orientation.toRotationMatrix();
        c.M = b.magnetization();
        return c;
    };
    return oracle::chargeQuadratureWrench(cuboid(source), cuboid(target), target.position, 16, 10).force;
}

std::vector<Configuration> configurations(const Dict& study) {
    std::vector<Configuration> out;
    for (double gap : study.get<std::vector<double>>("gaps")) {
        auto pair = cubePair(gap);
        const Vec3 F = exactCubeForce(pair[0], pair[1]);
        char name[64];
        std::snprintf(name, sizeof name, "gap %g cm", gap * 100);
        out.push_back({name, pair, F});
    }
    // Lateral offset (docs/physics.md#reference-values: (5, 0, 12) mm).
    std::vector<Body> offset = {cube("bottom", 0.01, 1.0, Vec3::Zero()), cube("top", 0.01, 1.0, Vec3(0.005, 0, 0.012))};
    out.push_back({"offset (5,0,12) mm", offset, exactCubeForce(offset[0], offset[1])});
    // Rotated and offset: upper cube turned 30 deg about (1, 1, 0).
    const Quat q(Eigen::AngleAxisd(pi / 6, Vec3(1, 1, 0).normalized()));
    std::vector<Body> rotated = {cube("bottom", 0.01, 1.0, Vec3::Zero()),
                                 cube("top", 0.01, 1.0, Vec3(0.003, 0.002, 0.016), q)};
    out.push_back({"rotated 30 deg, offset", rotated, quadratureForce(rotated[0], rotated[1])});
    return out;
}

} // namespace

void accuracyCostStudy(const Dict& study, const std::filesystem::path& caseDir) {
    const auto configs = configurations(study);
    const auto methods = readMethods(study);
    const double minSeconds = study.get<double>("minSeconds", 0.05);
    study.reportUnused();
    auto csv = openCsv(caseDir, "accuracyCost.csv", "configuration,method,n,seconds,relError,Fx,Fy,Fz,exactFx,exactFy,exactFz");
    for (const auto& m : methods) {
        std::vector<double> values = m.values.empty() ? std::vector<double>{0} : m.values;
        for (double v : values) {
            auto field = evaluator(substitute(m.field, "n", v));
            for (const auto& c : configs) {
                Wrench w;
                const double s = secondsPerCall([&] { w = field->interaction(c.bodies[0], c.bodies[1]); }, minSeconds);
                const double err = (w.force - c.exactForce).norm() / c.exactForce.norm();
                csv << '"' << c.name << "\",\"" << m.label << "\"," << v << ',' << s << ',' << err << ','
                    << w.force.x() << ',' << w.force.y() << ',' << w.force.z() << ',' << c.exactForce.x() << ','
                    << c.exactForce.y() << ',' << c.exactForce.z() << '\n';
                spdlog::info("  {:<24} {:<14} n={:<3} {:10.3e} s  error {:9.2e}", c.name, m.label, v, s, err);
            }
        }
    }
}

} // namespace mag::bench
