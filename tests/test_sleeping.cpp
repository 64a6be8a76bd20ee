// Sleeping bodies (docs/dynamics.md#sleeping) in magFoam runs: a cube magnet
// dropped onto a fixed disc magnet comes to rest and falls asleep; a second
// cube dropped from 30 cm wakes it as it comes near (its magnetic wrench
// changes) and both end asleep, stacked. The same scene without sleeping is
// the reference for the outcome; a split run with a restart is the reference
// for exactness.
#include "caseFixture.hpp"

#include <magFoam/Dictionary.hpp>
#include <magFoam/ResultsWriter.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>
#include <map>
#include <regex>
#include <sstream>
#include <sys/wait.h>

using Catch::Matchers::Contains;
using magtest::slurp;

namespace {

int runIn(const std::filesystem::path& dir, const std::string& log) { return magtest::runApp(dir, "magFoam", log); }

// The stack scene; `sleep`: the rigidBody.yaml line (empty: no sleeping).
void stack(magtest::TempCase& c, double endTime, const std::string& sleep, const std::string& extra = "") {
    std::ostringstream ctl;
    ctl << "endTime: " << endTime << "\ndeltaT: 0.00005\nadjustTimeStep: true\nmaxDeltaT: 0.01\n"
        << "writeInterval: 0.005\n" << extra;
    c.write("system/controlDict.yaml", ctl.str());
    c.write("system/magSchemes.yaml",
            "field: {type: hybrid, near: {type: MBM, quadrature: {type: gauss, n: 6}, overlap: amperian},\n"
            "        far: {type: EDM, n: 2}}\n");
    c.dropMagnet("  - {name: dropped, geometry: {box: {size: [0.006, 0.006, 0.006]}}, material: N42,\n"
                 "     magnetization: [0, 0, 1], position: [0.001, 0.001, 0.3]}\n",
                 sleep);
}

struct Row {
    double z = 0, speed = 0;
    int asleep = -1;
};

// The last bodies.csv row of each body.
std::map<std::string, Row> lastRows(const std::filesystem::path& csv) {
    std::istringstream in(slurp(csv));
    std::string line;
    std::getline(in, line);
    const bool sleepColumn = line.find(",asleep") != std::string::npos;
    std::map<std::string, Row> out;
    while (std::getline(in, line)) {
        std::vector<std::string> f;
        std::stringstream ss(line);
        for (std::string x; std::getline(ss, x, ',');) f.push_back(x);
        Row r;
        r.z = std::stod(f[4]);
        r.speed = std::hypot(std::stod(f[9]), std::stod(f[10]), std::stod(f[11]));
        if (sleepColumn) r.asleep = std::stoi(f[21]);
        out[f[1]] = r;
    }
    return out;
}

} // namespace

TEST_CASE("sleeping: a resting magnet sleeps, a dropped one wakes it, both end asleep on the stack", "[sleeping]") {
    magtest::TempCase awake, sleeping;
    stack(awake, 0.4, "");
    stack(sleeping, 0.4, "sleep: {}\n");
    REQUIRE(runIn(awake.dir(), "log") == 0);
    REQUIRE(runIn(sleeping.dir(), "log") == 0);
    const std::string log = slurp(sleeping.path("log"));
    INFO(log);
    // In this order: the cube sleeps, is woken by the approach, the stack sleeps.
    const auto first = log.find("asleep: cube\n");
    const auto woken = log.find("woken: cube (the magnetic wrench on 'cube' changed by ");
    const auto both = log.find("asleep: cube, dropped");
    REQUIRE(first != std::string::npos);
    REQUIRE(woken != std::string::npos);
    REQUIRE(both != std::string::npos);
    CHECK(first < woken);
    CHECK(woken < both);
    // Pairs of the sleeping cube and the fixed disc were kept, not evaluated.
    std::smatch m;
    REQUIRE(std::regex_search(log, m, std::regex("pairs evaluated ([0-9]+), kept from their last wrench ([0-9]+)")));
    CHECK(std::stol(m[2]) > 100);
    CHECK_THAT(log, Contains("0 warning(s)"));  // the audit: no energy rise, no large step
    // The outcome is the stack the run without sleeping ends in: heights to
    // the contact solver's softness (ODE's surface layer and cfm: ~1 um).
    const auto a = lastRows(awake.path("postProcessing/bodies.csv"));
    const auto s = lastRows(sleeping.path("postProcessing/bodies.csv"));
    for (const char* name : {"cube", "dropped"}) {
        INFO(name);
        CHECK(s.at(name).asleep == 1);
        CHECK(s.at(name).speed == 0.0);
        CHECK(a.at(name).speed < 1e-3);
        CHECK(s.at(name).z == Approx(a.at(name).z).margin(1e-5));
    }
    CHECK(s.at("cube").z == Approx(0.007).margin(1e-5));     // on the disc (4 mm + 3 mm)
    CHECK(s.at("dropped").z == Approx(0.013).margin(1e-5));  // on the cube
}

