// magBench table2's whole scenes (solvers/utilities/magBench/SceneRateStudy.cpp):
// the Fig. 6 case run to its endTime on a scratch copy, as magFoam runs it. The
// reference for the run is magFoam itself: the same case gives the same end
// state and step count; the rate is simulated time over the wall time measured.
#include "caseFixture.hpp"

#include <catch2/catch.hpp>

#include <fstream>
#include <sstream>

using Catch::Matchers::Contains;

namespace {

const std::filesystem::path fig6 = std::filesystem::path(MAG_SOURCE_DIR) / "cases/fig6-twoCubes";

std::vector<std::string> csvRows(const std::filesystem::path& file) {
    std::istringstream in(magtest::slurp(file));
    std::vector<std::string> rows;
    for (std::string line; std::getline(in, line);) rows.push_back(line);
    return rows;
}

} // namespace

TEST_CASE("magBench table2 scenes: a whole case run as magFoam runs it, simulated s per wall s", "[bench]") {
    magtest::TempCase bench, reference;
    bench.write("system/scenes.yaml", "studies:\n  table2:\n    scenes: {'" + fig6.string() +
                                          "': 4.5}\n    threads: [1]\n");
    REQUIRE(magtest::runApp(bench.dir(), "magBench", "log", "-dict scenes.yaml") == 0);
    const auto rows = csvRows(bench.path("postProcessing/table2Scenes.csv"));
    REQUIRE(rows.size() == 2);
    CHECK(rows[0] == "case,threads,simulatedSeconds,wallSeconds,steps,simulatedPerWall,paperSimulatedPerWall,ratio");
    std::vector<std::string> f;
    std::stringstream ss(rows[1]);
    for (std::string x; std::getline(ss, x, ',');) f.push_back(x);
    REQUIRE(f.size() == 8);
    CHECK(f[1] == "1");
    CHECK(std::stod(f[2]) == 10.0);
    const double wall = std::stod(f[3]), rate = std::stod(f[5]);
    CHECK(wall > 0);
    CHECK(rate == Approx(10.0 / wall).epsilon(1e-8));
    CHECK(std::stod(f[7]) == Approx(rate / 4.5).epsilon(1e-8));

    // The same case through magFoam: the same number of steps and the same end
    // state, bit for bit (the scratch copy is the case as shipped).
    std::filesystem::copy(fig6 / "constant", reference.path("constant"),
                          std::filesystem::copy_options::recursive | std::filesystem::copy_options::overwrite_existing);
    std::filesystem::copy(fig6 / "system", reference.path("system"),
                          std::filesystem::copy_options::recursive | std::filesystem::copy_options::overwrite_existing);
    REQUIRE(magtest::runApp(reference.dir(), "magFoam") == 0);
    const std::string log = magtest::slurp(reference.path("log"));
    CHECK_THAT(log, Contains("End: " + f[4] + " steps"));
    CHECK(magtest::slurp(bench.path("postProcessing/table2/fig6-twoCubes-threads1/10/bodies.yaml")) ==
          magtest::slurp(reference.path("10/bodies.yaml")));
}

TEST_CASE("magBench table2 scenes: a missing case is an error naming the key", "[bench]") {
    magtest::TempCase bench;
    bench.write("system/scenes.yaml", "studies:\n  table2:\n    scenes: {../noSuchCase: 4.5}\n    threads: [1]\n");
    CHECK(magtest::runApp(bench.dir(), "magBench", "log", "-dict scenes.yaml") != 0);
    const std::string log = magtest::slurp(bench.path("log"));
    CHECK_THAT(log, Contains("scenes.yaml"));
    CHECK_THAT(log, Contains("../noSuchCase"));
    CHECK_THAT(log, Contains("no case folder"));
}

TEST_CASE("magBench table2 cases: made meshes on a scratch copy, a backend from the case's own file for it",
          "[bench]") {
    // Fig. 9: its meshes come from magMakeGeometry and it ships
    // constant/rigidBody.bullet.yaml (convex pieces, rolling friction).
    const auto fig9 = std::filesystem::path(MAG_SOURCE_DIR) / "cases/fig9-crane";
    magtest::TempCase bench;
    bench.write("system/cases.yaml", "studies:\n  table2:\n    cases: ['" + fig9.string() +
                                         "']\n    steps: 2\n    repeats: 1\n    threads: [1]\n"
                                         "    backends: [ODE, Bullet]\n");
    REQUIRE(magtest::runApp(bench.dir(), "magBench", "log", "-dict cases.yaml") == 0);
    const std::string log = magtest::slurp(bench.path("log"));
    INFO(log);
    CHECK_THAT(log, Contains("fig9-crane: Bullet from constant/rigidBody.bullet.yaml"));
    CHECK(std::filesystem::exists(bench.path("postProcessing/table2Cases/fig9-crane/constant/geometry")));
    const auto rows = csvRows(bench.path("postProcessing/table2.csv"));
    REQUIRE(rows.size() == 3);
    CHECK_THAT(rows[1], Contains(",31,") && Contains(",ODE"));
    CHECK_THAT(rows[2], Contains(",31,") && Contains(",Bullet"));
}
