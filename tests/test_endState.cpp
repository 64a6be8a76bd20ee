// magEndState (docs/rigid-bodies.md#end-state): a cube resting on a fixed
// cube is attached and at rest; one 5 mm away and moving is loose and moving;
// one sunk 2 mm into the base is reported as such; -check's exit code
// follows; bad options are clear errors.
#include "caseFixture.hpp"

#include <catch2/catch.hpp>

#include <fstream>

using Catch::Matchers::Contains;

namespace {

// A fixed 1 cm cube at the origin and a 1 cm cube above it; the state folder
// 0.1 places the top cube at height z (its centre) moving at speed v along x.
void writeCase(magtest::TempCase& c, double z, double v) {
    c.write("constant/materials.yaml", "N42: {model: permanent, Br: 1.3, density: 7500}\n");
    c.write("constant/bodies.yaml",
            "bodies:\n"
            "  - {name: base, geometry: {box: {size: [0.01, 0.01, 0.01]}}, material: N42,\n"
            "     magnetization: [0, 0, 1], position: [0, 0, 0], motion: fixed}\n"
            "  - {name: top, geometry: {box: {size: [0.01, 0.01, 0.01]}}, material: N42,\n"
            "     magnetization: [0, 0, 1], position: [0, 0, 0.02]}\n");
    c.write("system/controlDict.yaml", "endTime: 0.1\ndeltaT: 0.001\nwriteInterval: 0.1\n");
    c.write("0.1/bodies.yaml", "time: 0.1\nstep: 100\nbodies:\n"
                               "  - {name: base, position: [0, 0, 0], orientation: [1, 0, 0, 0], velocity: [0, 0, 0],\n"
                               "     angularVelocity: [0, 0, 0], magnetization: [0, 0, 1034507]}\n"
                               "  - {name: top, position: [0, 0, " + std::to_string(z) + "], orientation: [1, 0, 0, 0],\n"
                               "     velocity: [" + std::to_string(v) + ", 0, 0], angularVelocity: [0, 0, 0],\n"
                               "     magnetization: [0, 0, 1034507]}\n");
}

} // namespace

TEST_CASE("magEndState: attached, at rest, loose, moving and sunk in bodies", "[endState][app]") {
    struct Row {
        double z, v;
        bool ok;
        const char* state;
        double gap;
    };
    const Row rows[] = {
        {0.010, 0.0, true, "attached, at rest", 0.0},     // resting face on face
        {0.015, 0.01, false, "loose, moving", 0.005},     // 5 mm up, 1 cm/s
        {0.008, 0.0, false, "SUNK IN", 0.0},              // 2 mm into the base
    };
    for (const Row& r : rows) {
        magtest::TempCase c;
        writeCase(c, r.z, r.v);
        INFO("z = " << r.z);
        const int rc = magtest::runApp(c.dir(), "magEndState", "log", "-check");
        const std::string log = magtest::slurp(c.path("log"));
        INFO(log);
        CHECK(rc == (r.ok ? 0 : 1));
        CHECK_THAT(log, Contains(r.state));
        const std::string csv = magtest::slurp(c.path("postProcessing/endState.csv"));
        REQUIRE_THAT(csv, Contains("body,speed,nearest,gap,overlap,attached,atRest,sunkIn\ntop,"));
        double speed = 0, gap = 0, overlap = 0;
        int attached = 0, rest = 0, sunk = 0;
        const auto row = csv.substr(csv.find("top,"));
        char nearest[64];
        REQUIRE(std::sscanf(row.c_str(), "top,%lf,%63[^,],%lf,%lf,%d,%d,%d", &speed, nearest, &gap, &overlap, &attached,
                            &rest, &sunk) == 7);
        CHECK(std::string(nearest) == "base");
        CHECK(speed == Approx(r.v));
        CHECK(gap == Approx(r.gap).margin(1e-12));  // vertex-face distances of axis-aligned cubes: exact
        CHECK(overlap == Approx(r.z < 0.01 ? 0.002 : 0.0).margin(1e-12));
    }
}