TEST_CASE("sleeping: islands of touching bodies, and a contact wakes a sleeping body", "[sleeping]") {
    // The cube comes to rest on the disc and sleeps while a ball of brass
    // (no magnetization: only a contact can tell the cube it is there) still
    // rolls by within reach of the bounding spheres; then a small brass cube falls
    // onto the sleeping cube. With islands of touching bodies (the default)
    // the cube sleeps first, alone: it touches only the fixed disc, and the
    // ball rolling by does not touch it. The falling cube's contact wakes it,
    // and the two fall asleep together. With islands of bounding
    // spheres (margin 4: the rolling ball's reach) the cube waits for the ball.
    // The small cube is dropped above where the magnet comes to rest
    // (x -0.5 mm, y -2.2 mm, turned 23 degrees: its path from the tilted start).
    const std::string balls =
        "  - {name: rolling, geometry: {sphere: {radius: 0.004}}, material: brass, magnetization: [0, 0, 1],\n"
        "     position: [0.02, -0.01, 0.004],\n"
        "     velocity: [0, 0.05, 0]}\n"
        "  - {name: falling, geometry: {box: {size: [0.003, 0.003, 0.003]}}, material: brass,\n"
        "     magnetization: [0, 0, 1], position: [-0.0005, -0.0022, 0.3]}\n";
    const auto run = [&](magtest::TempCase& c, const std::string& sleep) {
        stack(c, 0.4, sleep);        // controls and schemes of the stack scene,
        c.dropMagnet(balls, sleep);  // the balls instead of its second cube
        c.write("constant/materials.yaml",
                "N42: {model: permanent, Br: 1.3, density: 7500}\nbrass: {model: permanent, Br: 0, density: 8500}\n");
        const int status = runIn(c.dir(), "log");
        INFO(slurp(c.path("log")));
        REQUIRE(status == 0);
        return slurp(c.path("log"));
    };
    magtest::TempCase contacts, spheres;
    const std::string log = run(contacts, "sleep: {}\n");
    {
        INFO(log);
        const auto alone = log.find("asleep: cube\n");
        const auto woken = log.find("(a contact woke 'cube')");
        const auto together = log.find("asleep: cube, falling");
        REQUIRE(alone != std::string::npos);
        REQUIRE(woken != std::string::npos);
        REQUIRE(together != std::string::npos);
        CHECK(alone < woken);
        CHECK(woken < together);
        CHECK_THAT(log, Contains("0 warning(s)"));
        const auto rows = lastRows(contacts.path("postProcessing/bodies.csv"));
        for (const char* name : {"cube", "falling"}) {
            INFO(name);
            CHECK(rows.at(name).asleep == 1);
            CHECK(rows.at(name).speed == 0.0);
        }
        CHECK(rows.at("falling").z > 0.01);  // it lies on the cube (top at 10 mm), not beside it
    }
    // The rolling ball stays within reach of the cube's bounding sphere (25 mm)
    // to the end, never calm: with islands of bounding spheres it keeps the
    // cube, and the small cube on it, awake.
    const std::string sphereLog = run(spheres, "sleep: {islands: boundingSpheres, margin: 4}\n");
    INFO(sphereLog);
    CHECK(sphereLog.find("asleep: cube") == std::string::npos);
}

