// Paper Fig. 6 as shipped in cases/fig6-twoCubes (hybrid MBM, Amperian
// overlap, ODE), shortened to 1 s: the blue cube is attracted, hits the fixed
// red cube and must come to rest on it without the contact or the field
// creating energy.
#include "caseFixture.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <sstream>

namespace {

std::vector<std::vector<std::string>> readCsv(const std::filesystem::path& file, std::vector<std::string>& header) {
    std::ifstream in(file);
    std::string line;
    std::vector<std::vector<std::string>> rows;
    auto split = [](const std::string& l) {
        std::vector<std::string> out;
        std::stringstream ss(l);
        for (std::string c; std::getline(ss, c, ',');) out.push_back(c);
        return out;
    };
    std::getline(in, line);
    header = split(line);
    while (std::getline(in, line)) rows.push_back(split(line));
    return rows;
}

double column(const std::vector<std::string>& header, const std::vector<std::string>& row, const std::string& name) {
    for (std::size_t i = 0; i < header.size(); ++i)
        if (header[i] == name) return std::stod(row[i]);
    FAIL("no column " << name);
    return 0;
}

} // namespace

TEST_CASE("fig6: the attracted cube comes to rest on the fixed one, no energy created", "[solver][fig6]") {
    magtest::TempCase c;
    const std::filesystem::path src = std::filesystem::path(MAG_SOURCE_DIR) / "cases/fig6-twoCubes";
    for (const char* f : {"constant/materials.yaml", "constant/bodies.yaml", "constant/rigidBody.yaml",
                          "system/magSchemes.yaml"})
        std::filesystem::copy_file(src / f, c.path(f), std::filesystem::copy_options::overwrite_existing);
    c.write("system/controlDict.yaml", "endTime: 1\ndeltaT: 0.0001\nwriteInterval: 0.001\n");
    const std::string cmd = "cd '" + c.dir().string() + "' && '" + magtest::appPath("magFoam") + "' > log 2>&1";
    REQUIRE(std::system(cmd.c_str()) == 0);

    std::vector<std::string> eh, bh;
    const auto energy = readCsv(c.path("postProcessing/energy.csv"), eh);
    const auto bodies = readCsv(c.path("postProcessing/bodies.csv"), bh);
    REQUIRE(energy.size() == 1001);

    // Energy bound: the kinetic energy never exceeds the work the field and
    // gravity have done, i.e. the total never rises above its start. ODE's
    // push-out of a penetration is capped at 0.1 m/s (ODE backend
    // maxCorrectingVelocity), which may add at most m v^2 / 2 = 3.75e-5 J
    // (m = 7.5 g) at a contact event: that is the allowed excess.
    const double E0 = column(eh, energy.front(), "total");
    const double allowed = 0.5 * 7.5e-3 * 0.1 * 0.1;
    double maxExcess = -1e300, maxKinetic = 0;
    for (const auto& row : energy) {
        const double total = column(eh, row, "total");
        REQUIRE(std::isfinite(total));
        maxExcess = std::max(maxExcess, total - E0);
        maxKinetic = std::max(maxKinetic, column(eh, row, "kinetic"));
    }
    CHECK(maxExcess <= allowed);
    CHECK(maxKinetic > 1e-3);  // it did fall: ~0.05 J of field work at impact

    // At rest on the red cube (top face at z = 10 mm, blue centre 5 mm above):
    // gap within 5 um (ODE keeps a 1 um contact layer), tilt below 0.5 deg,
    // speed below 1e-6 m/s over the last 0.1 s.
    for (const auto& row : bodies) {
        if (row[1] != "blue" || column(bh, row, "time") < 0.9) continue;
        CHECK(std::abs(column(bh, row, "z") - 0.015) < 5e-6);
        const double qx = column(bh, row, "qx"), qy = column(bh, row, "qy");
        const double tilt = std::acos(std::clamp(1 - 2 * (qx * qx + qy * qy), -1.0, 1.0)) * 180 / M_PI;
        CHECK(tilt < 0.5);
        const double v = std::hypot(column(bh, row, "vx"), column(bh, row, "vy"), column(bh, row, "vz"));
        CHECK(v < 1e-6);
    }
}

