// induction: demag (modules/induction/demag): the demagnetization tensor from
// the mesh against Aharoni's prism factors and the sphere's 1/3 (through the
// magnetization a body takes in a uniform applied field), a soft sphere in a
// gradient field against V G M0 with M0 = 3 chi/(chi + 3) H (exact: uniform M
// is exact for a sphere in a linear field), saturation, and bad materials.
#include "caseFixture.hpp"

#include <magFoam/Case.hpp>
#include <magFoam/Error.hpp>
#include <magFoam/MagneticSystem.hpp>
#include <magFoam/ResultsWriter.hpp>
#include <oracles/demagOracle.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>

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
    // H_i / M_i - 1/chi is N_ii. At the default (graded fan, order 20) this
    // box's N is 7.5e-12 off Aharoni (measured; docs/physics.md#demag): 1e-9
    // leaves room for the solve's tolerance; the issue asks for 1e-3.
    const Eigen::Vector3d exact = oracle::prismDemagFactors(Eigen::Vector3d(0.005, 0.01, 0.015));
    for (int axis = 0; axis < 3; ++axis) {
        Vec3 B = Vec3::Zero();
        B[axis] = 1e-3;
        const std::string field = "type: uniform\nB: [" + std::to_string(B.x()) + ", " + std::to_string(B.y()) + ", " +
                                  std::to_string(B.z()) + "]\n";
        const Body b = softBody("{box: {size: [0.01, 0.02, 0.03]}}", "chi: 1e9, Js: 1e9, saturation: false", field);
        const Vec3 M = b.magnetization();
        INFO("axis " << axis << ": M " << M.transpose());
        CHECK(B[axis] / mu0 / M[axis] - 1e-9 == Approx(exact[axis]).margin(1e-9));
        CHECK(std::abs(M[(axis + 1) % 3]) + std::abs(M[(axis + 2) % 3]) < 1e-9 * std::abs(M[axis]));
    }
    const Body s = softBody("{sphere: {radius: 0.005, subdivisions: 3}}", "chi: 1e9, Js: 1e9, saturation: false",
                            "type: uniform\nB: [0, 0, 0.001]\n");
    // 1280 triangles: fan order 4 within the cost budget, 1.5e-7 off 1/3 (measured).
    CHECK(0.001 / mu0 / s.magnetization().z() == Approx(1.0 / 3.0).margin(1e-6));
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
    // The icosphere has the icosahedron's rotations, under which a symmetric
    // tensor is a multiple of I: its exact N is I/3. The rule for N respects
    // each triangle's symmetry, so the computed N is isotropic to rounding
    // (1e-15, measured) and M is along B: the bound, 1e-9 of |m||B|.
    CHECK(w.totalTorque().norm() < 1e-9 * scale);
}