TEST_CASE("magEndState: bad options and missing results are clear errors", "[endState][app][badInput]") {
    magtest::TempCase c;
    writeCase(c, 0.01, 0);
    CHECK(magtest::runApp(c.dir(), "magEndState", "log", "-attached fast") != 0);
    CHECK_THAT(magtest::slurp(c.path("log")), Contains("-attached fast") && Contains("expected a number"));
    CHECK(magtest::runApp(c.dir(), "magEndState", "log", "-time 7") != 0);
    CHECK_THAT(magtest::slurp(c.path("log")), Contains("-time 7") && Contains("not found"));
    std::filesystem::remove_all(c.path("0.1"));
    CHECK(magtest::runApp(c.dir(), "magEndState", "log") != 0);
    CHECK_THAT(magtest::slurp(c.path("log")), Contains("run magFoam first"));
}

TEST_CASE("etc/RunFunctions runRigidBodyVariant runs a case with another rigidBody.yaml and its end state",
          "[endState][app]") {
    magtest::TempCase c;
    writeCase(c, 0.0101, 0);  // the top cube 0.1 mm above the base
    std::filesystem::remove_all(c.path("0.1"));
    c.write("system/controlDict.yaml", "endTime: 0.02\ndeltaT: 0.0001\nwriteInterval: 0.01\n");
    c.write("system/magSchemes.yaml", "field: {type: MBM}\n");
    c.write("constant/rigidBody.alt.yaml", "type: ODE\ngravity: [0, 0, -9.81]\n");
    const std::string cmd = "cd '" + c.dir().string() + "' && PATH='" + (magtest::buildDir() / "bin").string() +
                            "':\"$PATH\" bash -c '. \"" + MAG_SOURCE_DIR +
                            "/etc/RunFunctions\" && runRigidBodyVariant alt rigidBody.alt.yaml' > log 2>&1";
    const int rc = std::system(cmd.c_str());
    INFO(magtest::slurp(c.path("log")) << magtest::slurp(c.path("alt/log.magFoam")));
    REQUIRE(rc == 0);
    // The variant folder has the other rigidBody.yaml, the run and its end state.
    CHECK(magtest::slurp(c.path("alt/constant/rigidBody.yaml")) == magtest::slurp(c.path("constant/rigidBody.alt.yaml")));
    CHECK(std::filesystem::exists(c.path("alt/0.02/bodies.yaml")));
    CHECK_THAT(magtest::slurp(c.path("alt/log.magEndState")), Contains("top") && Contains("base"));
    CHECK(std::filesystem::exists(c.path("alt/postProcessing/endState.csv")));
    // The case itself is untouched.
    CHECK_FALSE(std::filesystem::exists(c.path("0.02")));

    // With a schemes file as well: it becomes the variant's magSchemes.yaml.
    c.write("system/magSchemes.ext.yaml", "field: {type: MBM, overlap: exterior}\n");
    const std::string cmd2 = "cd '" + c.dir().string() + "' && PATH='" + (magtest::buildDir() / "bin").string() +
                             "':\"$PATH\" bash -c '. \"" + MAG_SOURCE_DIR +
                             "/etc/RunFunctions\" && runRigidBodyVariant ext rigidBody.alt.yaml magSchemes.ext.yaml' > log 2>&1";
    REQUIRE(std::system(cmd2.c_str()) == 0);
    CHECK(magtest::slurp(c.path("ext/system/magSchemes.yaml")) == magtest::slurp(c.path("system/magSchemes.ext.yaml")));
    CHECK_THAT(magtest::slurp(c.path("ext/log.magFoam")), Contains("overlap exterior"));
    CHECK(std::filesystem::exists(c.path("ext/0.02/bodies.yaml")));
}
