// tolerance: is the adaptive rule's tolerance honest, and what does accuracy cost?
// Two 1 cm, 1 T cubes in placements from separated through touching to overlapping;
// for each, the adaptive rule at every requested tolerance and the fixed rules (gauss,
// the paper's regular) at every n: force error against an independent reference
// (reference/oracles: one-sided Akoun-Yonnet for parallel pairs, the adaptive
// Gauss-Kronrod contact integral for rotated ones, Akoun-Yonnet through overlap),
// samples and seconds per evaluation (single thread).
//
//   tolerance:
//     tolerances: [1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8]
//     gauss: [2, 4, 6, 10, 16, 24, 40]
//     regular: [1, 2, 5, 10, 20, 40]
//     minSeconds: 0.02     # per timing
#include "BenchMBM.hpp"

#include "AdaptiveQuadrature.hpp"
#include "InteractionWrench.hpp"
#include "SurfaceQuadrature.hpp"

#include <oracles/akounYonnet.hpp>
#include <oracles/contactQuadrature.hpp>

#include <magFoam/Log.hpp>
#include <magFoam/MeshPrimitives.hpp>

#include <cmath>

namespace mag::bench {

namespace {

struct Placement {
    std::string name, kind; // kind: separated, near, touching, overlap
    Vec3 centre;
    Mat3 R = Mat3::Identity();
    bool parallel = true;
};

std::vector<Placement> placements() {
    const double h = 0.005, pi = 3.141592653589793;
    auto rot = [](const Vec3& axis, double angle) { return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix(); };
    const Mat3 vertexDown = Eigen::Quaterniond::FromTwoVectors(Vec3(1, 1, 1).normalized(), Vec3(0, 0, -1)).toRotationMatrix();
    return {
        {"gap 5 mm", "separated", {0, 0, 0.015}},
        {"gap 1 mm", "separated", {0, 0, 0.011}},
        {"offset (3, 2) mm, gap 2 mm", "separated", {0.003, 0.002, 0.012}},
        {"offset (3, 2) mm, gap 1 mm", "separated", {0.003, 0.002, 0.011}},
        // its lowest vertex 1 mm (0.28 mm) above the source
        {"rotated, gap 1 mm", "separated", {0.001, 0, 0.0125 + 0.001 - 0.000282397374723}, rot(Vec3(1, 2, 0), 0.4), false},
        {"rotated, gap 0.28 mm", "near", {0.001, 0, 0.0125}, rot(Vec3(1, 2, 0), 0.4), false},
        {"gap 100 um", "near", {0, 0, 0.0101}},
        {"gap 10 um", "near", {0, 0, 0.01001}},
        {"gap 1 um", "near", {0, 0, 0.010001}},
        {"face on face", "touching", {0, 0, 0.01}},
        {"offset face (3, 2) mm", "touching", {0.003, 0.002, 0.01}},
        {"edge on face", "touching", {0, 0, h + h * std::sqrt(2.0)}, rot(Vec3::UnitX(), pi / 4), false},
        {"vertex on face", "touching", {0, 0, h + h * std::sqrt(3.0)}, vertexDown, false},
        {"rotated footprint 30 deg", "touching", {0, 0, 0.01}, rot(Vec3::UnitZ(), pi / 6), false},
        {"overlap 5 mm", "overlap", {0, 0, 0.005}},
        {"overlap offset", "overlap", {0.002, 0.001, 0.007}},
    };
}

Vec3 referenceForce(const Placement& p, double M) {
    const Eigen::Vector3d size = Eigen::Vector3d::Constant(0.01);
    if (p.kind == "overlap") return oracle::akounYonnetForce(size, Vec3::Zero(), size, p.centre, 1.0, 1.0);
    if (p.parallel) return oracle::akounYonnetForceOneSided(size, Vec3::Zero(), size, p.centre, 1.0, 1.0);
    oracle::Cuboid s, t;
    s.halfSize = t.halfSize = Eigen::Vector3d::Constant(0.005);
    s.M = Vec3(0, 0, M);
    t.centre = p.centre;
    t.R = p.R;
    t.M = p.R * Vec3(0, 0, M);
    return oracle::contactChargeWrench(s, t, p.centre, 1e-10).force;
}

} // namespace

void toleranceStudy(const Dict& study, const std::filesystem::path& caseDir) {
    const auto tolerances = study.get<std::vector<double>>("tolerances", {1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8});
    const auto gaussN = study.get<std::vector<double>>("gauss", {2, 4, 6, 10, 16, 24, 40});
    const auto regularN = study.get<std::vector<double>>("regular", {1, 2, 5, 10, 20, 40});
    const double minSeconds = study.get<double>("minSeconds", 0.02);
    study.reportUnused();
    const SurfaceMesh mesh = makeBox(Vec3::Constant(0.01));
    const mbm::PolyhedronTables cube(mesh.vertices, mesh.triangles);
    const double M = 1.0 / mu0;
    const Vec3 Ms(0, 0, M);
    auto csv = openCsv(caseDir, "tolerance.csv", "placement,kind,rule,parameter,forceError,samples,secondsPerEval");
    for (const Placement& p : placements()) {
        const Vec3 ref = referenceForce(p, M);
        Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
        T.linear() = p.R;
        T.translation() = p.centre;
        const Vec3 Mt = p.R * Ms;
        const mbm::OverlapModel model = mbm::OverlapModel::charge;
        auto row = [&](const char* rule, double parameter, const Vec3& F, std::size_t samples, double seconds) {
            csv << '"' << p.name << "\"," << p.kind << ',' << rule << ',' << parameter << ','
                << (F - ref).norm() / ref.norm() << ',' << samples << ',' << seconds << '\n';
        };
        for (double tol : tolerances) {
            mbm::AdaptiveSettings s;
            s.tolerance = tol;
            s.maxSamples = 5'000'000;
            mbm::AdaptiveResult r;
            const double sec = secondsPerCall([&] { r = mbm::adaptiveInteraction(cube, Ms, cube, T, Mt, p.centre, model, s); }, minSeconds);
            row("adaptive", tol, r.wrench.force, r.samples, sec);
        }
        for (const auto& [rule, list] : {std::pair{mbm::QuadratureRule::gauss, gaussN}, std::pair{mbm::QuadratureRule::regular, regularN}})
            for (double nn : list) {
                const int n = static_cast<int>(nn);
                const mbm::SurfaceQuadrature q = mbm::buildSurfaceQuadrature(cube, rule, n);
                std::vector<Vec3> points, normals;
                mbm::transformSamples(q, T, points, normals);
                Wrench w;
                const double sec = secondsPerCall([&] { w = mbm::interactionWrench(cube, Ms, points, q.weights, normals, Mt, p.centre, model); }, minSeconds);
                row(rule == mbm::QuadratureRule::gauss ? "gauss" : "regular", n, w.force, q.size(), sec);
            }
        spdlog::info("  tolerance: {} done", p.name);
    }
}

} // namespace mag::bench
