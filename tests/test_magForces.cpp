// magForces end to end: the rotation sweep's torque about the axis is minus the
// derivative of its energy column, the translation sweep keeps its CSV and
// values, bad sweeps end the app naming the key, and the converged
// magnetization of soft bodies is printed.
#include "caseFixture.hpp"

#include <magFoam/Types.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <sys/wait.h>

namespace {

using mag::Vec3;

using magtest::slurp;

int runMagForces(const magtest::TempCase& c, std::string& log) {
    const int rc = magtest::runApp(c.dir(), "magForces");
    log = slurp(c.path("log"));
    return rc;
}

// The rows of postProcessing/forces.csv for one body: the columns by name.
struct Csv {
    std::string header;
    std::vector<std::map<std::string, double>> rows;
};

Csv readForces(const magtest::TempCase& c, const std::string& body) {
    std::ifstream in(c.path("postProcessing/forces.csv"));
    REQUIRE(in);
    Csv out;
    std::getline(in, out.header);
    std::vector<std::string> names;
    {
        std::stringstream ss(out.header);
        for (std::string n; std::getline(ss, n, ',');) names.push_back(n);
    }
    for (std::string line; std::getline(in, line);) {
        std::stringstream ss(line);
        std::map<std::string, double> row;
        std::string name;
        for (std::size_t k = 0; k < names.size(); ++k) {
            std::string field;
            std::getline(ss, field, ',');
            if (names[k] == "body")
                name = field;
            else
                row[names[k]] = std::stod(field);
        }
        if (name == body) out.rows.push_back(row);
    }
    return out;
}

// A fixed 1 cm cube and a 6 mm cube magnetized across its diagonal, its centre
// off the other's axis. Its half-diagonal (5.2 mm) is below the 6 mm from its
// centre to the lower cube's top face: no orientation touches.
void tiltedPair(magtest::TempCase& c, const std::string& field) {
    c.write("system/magSchemes.yaml", "field: " + field + "\n");
    c.write("constant/materials.yaml", "N: {model: permanent, Br: 1.0, density: 7500}\n");
    c.write("constant/bodies.yaml",
            "bodies:\n"
            "  - {name: bottom, geometry: {box: {size: [0.01, 0.01, 0.01]}}, material: N,\n"
            "     magnetization: [0, 0, 1], position: [0, 0, 0], motion: fixed}\n"
            "  - {name: top, geometry: {box: {size: [0.006, 0.006, 0.006]}}, material: N,\n"
            "     magnetization: [1, 0, 1], position: [0.004, 0.002, 0.011],\n"
            "     orientation: {axis: [1, 0, 0], angle: 10}}\n");
}

} // namespace