TEST_CASE("sleeping: a restart continues bit for bit, with bodies asleep and while they wake", "[sleeping][restart]") {
    // 0.1 s: the cube sleeps (its cached pairs are in sleep.yaml); 0.25 s:
    // after the wake, the dropped cube settling.
    for (const double split : {0.1, 0.25}) {
        INFO("split " << split);
        magtest::TempCase whole, parts;
        stack(whole, 0.4, "sleep: {}\n");
        stack(parts, split, "sleep: {}\n");
        REQUIRE(runIn(whole.dir(), "log") == 0);
        REQUIRE(runIn(parts.dir(), "log") == 0);
        CHECK(std::filesystem::exists(parts.path(mag::timeName(split) + "/sleep.yaml")));
        stack(parts, 0.4, "sleep: {}\n", "startFrom: latestTime\n");
        REQUIRE(runIn(parts.dir(), "log.restart") == 0);
        CHECK_THAT(slurp(parts.path("log.restart")), Contains("Restarting from"));
        CHECK(slurp(whole.path("0.4/bodies.yaml")) == slurp(parts.path("0.4/bodies.yaml")));
        CHECK(slurp(whole.path("0.4/sleep.yaml")) == slurp(parts.path("0.4/sleep.yaml")));
        CHECK(slurp(whole.path("postProcessing/bodies.csv")) == slurp(parts.path("postProcessing/bodies.csv")));
    }
}

TEST_CASE("sleeping: bad settings are errors naming the key", "[sleeping][badInput]") {
    magtest::TempCase c;
    stack(c, 0.01, "sleep: {enabled: true, time: -1}\n");
    REQUIRE(runIn(c.dir(), "log") == 1);
    CHECK_THAT(slurp(c.path("log")), Contains("rigidBody.yaml:5:") && Contains("sleep.time: must be >= 0"));
    stack(c, 0.01, "sleep: {enabled: true, speeed: 1}\n");
    REQUIRE(runIn(c.dir(), "log") == 1);
    CHECK_THAT(slurp(c.path("log")), Contains("unknown key 'speeed'") && Contains("speed"));
    stack(c, 0.01, "sleep: {islands: touching}\n");
    REQUIRE(runIn(c.dir(), "log") == 1);
    CHECK_THAT(slurp(c.path("log")), Contains("sleep.islands: unknown 'touching': expected contacts or boundingSpheres"));
}

TEST_CASE("sleeping: a soft part resting on a magnet sleeps and stays asleep", "[sleeping][induction]") {
    // A steel cube dropped onto the fixed disc magnet, magnetized by it. Once
    // asleep its pair with the disc is kept from its last wrench (a sleeping
    // body counts as fixed); evaluated as well, it would count twice, and the
    // doubled wrench woke the body at once (measured: Fig. 1's binder clips,
    // the island fell asleep and woke in the next step, the audit's total
    // dipping 0.44 J). Both induction models that carry a soft body's energy.
    const std::string induction = GENERATE(std::string("{type: LLG, tolerance: 1e-8, average: permanent}"),
                                           std::string("{type: demag, tolerance: 1e-8}"));
    INFO(induction);
    magtest::TempCase c;
    c.write("system/controlDict.yaml",
            "endTime: 0.3\ndeltaT: 0.00005\nadjustTimeStep: true\nmaxDeltaT: 0.01\nwriteInterval: 0.05\n");
    c.write("system/magSchemes.yaml",
            "field: {type: hybrid, near: {type: MBM, quadrature: {type: gauss, n: 4}, overlap: exterior},\n"
            "        far: {type: EDM, n: 2}}\ninduction: " + induction + "\n");
    c.dropMagnet("", "sleep: {}\n");
    const bool llg = induction.find("LLG") != std::string::npos;
    c.write("constant/materials.yaml", std::string("N42: {model: permanent, Br: 1.3, density: 7500}\n") +
                                           (llg ? "steel: {model: soft, k: 5, Js: 2.0, density: 7850}\n"
                                                : "steel: {model: soft, chi: 1000, Js: 2.0, density: 7850}\n"));
    std::string bodies = slurp(c.path("constant/bodies.yaml"));
    const std::string cube = "material: N42,\n     magnetization: [0, 0, 1], position: [0.003, 0, 0.025]";
    REQUIRE(bodies.find(cube) != std::string::npos);
    bodies.replace(bodies.find(cube), cube.size(), "material: steel,\n     position: [0.003, 0, 0.025]");
    c.write("constant/bodies.yaml", bodies);
    REQUIRE(runIn(c.dir(), "log") == 0);
    const std::string log = slurp(c.path("log"));
    INFO(log.substr(log.size() > 3000 ? log.size() - 3000 : 0));
    CHECK(log.find("asleep: cube") != std::string::npos);
    CHECK(log.find("woken") == std::string::npos);
    std::smatch m;
    REQUIRE(std::regex_search(log, m, std::regex("pairs evaluated ([0-9]+), kept from their last wrench ([0-9]+)")));
    CHECK(std::stol(m[2]) > 10);
    CHECK_THAT(log, Contains("0 warning(s)"));
}
