// induction: demag (modules/induction/demag): the demagnetization tensor from
// the mesh against Aharoni's prism factors and the sphere's 1/3 (through the
// magnetization a body takes in a uniform applied field), a soft sphere in a
// gradient field against V G M0 with M0 = 3 chi/(chi + 3) H (exact: uniform M
// is exact for a sphere in a linear field), saturation, and bad materials.
#include "caseFixture.hpp"

#include <magFoam/Case.hpp>
#include <magFoam/Error.hpp>
#include <magFoam/MagneticSystem.hpp>
#include <oracles/demagOracle.hpp>

#include <catch2/catch.hpp>

using namespace mag;
using Catch::Matchers::Contains;

namespace {

// One soft body of `geometry` in `applied`; returns the converged body.
Body softBody(const std::string& geometry, const std::string& material, const std::string& applied,
              const std::string& orientation = "", Wrench* wrench = nullptr) {
    magtest::TempCase c;
    c.write("system/controlDict.yaml", "endTime: 0.01\ndeltaT: 0.001\n");
    c.write("system/magSchemes.yaml", "field: {type: MBM}\ninduction: {type: demag, tolerance: 1e-10}\n");
    c.write("constant/materials.yaml", "steel: {model: soft, density: 7850, " + material + "}\n");
    c.write("constant/bodies.yaml", "bodies:\n  - {name: iron, geometry: " + geometry +
                                        ", material: steel, position: [0.001, 0.002, 0.003]" + orientation + "}\n");
    c.write("constant/appliedField.yaml", applied);
    Case k = Case::read(c.dir());
    MagneticSystem s(k);
    const InductionReport r = s.converge(k.bodies());
    REQUIRE(r.converged);
    if (wrench) *wrench = s.wrenches(k.bodies()).at(0);
    return k.bodies().at(0);
}

} // namespace

TEST_CASE("demag: N of a box from its mesh equals Aharoni's prism factors, N of a sphere 1/3", "[demag]") {
    // A linear body of chi = 1e9 in a uniform H takes M = (I/chi + N)^-1 H, so
    // H_i / M_i - 1/chi is N_ii. The mesh route converges slowly at edges (A's
    // gradient is log-singular there): at the default split 4 x 4, Gauss 8 x 8
    // a cube's N is 3.9e-6 off 1/3 and this box's 7e-6 off Aharoni (measured;
    // docs/physics.md#demag); the issue asks for 1e-3.
    const Eigen::Vector3d exact = oracle::prismDemagFactors(Eigen::Vector3d(0.005, 0.01, 0.015));
    for (int axis = 0; axis < 3; ++axis) {
        Vec3 B = Vec3::Zero();
        B[axis] = 1e-3;
        const std::string field = "type: uniform\nB: [" + std::to_string(B.x()) + ", " + std::to_string(B.y()) + ", " +
                                  std::to_string(B.z()) + "]\n";
        const Body b = softBody("{box: {size: [0.01, 0.02, 0.03]}}", "chi: 1e9, Js: 1e9, saturation: false", field);
        const Vec3 M = b.magnetization();
        INFO("axis " << axis << ": M " << M.transpose());
        CHECK(B[axis] / mu0 / M[axis] - 1e-9 == Approx(exact[axis]).margin(1e-5));
        CHECK(std::abs(M[(axis + 1) % 3]) + std::abs(M[(axis + 2) % 3]) < 1e-5 * std::abs(M[axis]));
    }
    const Body s = softBody("{sphere: {radius: 0.005, subdivisions: 3}}", "chi: 1e9, Js: 1e9, saturation: false",
                            "type: uniform\nB: [0, 0, 0.001]\n");
    CHECK(0.001 / mu0 / s.magnetization().z() == Approx(1.0 / 3.0).margin(1e-5));
}