TEST_CASE("demag: a soft prolate spheroid from an STL turns its long axis to a uniform field (Osborn)", "[demag]") {
    // 9 x 3 x 3 mm (semi-axes 4.5, 1.5, 1.5 mm along x, y, z), chi = 1000,
    // linear, in B = 5 mT at 45 degrees in the x-y plane. Exact for the
    // ellipsoid: M_i = chi H_i / (1 + chi N_i) on the principal axes (uniform M
    // is exact), torque mu0 V M x H. The mesh is the oracle's icosphere
    // (level 4, 5120 triangles) scaled, written as ASCII STL; its faceting
    // (volume 0.3 % low, N_x a few 1e-4 off) is inside the 3 %.
    const Eigen::Vector3d semi(0.0045, 0.0015, 0.0015);
    const oracle::TriMesh mesh = oracle::scaledMesh(oracle::icosphereMesh(4), semi);
    magtest::TempCase c;
    {
        std::ofstream stl(c.path("constant/geometry/spheroid.stl"));
        stl.precision(17);
        stl << "solid spheroid\n";
        for (const auto& t : mesh.triangles) {
            const Eigen::Vector3d &a = mesh.vertices[t[0]], &b = mesh.vertices[t[1]], &d = mesh.vertices[t[2]];
            const Eigen::Vector3d n = (b - a).cross(d - a).normalized();
            stl << "facet normal " << n.x() << ' ' << n.y() << ' ' << n.z() << "\n outer loop\n";
            for (const auto* v : {&a, &b, &d}) stl << "  vertex " << v->x() << ' ' << v->y() << ' ' << v->z() << '\n';
            stl << " endloop\nendfacet\n";
        }
        stl << "endsolid spheroid\n";
    }
    const double chi = 1000, B0 = 0.005;
    c.write("system/controlDict.yaml", "endTime: 0.01\ndeltaT: 0.001\n");
    c.write("system/magSchemes.yaml", "field: {type: MBM}\ninduction: {type: demag, tolerance: 1e-10}\n");
    c.write("constant/materials.yaml", "steel: {model: soft, density: 7850, chi: 1000, Js: 2.0, saturation: false}\n");
    c.write("constant/bodies.yaml", "bodies:\n  - {name: needle, geometry: {file: geometry/spheroid.stl}, "
                                    "material: steel, position: [0, 0, 0]}\n");
    const Vec3 B = B0 * Vec3(1, 1, 0).normalized();
    c.write("constant/appliedField.yaml", "type: uniform\nB: [" + std::to_string(B.x()) + ", " + std::to_string(B.y()) +
                                              ", 0]\n");
    Case k = Case::read(c.dir());
    MagneticSystem s(k);
    REQUIRE(s.converge(k.bodies()).converged);
    const Wrench w = s.wrenches(k.bodies()).at(0);

    const Eigen::Vector3d N = oracle::ellipsoidDemagFactors(semi);
    const Vec3 H = B / mu0;
    const Vec3 M(chi * H.x() / (1 + chi * N.x()), chi * H.y() / (1 + chi * N.y()), chi * H.z() / (1 + chi * N.z()));
    const double V = 4.0 / 3.0 * std::numbers::pi * semi.prod();
    const Vec3 torque = mu0 * V * M.cross(H);
    INFO("torque " << w.totalTorque().transpose() << ", exact " << torque.transpose() << ", relative error "
                   << (w.totalTorque() - torque).norm() / torque.norm());
    CHECK(torque.z() > 0); // x (the long axis) turns toward B
    CHECK((w.totalTorque() - torque).norm() < 0.03 * torque.norm());
    CHECK(w.force.norm() == 0); // uniform field
}

namespace {

// A 4 x 4 x 12 mm soft rod (long axis z) flies past a fixed 1 cm N42 cube
// (magnetized along z) at 3 m/s, its axis 10 mm from the cube's centre plane
// (3 mm from the side face at the closest), no contacts, no gravity, Delta t
// 2e-5 s: it is slung around the cube, up to 8 m/s. Returns (E_end - E_0) /
// peak kinetic energy from energy.csv.
magtest::EnergyRecord flyBy(const std::string& material, const std::string& schemes, const std::string& spin = "",
                            const std::string& extraBodies = "", std::string* log = nullptr) {
    magtest::TempCase c;
    c.write("system/controlDict.yaml", "endTime: 0.0266\ndeltaT: 2e-5\nwriteInterval: 0.0002\n");
    c.write("system/magSchemes.yaml", schemes);
    c.write("constant/materials.yaml", "N42: {model: permanent, Br: 1.3, density: 7500}\nsteel: " + material + "\n");
    c.write("constant/bodies.yaml",
            "bodies:\n"
            "  - {name: magnet, geometry: {box: {size: [0.01, 0.01, 0.01]}}, material: N42, magnetization: [0, 0, 1],\n"
            "     position: [0, 0, 0], motion: fixed}\n"
            "  - {name: rod, geometry: {box: {size: [0.004, 0.004, 0.012]}}, material: steel,\n"
            "     position: [-0.04, 0.01, 0], velocity: [3, 0, 0]" + spin + "}\n" + extraBodies);
    c.write("constant/rigidBody.yaml", "type: free\ngravity: [0, 0, 0]\n");
    REQUIRE(magtest::runApp(c.dir(), "magFoam") == 0);
    if (log) *log = magtest::slurp(c.path("log"));
    const magtest::EnergyRecord e = magtest::readEnergyCsv(c.path("postProcessing/energy.csv"));
    REQUIRE(e.rows > 100);
    return e;
}
double flyByDrift(const std::string& material, const std::string& schemes, const std::string& spin = "",
                  const std::string& extraBodies = "") {
    return flyBy(material, schemes, spin, extraBodies).drift();
}

} // namespace