// The paper's comparison (Fig. 6c vs 6d) with contacts that allow
// interpenetration (cases/fig6-twoCubes, constant/rigidBody.penetrating.yaml):
// the same case, shortened to 0.3 s, once with the default field and once
// with EDM n = 5. MBM stays bounded and rests; EDM's force diverges when the
// dipoles close in and the cube is shot away, without NaN or crash.
namespace {

struct RunSummary {
    double maxExcess = -1e300; // max over write times of total energy - start (J)
    double maxSpeed = 0;       // blue cube, m/s
    double finalGap = 0;       // blue centre z - 15 mm (m)
};

RunSummary runPenetrating(const std::string& schemes,
                          const std::string& rigidBody = "constant/rigidBody.penetrating.yaml") {
    magtest::TempCase c;
    const std::filesystem::path src = std::filesystem::path(MAG_SOURCE_DIR) / "cases/fig6-twoCubes";
    for (const char* f : {"constant/materials.yaml", "constant/bodies.yaml"})
        std::filesystem::copy_file(src / f, c.path(f), std::filesystem::copy_options::overwrite_existing);
    std::filesystem::copy_file(src / rigidBody, c.path("constant/rigidBody.yaml"),
                               std::filesystem::copy_options::overwrite_existing);
    std::filesystem::copy_file(src / ("system/" + schemes), c.path("system/magSchemes.yaml"),
                               std::filesystem::copy_options::overwrite_existing);
    c.write("system/controlDict.yaml", "endTime: 0.3\ndeltaT: 0.001\nwriteInterval: 0.001\n");
    const std::string cmd = "cd '" + c.dir().string() + "' && '" + magtest::appPath("magFoam") + "' > log 2>&1";
    REQUIRE(std::system(cmd.c_str()) == 0);
    std::vector<std::string> eh, bh;
    const auto energy = readCsv(c.path("postProcessing/energy.csv"), eh);
    const auto bodies = readCsv(c.path("postProcessing/bodies.csv"), bh);
    REQUIRE(energy.size() == 301);
    RunSummary s;
    const double E0 = column(eh, energy.front(), "total");
    for (const auto& row : energy) {
        const double total = column(eh, row, "total");
        REQUIRE(std::isfinite(total));
        s.maxExcess = std::max(s.maxExcess, total - E0);
    }
    for (const auto& row : bodies) {
        if (row[1] != "blue") continue;
        const double v = std::hypot(column(bh, row, "vx"), column(bh, row, "vy"), column(bh, row, "vz"));
        REQUIRE(std::isfinite(v));
        s.maxSpeed = std::max(s.maxSpeed, v);
        s.finalGap = column(bh, row, "z") - 0.015;
    }
    return s;
}

} // namespace

TEST_CASE("fig6 with penetrating contacts: MBM rests, EDM diverges without crashing", "[solver][fig6]") {
    const RunSummary mbm = runPenetrating("magSchemes.yaml");
    const RunSummary edm = runPenetrating("magSchemes.EDM.yaml");
    INFO("MBM: excess " << mbm.maxExcess << " J, max speed " << mbm.maxSpeed << " m/s, final gap " << mbm.finalGap);
    INFO("EDM: excess " << edm.maxExcess << " J, max speed " << edm.maxSpeed << " m/s, final gap " << edm.finalGap);
    // MBM: no energy created beyond ODE's capped push-out (m (0.1 m/s)^2 / 2,
    // as above); rests within 1 mm of contact (measured: 0.096 mm deep, soft
    // contacts); the impact speed is what 0.05 J of field work gives (~3 m/s).
    CHECK(mbm.maxExcess <= 0.5 * 7.5e-3 * 0.1 * 0.1);
    CHECK(std::abs(mbm.finalGap) < 1e-3);
    CHECK(mbm.maxSpeed < 5);
    // EDM: the instability is the point of the comparison. The field can do at
    // most ~0.1 J of work on the way down (MBM's total drop); EDM creating
    // more than 1 J, 10x that, is the divergence the paper shows (measured:
    // +3.6e7 J, 5.8e4 m/s in the full case; the path depends on the run).
    CHECK(edm.maxExcess > 1.0);
    CHECK(edm.maxSpeed > 100);
}

TEST_CASE("fig6 on Bullet's penetrating contacts: MBM stays bounded, EDM diverges", "[solver][fig6][bulletBackend]") {
    // The same comparison with the Bullet backend's contact springs
    // (constant/rigidBody.bullet-penetrating.yaml: 2e4 N/m, 20 N s/m).
    const std::string bullet = "constant/rigidBody.bullet-penetrating.yaml";
    const RunSummary mbm = runPenetrating("magSchemes.yaml", bullet);
    const RunSummary edm = runPenetrating("magSchemes.EDM.yaml", bullet);
    INFO("MBM: excess " << mbm.maxExcess << " J, max speed " << mbm.maxSpeed << " m/s, final gap " << mbm.finalGap);
    INFO("EDM: excess " << edm.maxExcess << " J, max speed " << edm.maxSpeed << " m/s, final gap " << edm.finalGap);
    // MBM: no energy created (the springs are damped and Bullet adds no
    // push-out speed: measured at most 0 J above the start), within 1 mm of
    // contact (measured 0.50 mm deep), the impact speed of ~0.05 J of field work.
    CHECK(mbm.maxExcess <= 1e-9);
    CHECK(std::abs(mbm.finalGap) < 1e-3);
    CHECK(mbm.maxSpeed < 5);
    // EDM: more than 10x the field's possible work (measured +18 J, 59 m/s).
    CHECK(edm.maxExcess > 1.0);
}