TEST_CASE("demag: a soft sphere in a gradient field feels V G M0, M0 = 3 chi/(chi + 3) H", "[demag]") {
    // B(r) = B0 + G r with B0 = 1 mT along z: linear, so the volume average is
    // the centre value and the exact M is uniform; 1 % is the bar, the
    // mesh (icosphere 4 has 0.3 % less volume than the ball) is inside it.
    const std::string field = "type: gradient\nB: [0.0002, 0, 0.001]\n"
                              "gradient: [[-0.05, 0, 0.02], [0, -0.05, 0], [0.02, 0, 0.1]]\n";
    for (double chi : {5.0, 1000.0}) {
        INFO("chi " << chi);
        Wrench w;
        const Body b = softBody("{sphere: {radius: 0.005, subdivisions: 4}}",
                                "chi: " + std::to_string(chi) + ", Js: 2.0", field, "", &w);
        Mat3 G;
        G << -0.05, 0, 0.02, 0, -0.05, 0, 0.02, 0, 0.1;
        const Vec3 c(0.001, 0.002, 0.003);
        const Vec3 H = (Vec3(0.0002, 0, 0.001) + G * c) / mu0;
        const Vec3 M0 = 3 * chi / (chi + 3) * H;
        const double V = b.shape->volume;
        CHECK((b.magnetization() - M0).norm() < 1e-4 * M0.norm());
        CHECK((w.force - V * G * M0).norm() < 0.01 * (V * G * M0).norm());
    }
    // Saturated: B0 = 1.5 T, Js = 2 T: M = Ms along H.
    Wrench w;
    const Body b = softBody("{sphere: {radius: 0.005, subdivisions: 3}}", "chi: 1000, Js: 2.0",
                            "type: gradient\nB: [0, 0, 1.5]\ngradient: [[-0.5, 0, 0], [0, -0.5, 0], [0, 0, 1]]\n",
                            "", &w);
    const double Ms = 2.0 / mu0;
    CHECK(b.magnetization().norm() == Approx(Ms).epsilon(1e-3));
    const Vec3 F = b.shape->volume * Vec3(0, 0, 1.0 * b.magnetization().z());
    CHECK((w.force - F).norm() < 0.01 * F.norm());
    CHECK(w.force.z() == Approx(b.shape->volume * Ms).epsilon(0.01));
}

TEST_CASE("demag: a soft sphere in a uniform field feels no force and no torque", "[demag]") {
    Wrench w;
    const Body b = softBody("{sphere: {radius: 0.005, subdivisions: 3}}", "chi: 1000, Js: 2.0",
                            "type: uniform\nB: [0.003, -0.002, 0.001]\n", "", &w);
    const double scale = b.magneticMoment().norm() * 0.0037;  // |m| |B|
    CHECK(w.force.norm() == 0);                                 // G = 0
    // M is along B up to the mesh's anisotropy of N (~1e-7 of 1/3): measured 1e-7.
    CHECK(w.totalTorque().norm() < 1e-6 * scale);
}

TEST_CASE("demag: bad soft materials name the key", "[demag][badInput]") {
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"chi: -1, Js: 2", "chi must be > 0"},
        {"mur: 0.5, Js: 2", "mur must be > 1"},
        {"chi: 100, Js: 0", "Js must be > 0"},
        {"chi: 100, mur: 101, Js: 2", "one of them"},
        {"Js: 2", "give the susceptibility chi"},
        {"k: 5, Js: 2", "k and alpha are LLG's"},
        {"chi: 100, Js: 2, saturation: 3", "saturation"},
    };
    for (const auto& [material, message] : cases) {
        INFO(material);
        std::string what;
        try {
            (void)softBody("{sphere: {radius: 0.005, subdivisions: 2}}", material, "type: uniform\nB: [0, 0, 0.001]\n");
        } catch (const InputError& e) {
            what = e.what();
        }
        CHECK_THAT(what, Contains("materials.yaml"));
        CHECK_THAT(what, Contains(message));
    }
}