TEST_CASE("demag: a soft rod slung past a magnet conserves energy, the drift falls with the tolerance", "[demag]") {
    // The bar: |drift| <= 1e-3 of the peak kinetic energy. Measured
    // (MBM adaptive tolerance 1e-4, the default): 2.3e-5; spinning at 200
    // rad/s: 1.7e-5. By tolerance: 1e-2 1.8e-4, 1e-5 6.0e-6.
    const std::string steel = "{model: soft, chi: 1000, Js: 2.0, density: 7850}";
    const std::string demag = "induction: {type: demag, tolerance: 1e-10}\n";
    const double drift = flyByDrift(steel, "field: {type: MBM}\n" + demag);
    CHECK(std::abs(drift) <= 1e-3);
    const double spinning = flyByDrift(steel, "field: {type: MBM}\n" + demag, ", angularVelocity: [0, 200, 0]");
    CHECK(std::abs(spinning) <= 1e-3);
    const double coarse = flyByDrift(steel, "field: {type: MBM, quadrature: {type: adaptive, tolerance: 1e-2}}\n" + demag);
    const double fine = flyByDrift(steel, "field: {type: MBM, quadrature: {type: adaptive, tolerance: 1e-5}}\n" + demag);
    INFO("drift " << drift << ", spinning " << spinning << ", tolerance 1e-2: " << coarse << ", 1e-5: " << fine);
    CHECK(std::abs(fine) < 0.1 * std::abs(coarse));
    // The same bar catches a model whose force is not a gradient: the paper's
    // LLG (field at the centre of mass) gains 3.6 % here (measured).
    const double llg = flyByDrift("{model: soft, k: 5, Js: 2.0, density: 7850}",
                                  "field: {type: MBM}\ninduction: {type: LLG, tolerance: 1e-10}\n");
    INFO("LLG drift " << llg);
    CHECK(std::abs(llg) > 1e-2);
}

TEST_CASE("LLG average: fields averaged as the energy sees them make LLG's induced forces conserve energy",
          "[LLG][demag]") {
    // The fly-by above with LLG relaxing in the averaged field (the field
    // integral of the pair energy over the rod) instead of the field at its
    // centre: M is then stationary for -M.I + mu0 V |M|^2/(2k), whose gradient
    // the forces are, so the drift falls to the demag model's bar (1e-3 of the
    // peak kinetic energy; measured below). The rod (k = 5, Js = 2 T) saturates
    // near the cube, so both branches of LLG's equilibrium are crossed.
    const std::string k5 = "{model: soft, k: 5, Js: 2.0, density: 7850}";
    const std::string mbm = "field: {type: MBM}\n";
    const double permanent =
        flyByDrift(k5, mbm + "induction: {type: LLG, tolerance: 1e-10, average: permanent}\n");
    INFO("LLG average permanent, one soft body: drift " << permanent);
    CHECK(std::abs(permanent) <= 1e-3);
    // A second soft rod beside the first, passing the cube's other side 7 mm
    // from it, magnetized by the cube and by the first: with average: all the
    // soft-soft field is averaged too; with average: permanent it is taken at
    // the centres and is not a gradient. The three drifts are printed for the
    // docs. (Both rods 3 mm from the cube meet behind it: a collision without
    // contacts, no test of the model.)
    const std::string block = "  - {name: rod2, geometry: {box: {size: [0.004, 0.004, 0.012]}}, material: steel,\n"
                              "     position: [-0.04, -0.014, 0], velocity: [3, 0, 0]}\n";
    const double all = flyByDrift(k5, mbm + "induction: {type: LLG, tolerance: 1e-10, average: all}\n", "", block);
    const double mixed =
        flyByDrift(k5, mbm + "induction: {type: LLG, tolerance: 1e-10, average: permanent}\n", "", block);
    const double centre = flyByDrift(k5, mbm + "induction: {type: LLG, tolerance: 1e-10}\n", "", block);
    std::printf("LLG fly-by drift of the peak kinetic energy: one soft body, average permanent %.2e; with a second "
                "rod: all %.2e, permanent %.2e, none %.2e\n",
                permanent, all, mixed, centre);
    INFO("with a second rod: all " << all << ", permanent " << mixed << ", none " << centre);
    CHECK(std::abs(all) <= 1e-3);
    CHECK(std::abs(centre) > 1e-2);
}

