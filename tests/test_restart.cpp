// Restart is exact: a run 0 -> T and a run 0 -> T_split continued with
// startFrom: latestTime to T write the same numbers, bit for bit (the final
// bodies.yaml byte for byte, every CSV row). Split times are not multiples of
// the write interval: the first run writes the state at its endTime, and the
// models' own state (<time>/induction.yaml, <time>/rigidBody.yaml) with it.
// One case per piece of carried state: LLG's sub-magnetizations (soft iron),
// the free backend's verlet kick, ODE (the dropMagnet tutorial; a heap of
// cubes with quickStep: random generator and collision-space order). And
// <time>/bodies.yaml reads back exactly what was written.
#include "caseFixture.hpp"

#include <magFoam/Dictionary.hpp>
#include <magFoam/MeshPrimitives.hpp>
#include <magFoam/ResultsWriter.hpp>
#include <magFoam/ShapeFactory.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <random>
#include <sstream>
#include <sys/wait.h>

using mag::Vec3;

namespace {

int runIn(const std::filesystem::path& dir, const std::string& log) { return magtest::runApp(dir, "magFoam", log); }

using magtest::slurp;

// The CSV's lines without those at time t (the extra write of a split run).
std::vector<std::string> rowsExcept(const std::filesystem::path& csv, double t) {
    std::istringstream in(slurp(csv));
    std::vector<std::string> rows;
    for (std::string line; std::getline(in, line);)
        if (rows.empty() || std::abs(std::strtod(line.c_str(), nullptr) - t) > 1e-12) rows.push_back(line);
    return rows;
}

// controlDict with endTime; `extra` appended (startFrom).
std::string controlDict(double deltaT, double endTime, double writeInterval, const std::string& extra = "") {
    std::ostringstream os;
    os.precision(17);
    os << "deltaT: " << deltaT << "\nendTime: " << endTime << "\nwriteInterval: " << writeInterval << "\n" << extra;
    return os.str();
}

// Run `setup` 0 -> T in one case, and 0 -> split, then restart -> T in another;
// compare what both wrote.
template <class Setup>
void checkExactRestart(Setup setup, double deltaT, double T, double split, double writeInterval,
                       const std::vector<std::string>& stateFiles) {
    REQUIRE(std::abs(std::remainder(split, deltaT)) < 1e-6 * deltaT);       // a step
    REQUIRE(std::abs(std::remainder(split, writeInterval)) > deltaT / 2);  // not a write time
    magtest::TempCase whole, parts;
    setup(whole), setup(parts);
    whole.write("system/controlDict.yaml", controlDict(deltaT, T, writeInterval));
    parts.write("system/controlDict.yaml", controlDict(deltaT, split, writeInterval));
    REQUIRE(runIn(whole.dir(), "log.whole") == 0);
    REQUIRE(runIn(parts.dir(), "log.first") == 0);
    // The state at the split, with the models' files beside it.
    const auto splitFolder = mag::latestTimeFolder(parts.dir());
    REQUIRE(splitFolder.has_value());
    CHECK(mag::Dict::fromFile(*splitFolder / "bodies.yaml").get<double>("time") == Approx(split).margin(1e-12));
    for (const std::string& f : stateFiles) CHECK(std::filesystem::exists(*splitFolder / f));
    parts.write("system/controlDict.yaml", controlDict(deltaT, T, writeInterval, "startFrom: latestTime\n"));
    REQUIRE(runIn(parts.dir(), "log.restart") == 0);
    CHECK_THAT(slurp(parts.path("log.restart")), Catch::Matchers::Contains("Restarting from"));

    const auto a = mag::latestTimeFolder(whole.dir()), b = mag::latestTimeFolder(parts.dir());
    REQUIRE(a.has_value());
    REQUIRE(b.has_value());
    CHECK(a->filename() == b->filename());
    CHECK(slurp(*a / "bodies.yaml") == slurp(*b / "bodies.yaml"));
    for (const std::string& f : stateFiles) CHECK(slurp(*a / f) == slurp(*b / f));
    for (const char* csv : {"bodies.csv", "energy.csv", "induction.csv"}) {
        INFO(csv);
        const auto file = std::string("postProcessing/") + csv;
        REQUIRE(std::filesystem::exists(whole.path(file)) == std::filesystem::exists(parts.path(file)));
        if (!std::filesystem::exists(whole.path(file))) continue;
        const std::vector<std::string> x = rowsExcept(whole.path(file), split), y = rowsExcept(parts.path(file), split);
        CHECK(x.size() > 3);
        CHECK(x == y);
    }
}

} // namespace