TEST_CASE("magForces rotation sweep: torque about the axis = -dU/dangle", "[magForces]") {
    magtest::TempCase c;
    // gauss n = 16: fixed samples that turn with the body, so U(angle) is
    // smooth, and torque and energy come from one rule (the adaptive rule's
    // refinement switches as the body turns: at tolerance 1e-4 the error below
    // reaches 1.6e-3). n = 4 misses by 1.6e-4; from n = 8 on the rule's share
    // is below the printing floor (n = 16 and 32: the same energies, torques
    // within 1e-13 N m).
    tiltedPair(c, "{type: MBM, quadrature: {type: gauss, n: 16}}");
    const double stepDeg = 0.1;
    c.write("system/forcesDict.yaml", "sweep: {body: top, rotate: {axis: [0.3, 0, 1], from: 0, to: 60, steps: 601}}\n");
    std::string log;
    REQUIRE(runMagForces(c, log) == 0);
    INFO(log);
    const Csv csv = readForces(c, "top");
    CHECK(csv.header == "step,angle,body,Fx,Fy,Fz,Tx,Ty,Tz,TmagX,TmagY,TmagZ,energy");
    REQUIRE(csv.rows.size() == 601);  // steps: from and to included
    CHECK(csv.rows.front().at("angle") == 0.0);
    CHECK(csv.rows.back().at("angle") == 60.0);
    CHECK(csv.rows[250].at("angle") == Approx(25.0).epsilon(1e-12));

    const Vec3 a = Vec3(0.3, 0, 1).normalized();
    auto torqueAbout = [&](std::size_t k) {
        const auto& r = csv.rows[k];
        return Vec3(r.at("Tx"), r.at("Ty"), r.at("Tz")).dot(a);
    };
    double scale = 0;  // the torque's size over the sweep
    for (std::size_t k = 0; k < csv.rows.size(); ++k) scale = std::max(scale, std::abs(torqueAbout(k)));
    REQUIRE(scale > 1e-4);  // N m: a real torque, not a symmetric zero

    const double h = stepDeg * mag::pi / 180;  // rad
    double worst = 0;
    for (std::size_t k = 10; k + 10 < csv.rows.size(); k += 10) {
        const double dU = (csv.rows[k + 1].at("energy") - csv.rows[k - 1].at("energy")) / (2 * h);
        const double err = std::abs(torqueAbout(k) + dU) / scale;
        worst = std::max(worst, err);
        // Bound, relative to the torque scale (1.95e-3 N m; |U| <= 0.0146 J):
        // the energy's 10 printed digits, 5e-12 J each, give 2 * 5e-12 / (2h)
        // = 2.9e-9 N m = 1.5e-6; the central difference's h^2/6 |U'''| is 4e-7
        // (1e-5 measured at 5 h); the rule's share is below 1e-7. 1e-5 is 5x
        // that sum (measured 1.8e-6 at most) and far below a wrong sign (2), a
        // turn about a point other than the centre of mass, or degrees read as
        // radians (O(1) each).
        INFO("angle " << csv.rows[k].at("angle") << " deg: T.a " << torqueAbout(k) << " N m, -dU/dangle " << -dU);
        CHECK(err <= 1e-5);
    }
    std::printf("magForces rotation sweep: max |T.a + dU/dangle| / max|T.a| = %.2e (torque scale %.4g N m)\n", worst,
                scale);
}

TEST_CASE("magForces translation sweep: CSV and values as before", "[magForces]") {
    magtest::TempCase c;
    c.twoCubes(0.001);  // MBM, adaptive 1e-4
    c.write("system/forcesDict.yaml", "sweep: {body: top, direction: [0, 0, 2], from: 0, to: 0.001, steps: 3}\n");
    std::string log;
    REQUIRE(runMagForces(c, log) == 0);
    INFO(log);
    const Csv csv = readForces(c, "top");
    CHECK(csv.header == "step,offset,body,Fx,Fy,Fz,Tx,Ty,Tz,TmagX,TmagY,TmagZ,energy");
    REQUIRE(csv.rows.size() == 3);  // from, midway, to
    CHECK(slurp(c.path("postProcessing/forces.csv")).find("\n1,0.000500,top,") != std::string::npos);
    // Gaps 1 mm and 2 mm (docs/physics.md#reference-values): 20.360 N, 14.673 N attracting.
    CHECK(csv.rows[0].at("Fz") == Approx(-20.360).epsilon(2e-4));
    CHECK(csv.rows[2].at("Fz") == Approx(-14.673).epsilon(2e-4));
    CHECK(std::regex_search(log, std::regex("step 2 offset \\+0.001 m")));
    CHECK(log.find("soft ") == std::string::npos);  // no soft body, no magnetization line
}