TEST_CASE("demag: a fixed soft body's pairs with fixed magnets count in the audit", "[demag][audit]") {
    // A steel block held fixed 2 mm beside the cube's other face: the rod
    // passing magnetizes it, so its energy with the (fixed) cube changes,
    // though neither moves. The step's wrenches leave pairs of two fixed
    // bodies out as constant unless a fixed body is soft
    // (MagneticSystem::fixedPairsConstant), and the audit, which sums the step's wrenches,
    // must count them as energy.csv (full wrenches) does: the audit's start
    // energy equals energy.csv's first total (the log prints 6 digits).
    // Without the block's pair the audit started 7.3e-3 J off (0.0104 J against
    // 0.0031 J), measured.
    const std::string block = "  - {name: block, geometry: {box: {size: [0.004, 0.004, 0.012]}}, material: steel,\n"
                              "     position: [0, -0.009, 0], motion: fixed}\n";
    std::string log;
    const magtest::EnergyRecord e = flyBy("{model: soft, chi: 1000, Js: 2.0, density: 7850}",
                                          "field: {type: MBM}\ninduction: {type: demag, tolerance: 1e-10}\n", "",
                                          block, &log);
    const std::size_t at = log.find("Audit: total energy ");
    REQUIRE(at != std::string::npos);
    const double auditStart = std::stod(log.substr(at + 20));
    INFO("audit start " << auditStart << " J, energy.csv " << e.first << " J; drift " << e.drift());
    CHECK(std::abs(auditStart - e.first) <= 1e-5 * std::abs(e.first));
    CHECK(std::abs(e.drift()) <= 1e-3); // the fly-by's bar; measured 3.8e-4
}