TEST_CASE("restart is exact: a compound with a soft part, with LLG", "[restart][compound]") {
    // A magnet with a steel cap (one compound, docs/compound-bodies.md) falls
    // onto a steel plate: the cap's magnetization and LLG's state per part.
    auto setup = [](magtest::TempCase& c) {
        c.write("system/magSchemes.yaml", "field: {type: MBM, quadrature: {type: regular, n: 1}, overlap: amperian}\n"
                                          "induction: {type: LLG, tolerance: 1e-6, maxIterations: 200}\n");
        c.write("constant/materials.yaml", "N42: {model: permanent, Br: 1.3, density: 7500}\n"
                                           "steel: {model: soft, k: 5, Js: 2.0, density: 7850}\n");
        c.write("constant/bodies.yaml",
                "bodies:\n"
                "  - {name: plate, geometry: {box: {size: [0.03, 0.03, 0.002]}}, material: steel,\n"
                "     position: [0, 0, 0.001], motion: fixed}\n"
                "  - name: holder\n"
                "    parts:\n"
                "      - {geometry: {box: {size: [0.01, 0.01, 0.004]}}, material: steel, position: [0, 0, 0.007]}\n"
                "      - {geometry: {cylinder: {radius: 0.004, height: 0.005, segments: 24}}, material: N42,\n"
                "         magnetization: [0, 0, 1], position: [0, 0, 0.0025]}\n"
                "    position: [0.001, 0, 0.008]\n"
                "    orientation: {axis: [1, 0, 0], angle: 15}\n");
        c.write("constant/rigidBody.yaml", "type: ODE\ngravity: [0, 0, -9.81]\n"
                                           "contact: {friction: 0.4, restitution: 0.1}\nmaxTravel: 0.01\n");
    };
    checkExactRestart(setup, 1e-4, 0.015, 0.0087, 0.002, {"induction.yaml", "rigidBody.yaml"});
}

TEST_CASE("restart is exact: soft iron with LLG", "[restart]") {
    // tutorials/softIron, smaller: a steel block pulled onto a fixed magnet.
    auto setup = [](magtest::TempCase& c) {
        c.write("system/magSchemes.yaml", "field: {type: MBM, quadrature: {type: regular, n: 1}, overlap: amperian}\n"
                                          "induction: {type: LLG, tolerance: 1e-6, maxIterations: 200}\n");
        c.write("constant/materials.yaml", "N42: {model: permanent, Br: 1.3, density: 7500}\n"
                                           "steel: {model: soft, k: 5, Js: 2.0, density: 7850}\n");
        c.write("constant/bodies.yaml",
                "bodies:\n"
                "  - {name: magnet, geometry: {box: {size: [0.01, 0.01, 0.01]}}, material: N42,\n"
                "     magnetization: [1, 0, 0], position: [0, 0, 0.005], motion: fixed}\n"
                "  - {name: block, geometry: {box: {size: [0.006, 0.004, 0.003]}}, material: steel,\n"
                "     position: [0.01, 0.001, 0.0015], orientation: {axis: [0, 0, 1], angle: 20}}\n");
        c.write("constant/rigidBody.yaml", "type: ODE\ngravity: [0, 0, -9.81]\nground: {height: 0}\n"
                                           "contact: {friction: 0.4, restitution: 0.1}\nmaxTravel: 0.01\n");
    };
    checkExactRestart(setup, 1e-4, 0.02, 0.0137, 0.002, {"induction.yaml", "rigidBody.yaml"});

    // Writing converges a copy of the soft bodies for energy.csv; the model's
    // own state (LLG's sub-magnetizations) must come back, or the path would
    // depend on how often the run writes.
    magtest::TempCase often, rarely;
    setup(often), setup(rarely);
    often.write("system/controlDict.yaml", controlDict(1e-4, 0.02, 0.001));
    rarely.write("system/controlDict.yaml", controlDict(1e-4, 0.02, 0.01));
    REQUIRE(runIn(often.dir(), "log.often") == 0);
    REQUIRE(runIn(rarely.dir(), "log.rarely") == 0);
    for (const char* f : {"bodies.yaml", "induction.yaml"})
        CHECK(slurp(often.path(std::string("0.02/") + f)) == slurp(rarely.path(std::string("0.02/") + f)));
}