TEST_CASE("magForces sweep: bad input names the key", "[magForces][badInput]") {
    struct Bad {
        std::string what, sweep, message;
    };
    const std::vector<Bad> cases = {
        {"both forms", "{body: top, direction: [0, 0, 1], rotate: {axis: [0, 0, 1], from: 0, to: 90, steps: 19}}",
         "forcesDict.yaml:1:[0-9]+: sweep.direction: a sweep is a translation .* or a rotation .*, not both"},
        {"steps beside rotate", "{body: top, steps: 3, rotate: {axis: [0, 0, 1], from: 0, to: 90}}",
         "sweep.steps: a sweep is .*not both; with rotate, from, to and steps go inside it"},
        {"neither form", "{body: top}", "forcesDict.yaml:1:[0-9]+: sweep: expected a translation"},
        {"zero axis", "{body: top, rotate: {axis: [0, 0, 0], from: 0, to: 90, steps: 19}}",
         "sweep.rotate.axis: sweep axis has zero length"},
        {"no steps", "{body: top, rotate: {axis: [0, 0, 1], from: 0, to: 90}}",
         "sweep.rotate.steps: required key is missing"},
        {"zero steps", "{body: top, rotate: {axis: [0, 0, 1], from: 0, to: 90, steps: 0}}",
         "sweep.rotate.steps: steps \\(the number of evaluations, from and to included\\) must be >= 1"},
        {"unknown key", "{body: top, rotate: {axis: [0, 0, 1], from: 0, to: 90, steps: 2, centre: [0, 0, 0]}}",
         "sweep.rotate: unknown key 'centre'"},
        {"translation without direction", "{body: top, from: 0, to: 0.01, steps: 2}",
         "sweep.direction: required key is missing"},
    };
    for (const Bad& b : cases) {
        INFO(b.what);
        magtest::TempCase c;
        c.twoCubes(0.001, "{type: EDM, n: 1}");
        c.write("system/forcesDict.yaml", "sweep: " + b.sweep + "\n");
        std::string log;
        CHECK(runMagForces(c, log) == 1);
        INFO(log);
        CHECK(std::regex_search(log, std::regex(b.message)));
    }
    // An angle that looks like radians is a warning; the sweep runs.
    magtest::TempCase c;
    c.twoCubes(0.001, "{type: EDM, n: 1}");
    c.write("system/forcesDict.yaml", "sweep: {body: top, rotate: {axis: [0, 0, 1], from: 0, to: 1.5708, steps: 2}}\n");
    std::string log;
    CHECK(runMagForces(c, log) == 0);
    CHECK(std::regex_search(log, std::regex("forcesDict.yaml:1:[0-9]+: sweep.rotate.to: 1.5708 looks like radians")));
}

TEST_CASE("magForces prints the converged magnetization of soft bodies", "[magForces][induction]") {
    // A steel ball 2 mm above a 1 cm magnet, on its axis: B there is along +z.
    magtest::TempCase c;
    c.write("system/magSchemes.yaml", "field: {type: MBM}\ninduction: {type: LLG, tolerance: 1e-6}\n");
    c.write("constant/materials.yaml", "N42: {model: permanent, Br: 1.3, density: 7500}\n"
                                       "steel: {model: soft, k: 5, Js: 2.0, density: 7850}\n");
    c.write("constant/bodies.yaml",
            "bodies:\n"
            "  - {name: magnet, geometry: {box: {size: [0.01, 0.01, 0.01]}}, material: N42,\n"
            "     magnetization: [0, 0, 1], position: [0, 0, 0], motion: fixed}\n"
            "  - {name: ball, geometry: {sphere: {radius: 0.002, subdivisions: 2}}, material: steel,\n"
            "     position: [0, 0, 0.009]}\n");
    std::string log;
    REQUIRE(runMagForces(c, log) == 0);
    INFO(log);
    CHECK(log.find("induction did not converge") == std::string::npos);
    CHECK(log.find("soft magnet") == std::string::npos);  // permanent: no line
    const std::string num = "([-+0-9.e]+)";
    std::smatch m;
    REQUIRE(std::regex_search(log, m,
                              std::regex("soft ball +M = \\(" + num + ", " + num + ", " + num + "\\) A/m \\(world\\), \\|M\\| = " +
                                         num + " A/m, mu0\\|M\\| = " + num + " T")));
    // The ball's line follows the table (its force row).
    CHECK(log.find("  ball ") < std::size_t(m.position(0)));
    const Vec3 M(std::stod(m[1]), std::stod(m[2]), std::stod(m[3]));
    const double normM = std::stod(m[4]), J = std::stod(m[5]);
    CHECK(normM == Approx(M.norm()).epsilon(1e-5));
    CHECK(J == Approx(mag::mu0 * normM).epsilon(1e-3));
    // Plausible: along the field on the axis, at most saturation (Js = 2 T),
    // and clearly magnetized (B of the magnet there is a few tenths of a tesla).
    CHECK(M.z() > 0);
    CHECK(std::hypot(M.x(), M.y()) <= 1e-3 * M.norm());
    CHECK(J > 0.05);
    CHECK(J <= 2.0);
}