TEST_CASE("fieldIntegral: each evaluator's one-pass integral is -dU/dM_t of its own interaction energy", "[demag]") {
    // The base class takes three energies with unit target magnetizations;
    // the evaluators read the integral off one interaction(). Same samples
    // (regular rule, EDM, dipole pairs): equal to rounding. The adaptive rule
    // refines for the target's magnetization, so the two use other samples:
    // equal to its tolerance. Overlapping, touching and apart; a rotated target.
    const std::vector<std::pair<std::string, double>> fields = {
        {"{type: MBM, quadrature: {type: regular, n: 3}, overlap: charge}", 1e-12},
        {"{type: MBM, quadrature: {type: regular, n: 3}, overlap: amperian}", 1e-12},
        {"{type: MBM, quadrature: {type: regular, n: 3}, overlap: exterior}", 1e-12},
        {"{type: MBM, quadrature: {type: regular, n: 3, form: surfaceCharge}, overlap: exterior}", 1e-12},
        {"{type: MBM}", 1e-3},
        {"{type: EDM, n: 3}", 1e-12},
        {"{type: hybrid, near: {type: MBM, quadrature: {type: regular, n: 2}}, far: {type: EDM, n: 2}}", 1e-12}};
    for (const auto& [field, tol] : fields)
        for (double z : {0.006, 0.01, 0.03, 0.2}) {
            magtest::TempCase c;
            c.twoCubes(0.0, field);
            Case k = Case::read(c.dir());
            MagneticSystem s(k);
            Body& target = k.bodies()[1];
            target.position = Vec3(0.002, -0.001, z);
            target.orientation = Quat(Eigen::AngleAxisd(0.4, Vec3(1, 2, 3).normalized()));
            const FieldEvaluator& e = s.fieldEvaluator();
            const Vec3 fast = e.fieldIntegral(k.bodies()[0], target);
            const Vec3 slow = e.FieldEvaluator::fieldIntegral(k.bodies()[0], target);
            INFO(field << " at z = " << z << ": " << fast.transpose() << " against " << slow.transpose());
            CHECK(fast.norm() > 0);
            CHECK((fast - slow).norm() <= tol * slow.norm());
            // The map per unit source magnetization (one geometric pass for MBM's
            // regular rules) against three fieldIntegral() calls, and applied to
            // the source's magnetization against fieldIntegral() itself.
            const Mat3 map = e.fieldIntegralMap(k.bodies()[0], target);
            const Mat3 three = e.FieldEvaluator::fieldIntegralMap(k.bodies()[0], target);
            INFO("map\n" << map << "\nagainst three calls\n" << three);
            CHECK(map.norm() > 0);
            CHECK((map - three).norm() <= 1e-12 * three.norm());
            CHECK((map * k.bodies()[0].magnetization() - fast).norm() <= tol * fast.norm());
        }
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

// The demag variants shipped with the Fig. 1 and Fig. 9 cases
// (system/magSchemes.demag.yaml, constant/materials.demag.yaml), as a user
// runs them (RunFunctions runVariant), for their first 20 steps: the files
// read, every soft body is magnetized below its saturation and converged in
// every step, and the total energy does not rise above its start: the demag
// forces are an energy's gradient, and with the parts apart at the start
// nothing but the field and gravity acts yet. (Fig. 9's layout once started
// with four overlapping pairs that ODE pushed apart, adding energy unrelated
// to the induction; its bodies.yaml now turns them apart.)
TEST_CASE("demag variants of Figs. 1 and 9 run as shipped", "[demag][cases]") {
    const std::string name = GENERATE(std::string("fig1-binderClips"), std::string("fig9-crane"));
    INFO(name);
    magtest::TempCase c;
    const std::filesystem::path src = std::filesystem::path(MAG_SOURCE_DIR) / "cases" / name;
    std::filesystem::copy(src / "constant", c.path("constant"), std::filesystem::copy_options::recursive |
                                                                    std::filesystem::copy_options::overwrite_existing);
    std::filesystem::copy_file(src / "system/geometryDict.yaml", c.path("system/geometryDict.yaml"),
                               std::filesystem::copy_options::overwrite_existing);
    std::filesystem::copy_file(src / "system/magSchemes.demag.yaml", c.path("system/magSchemes.yaml"),
                               std::filesystem::copy_options::overwrite_existing);
    std::filesystem::copy_file(src / "constant/materials.demag.yaml", c.path("constant/materials.yaml"),
                               std::filesystem::copy_options::overwrite_existing);
    c.write("system/controlDict.yaml", "endTime: 0.002\ndeltaT: 0.0001\nwriteInterval: 0.0001\n");
    const std::string cmd = "cd '" + c.dir().string() + "' && '" + magtest::appPath("magMakeGeometry") +
                            "' > log.geo 2>&1 && '" + magtest::appPath("magFoam") + "' > log 2>&1";
    const int rc = std::system(cmd.c_str());
    const std::string log = magtest::slurp(c.path("log"));
    INFO(log.substr(log.size() > 3000 ? log.size() - 3000 : 0));
    REQUIRE(rc == 0);
    CHECK_THAT(log, Contains("demag (tolerance"));
    CHECK(log.find("not converged") == std::string::npos);

    // Every soft body magnetized, below saturation (mu0 |M| < Js: tanh never reaches it).
    Case cs = Case::read(c.dir());
    const auto latest = latestTimeFolder(c.dir());
    REQUIRE(latest);
    readState(*latest / "bodies.yaml", cs.bodies());
    for (const Body& b : cs.bodies()) {
        if (!b.soft()) continue;
        INFO(b.name);
        const double Js = b.material.property("Js");
        const double J = mu0 * b.magnetization().norm();
        CHECK(J > 0);
        CHECK(J < Js);
    }
    std::ifstream e(c.path("postProcessing/energy.csv"));
    std::string line;
    std::getline(e, line);
    double E0 = NAN, maxExcess = -1e300;
    int rows = 0;
    while (std::getline(e, line)) {
        double t, kin, grav, magE, tot;
        REQUIRE(std::sscanf(line.c_str(), "%lf,%lf,%lf,%lf,%lf", &t, &kin, &grav, &magE, &tot) == 5);
        if (std::isnan(E0)) E0 = tot;
        maxExcess = std::max(maxExcess, tot - E0);
        ++rows;
    }
    CHECK(rows == 21);
    INFO("most the total rose above its start: " << maxExcess << " J");
    CHECK(maxExcess <= 1e-10);
}