TEST_CASE("restart is exact: free backend, verlet", "[restart]") {
    // A tilted, spinning cube falling onto a fixed one (no contacts: through it).
    auto setup = [](magtest::TempCase& c) {
        c.twoCubes(0.004, "{type: MBM, quadrature: {type: gauss, n: 3}}");
        c.write("constant/bodies.yaml",
                "bodies:\n"
                "  - {name: bottom, geometry: {box: {size: [0.01, 0.01, 0.01]}}, material: N,\n"
                "     magnetization: [0, 0, 1], position: [0, 0, 0], motion: fixed}\n"
                "  - {name: top, geometry: {box: {size: [0.01, 0.008, 0.006]}}, material: N,\n"
                "     magnetization: [0, 0, 1], position: [0.002, 0, 0.014],\n"
                "     orientation: {axis: [1, 1, 0], angle: 25}, angularVelocity: [3, -2, 5]}\n");
        c.write("constant/rigidBody.yaml", "type: free\ngravity: [0, 0, -9.81]\nintegrator: verlet\nsubSteps: 2\n");
    };
    checkExactRestart(setup, 1e-3, 0.04, 0.023, 0.005, {"rigidBody.yaml"});
}

TEST_CASE("restart is exact: ODE, tutorials/dropMagnet", "[restart]") {
    // The tutorial as it is (0.3 s), continued from 0.1437 s, after the landing.
    auto setup = [](magtest::TempCase& c) {
        const std::filesystem::path tutorial = std::filesystem::path(MAG_SOURCE_DIR) / "tutorials/dropMagnet";
        for (const char* f : {"system/magSchemes.yaml", "constant/materials.yaml", "constant/bodies.yaml",
                              "constant/rigidBody.yaml"})
            c.write(f, slurp(tutorial / f));
    };
    checkExactRestart(setup, 5e-5, 0.3, 0.1437, 0.005, {"rigidBody.yaml"});
}

TEST_CASE("restart is exact: ODE, a heap of cubes with quickStep", "[restart]") {
    // Five cubes that attract each other and fall on the ground: contacts
    // between dynamic bodies (the space order changes as they move) and
    // quickStep's random constraint order.
    auto setup = [](magtest::TempCase& c) {
        c.write("system/magSchemes.yaml", "field: {type: MBM, quadrature: {type: gauss, n: 2}, overlap: amperian}\n");
        c.write("constant/materials.yaml", "N: {model: permanent, Br: 0.3, density: 7500}\n");
        std::string bodies = "bodies:\n";
        const char* poses[] = {"[0, 0, 0.003]", "[0.0065, 0.001, 0.004]", "[-0.001, 0.0068, 0.006]",
                               "[0.006, 0.007, 0.009]", "[0.003, 0.003, 0.014]"};
        const char* dirs[] = {"[0, 0, 1]", "[0, 0, -1]", "[1, 0, 0]", "[0, 1, 0]", "[0, 0, 1]"};
        for (int i = 0; i < 5; ++i)
            bodies += "  - {name: c" + std::to_string(i) +
                      ", geometry: {box: {size: [0.006, 0.006, 0.006]}}, material: N, magnetization: " + dirs[i] +
                      ", position: " + poses[i] + ", orientation: {axis: [1, 2, 3], angle: " +
                      std::to_string(10 * i) + "}}\n";
        c.write("constant/bodies.yaml", bodies);
        c.write("constant/rigidBody.yaml", "type: ODE\ngravity: [0, 0, -9.81]\nground: {height: 0}\n"
                                           "stepper: quickStep\niterations: 20\nseed: 7\n");
    };
    checkExactRestart(setup, 2e-4, 0.06, 0.0374, 0.005, {"rigidBody.yaml"});
}

TEST_CASE("restart is exact: ODE, paperclips colliding through their convex pieces", "[restart][convexPieces]") {
    // The Fig. 8 case's magnet and clip meshes (with the clip's pieces), LLG
    // steel; three clips pulled onto the magnet (at the split, 35 ms, all
    // three are within 26 um of it and moving at 0.1-0.3 m/s, measured).
    auto setup = [](magtest::TempCase& c) {
        const std::filesystem::path src = std::filesystem::path(MAG_SOURCE_DIR) / "cases/fig8-paperclips";
        for (const char* f : {"system/magSchemes.yaml", "constant/materials.yaml", "system/geometryDict.yaml",
                              "constant/rigidBody.yaml"})
            c.write(f, slurp(src / f));
        REQUIRE(magtest::runApp(c.dir(), "magMakeGeometry", "log.geo") == 0);
        REQUIRE(std::filesystem::exists(c.path("constant/geometry/paperclip.pieces.yaml")));
        c.write("constant/bodies.yaml",
                "bodies:\n"
                "  - {name: magnet, geometry: {file: geometry/barMagnet.stl}, material: N42,\n"
                "     magnetization: [1, 0, 0], position: [0, 0, 0.005], motion: fixed}\n"
                "  - {name: clip1, geometry: {file: geometry/paperclip.stl}, material: steel,\n"
                "     position: [0.0435, 0.004, 0.00046], orientation: {axis: [0, 0, 1], angle: 3}}\n"
                "  - {name: clip2, geometry: {file: geometry/paperclip.stl}, material: steel,\n"
                "     position: [0.012, 0.0, 0.0115], orientation: {axis: [0, 0, 1], angle: 10}}\n"
                "  - {name: clip3, geometry: {file: geometry/paperclip.stl}, material: steel,\n"
                "     position: [-0.010, 0.001, 0.0135], orientation: {axis: [0, 0, 1], angle: -20}}\n");
    };
    checkExactRestart(setup, 1e-4, 0.06, 0.0353, 0.005, {"rigidBody.yaml", "induction.yaml"});
}

TEST_CASE("bodies.yaml reads back exactly what was written", "[restart]") {
    magtest::TempCase c;
    std::mt19937_64 rng(42);
    std::uniform_real_distribution<double> u(-1, 1);
    auto shape = mag::makeShape(mag::makeBox(Vec3(0.01, 0.01, 0.01)), mag::ShapeKind{});
    std::vector<mag::Body> bodies(20);
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        mag::Body& b = bodies[i];
        b.name = "b";
        b.name += std::to_string(i);
        b.shape = shape;
        b.material.density = 7500;
        b.position = Vec3(u(rng), u(rng), u(rng)) * std::pow(10.0, -int(i % 7));
        b.orientation = mag::Quat(u(rng), u(rng), u(rng), u(rng)).normalized();
        b.velocity = Vec3(u(rng), u(rng), u(rng)) / 3;
        b.angularVelocity = Vec3(u(rng), u(rng), u(rng)) * 1e3 / 7;
        b.magnetizationBody = Vec3(u(rng), u(rng), u(rng)) * 1e6 / 3;
    }
    const double time = 0.1 + 0.2;  // 0.30000000000000004, written in folder "0.3"
    {
        mag::ResultsWriter writer(c.dir(), std::nullopt);
        writer.write(time, 1234567, bodies, std::vector<mag::Wrench>(bodies.size()), mag::Energies{});
    }
    std::vector<mag::Body> read = bodies;
    for (mag::Body& b : read) b.position = b.velocity = b.angularVelocity = b.magnetizationBody = Vec3::Zero();
    const mag::RestartState s = mag::readState(c.path("0.3/bodies.yaml"), read);
    CHECK(s.time == time);
    CHECK(s.step == 1234567);
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        INFO(bodies[i].name);
        CHECK(read[i].position == bodies[i].position);
        CHECK(read[i].orientation.coeffs() == bodies[i].orientation.coeffs());
        CHECK(read[i].velocity == bodies[i].velocity);
        CHECK(read[i].angularVelocity == bodies[i].angularVelocity);
        CHECK(read[i].magnetizationBody == bodies[i].magnetizationBody);
    }
}

namespace {

// Two cubes on the free backend: fast, and every state file a plain write.
void freeCubes(magtest::TempCase& c, double endTime, const std::string& extra = "") {
    c.twoCubes(0.004, "{type: MBM, quadrature: {type: gauss, n: 3}}");
    c.write("constant/rigidBody.yaml", "type: free\ngravity: [0, 0, -9.81]\n");
    c.write("system/controlDict.yaml", controlDict(5e-4, endTime, 0.0025, extra));
}

} // namespace

TEST_CASE("restart: the newest valid time folder, cut, empty and mislabelled ones are skipped and named",
          "[restart][badInput]") {
    magtest::TempCase whole, parts;
    freeCubes(whole, 0.02);
    freeCubes(parts, 0.01);
    REQUIRE(runIn(whole.dir(), "log.whole") == 0);
    REQUIRE(runIn(parts.dir(), "log.first") == 0);
    // What a crash or a full disk can leave behind, newest first: an empty
    // bodies.yaml, one cut in the middle, one that holds another time's
    // state, a CSV row cut off; and an "inf" folder, which is no time.
    const std::string good = slurp(parts.path("0.005/bodies.yaml"));
    parts.write("0.01/bodies.yaml", "");
    const std::string cut = slurp(parts.path("0.0075/bodies.yaml"));
    parts.write("0.0075/bodies.yaml", cut.substr(0, cut.size() / 2));
    parts.write("0.009/bodies.yaml", good);
    parts.write("inf/bodies.yaml", good);
    std::ofstream(parts.path("postProcessing/bodies.csv"), std::ios::app) << "0.0101,top,0.00";
    parts.write("system/controlDict.yaml", controlDict(5e-4, 0.02, 0.0025, "startFrom: latestTime\n"));
    REQUIRE(runIn(parts.dir(), "log.restart") == 0);
    const std::string log = slurp(parts.path("log.restart"));
    using Catch::Matchers::Contains;
    CHECK_THAT(log, Contains("skipping time folder 0.01/: ") && Contains("the file is empty"));
    CHECK_THAT(log, Contains("skipping time folder 0.009/: ") &&
                        Contains("holds the state of t = 0.005") && Contains("not of its folder's time"));
    CHECK_THAT(log, Contains("skipping time folder 0.0075/: "));
    // The app runs in the case folder (-case .): the folder as it names it.
    CHECK_THAT(log, Contains("Restarting from ./0.005 (step 10)"));
    // ... and continues as if nothing had happened.
    CHECK(slurp(whole.path("0.02/bodies.yaml")) == slurp(parts.path("0.02/bodies.yaml")));
    CHECK(slurp(whole.path("postProcessing/bodies.csv")) == slurp(parts.path("postProcessing/bodies.csv")));
    CHECK(slurp(whole.path("postProcessing/energy.csv")) == slurp(parts.path("postProcessing/energy.csv")));
}

TEST_CASE("restart: no valid time folder is an error naming each and why", "[restart][badInput]") {
    magtest::TempCase c;
    freeCubes(c, 0.0025);
    REQUIRE(runIn(c.dir(), "log.first") == 0);
    c.write("0/bodies.yaml", "");
    c.write("0.0025/bodies.yaml", "time: 0.0025\nstep: 2\nbodies: [");
    c.write("system/controlDict.yaml", controlDict(5e-4, 0.005, 0.0025, "startFrom: latestTime\n"));
    REQUIRE(runIn(c.dir(), "log.restart") == 1);
    const std::string log = slurp(c.path("log.restart"));
    using Catch::Matchers::Contains;
    CHECK_THAT(log, Contains("controlDict.yaml: startFrom: latestTime, but no time folder can be restarted from"));
    CHECK_THAT(log, Contains("  0/: ") && Contains("the file is empty"));
    CHECK_THAT(log, Contains("  0.0025/: ") && Contains("malformed YAML"));
}

TEST_CASE("restart reads the dictionaries anew: a changed Br takes effect", "[restart]") {
    magtest::TempCase c;
    freeCubes(c, 0.005);
    REQUIRE(runIn(c.dir(), "log.first") == 0);
    c.write("constant/materials.yaml", "N: {model: permanent, Br: 0.5, density: 7500}\n");
    c.write("system/controlDict.yaml", controlDict(5e-4, 0.01, 0.0025, "startFrom: latestTime\n"));
    REQUIRE(runIn(c.dir(), "log.restart") == 0);
    CHECK_THAT(slurp(c.path("log.restart")),
               Catch::Matchers::Contains("body 'top' takes its magnetization from constant/"));
    std::vector<mag::Body> bodies(2);
    bodies[0].name = "bottom", bodies[1].name = "top";
    mag::readState(c.path("0.01/bodies.yaml"), bodies);
    for (const mag::Body& b : bodies) {
        INFO(b.name);
        // Br / mu0, as Case computes it: to the last bits.
        CHECK(b.magnetizationBody.norm() == Approx(0.5 / mag::mu0).epsilon(1e-15));
    }
}

TEST_CASE("restart is exact: tutorials/dropMagnet as shipped (adaptive steps, sleeping), split at 0.145 and 0.185 s",
          "[restart]") {
    // The splits at which an earlier build's restart differed in the 8th
    // digit; write times, so the adaptive paths do not part (the first run's
    // endTime is a step of the whole run), and after the cube fell asleep.
    const std::filesystem::path tutorial = std::filesystem::path(MAG_SOURCE_DIR) / "tutorials/dropMagnet";
    auto setup = [&](magtest::TempCase& c, const std::string& endTime, const std::string& extra) {
        for (const char* f : {"system/magSchemes.yaml", "constant/materials.yaml", "constant/bodies.yaml",
                              "constant/rigidBody.yaml"})
            c.write(f, slurp(tutorial / f));
        std::string ctl = slurp(tutorial / "system/controlDict.yaml");
        const auto at = ctl.find("endTime: 0.3");
        REQUIRE(at != std::string::npos);
        c.write("system/controlDict.yaml", ctl.replace(at, 12, "endTime: " + endTime) + extra);
    };
    magtest::TempCase whole;
    setup(whole, "0.3", "");
    REQUIRE(runIn(whole.dir(), "log") == 0);
    for (const char* split : {"0.145", "0.185"}) {
        INFO("split " << split);
        magtest::TempCase parts;
        setup(parts, split, "");
        REQUIRE(runIn(parts.dir(), "log.first") == 0);
        setup(parts, "0.3", "startFrom: latestTime\n");
        REQUIRE(runIn(parts.dir(), "log.restart") == 0);
        CHECK(slurp(whole.path("0.3/bodies.yaml")) == slurp(parts.path("0.3/bodies.yaml")));
        CHECK(slurp(whole.path("postProcessing/bodies.csv")) == slurp(parts.path("postProcessing/bodies.csv")));
    }
}
