// magField's `type: points` sets (inline list and CSV file): the B written at
// the points equals the closed-form field of the cube magnet
// (reference/oracles/cuboidField.hpp) and a `type: line` through the same
// points; bad input ends the app naming file, line or key.
#include "caseFixture.hpp"

#include <magFoam/Types.hpp>

#include <catch2/catch.hpp>
#include "oracles/cuboidField.hpp"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <regex>
#include <sstream>
#include <sys/wait.h>

namespace {

using mag::Vec3;

// One 1 cm cube, Br 1 T along a tilted body direction, turned 30 deg about
// (1, 2, 3) and off the origin: no symmetry makes a component vanish.
const Vec3 kCentre(0.001, -0.002, 0.0005);
const Vec3 kAxis = Vec3(1, 2, 3).normalized();
const double kAngle = 30;  // degrees
const Vec3 kDirection = Vec3(0.2, 0.3, 1).normalized();

void cubeCase(magtest::TempCase& c, const std::string& sets) {
    c.write("system/magSchemes.yaml", "field: {type: MBM}\n");
    c.write("constant/materials.yaml", "N: {model: permanent, Br: 1.0, density: 7500}\n");
    c.write("constant/bodies.yaml",
            "bodies:\n"
            "  - {name: cube, geometry: {box: {size: [0.01, 0.01, 0.01]}}, material: N, motion: fixed,\n"
            "     magnetization: [0.2, 0.3, 1], position: [0.001, -0.002, 0.0005],\n"
            "     orientation: {axis: [1, 2, 3], angle: 30}}\n");
    c.write("system/fieldDict.yaml", "sets:\n" + sets);
}

using magtest::slurp;

int runMagField(const magtest::TempCase& c, std::string& log) {
    const int rc = magtest::runApp(c.dir(), "magField");
    log = slurp(c.path("log"));
    return rc;
}

struct Row {
    Vec3 p, B;
    std::string text;
};

std::vector<Row> readCsv(const std::filesystem::path& file) {
    std::ifstream in(file);
    REQUIRE(in);
    std::string line;
    std::getline(in, line);
    CHECK(line == "x,y,z,Bx,By,Bz,magB,Ax,Ay,Az,Hx,Hy,Hz");
    std::vector<Row> rows;
    while (std::getline(in, line)) {
        std::stringstream ss(line);
        double v[13];
        char comma;
        for (int k = 0; k < 13; ++k) ss >> v[k] >> comma;
        rows.push_back({Vec3(v[0], v[1], v[2]), Vec3(v[3], v[4], v[5]), line});
    }
    return rows;
}

oracle::Cuboid oracleCube() {
    oracle::Cuboid c;
    c.centre = kCentre;
    c.halfSize = Vec3(0.005, 0.005, 0.005);
    c.R = Eigen::AngleAxisd(kAngle * mag::pi / 180, kAxis).toRotationMatrix();
    c.M = c.R * kDirection / mag::mu0;
    return c;
}

} // namespace

TEST_CASE("magField type points: B at inline and file points equals the cube's closed form", "[magField]") {
    // Outside (near a face, beyond a corner, far) and inside, away from the edges.
    const std::vector<Vec3> pts = {{0, 0, 0.012}, {0.004, -0.003, 0.0085}, {0.02, 0.01, -0.015},
                                   {0.001, 0.001, 0.001}, {-0.0075, 0.0021, -0.0033}};
    std::string inline_ = "[", csv = "x,y,z\n";
    for (std::size_t i = 0; i < pts.size(); ++i) {
        std::ostringstream p;
        p.precision(17);
        p << pts[i].x() << ", " << pts[i].y() << ", " << pts[i].z();
        inline_ += (i ? ", [" : "[") + p.str() + "]";
        std::string row = p.str();
        row.erase(std::remove(row.begin(), row.end(), ' '), row.end());
        // a blank line and blanks around the numbers are allowed
        csv += (i == 2 ? "\n " + p.str() : row) + "\r\n";
    }
    inline_ += "]";
    magtest::TempCase c;
    cubeCase(c, "  - {name: inline, type: points, points: " + inline_ +
                    "}\n"
                    "  - {name: fromFile, type: points, file: probes/points.csv}\n"
                    "  - {name: line, type: line, start: [0, 0, 0.012], end: [0.004, -0.003, 0.0085], points: 2}\n");
    c.write("probes/points.csv", csv);
    std::string log;
    REQUIRE(runMagField(c, log) == 0);
    INFO(log);

    const oracle::Cuboid cube = oracleCube();
    for (const std::string set : {"inline", "fromFile"}) {
        const auto rows = readCsv(c.path("postProcessing/magField/" + set + ".csv"));
        REQUIRE(rows.size() == pts.size());
        double worst = 0;
        for (std::size_t i = 0; i < pts.size(); ++i) {
            CHECK((rows[i].p - pts[i]).norm() <= 1e-9 * pts[i].norm());  // %.9g in the CSV
            const Vec3 B = oracle::cuboidB(cube, pts[i]);
            const double err = (rows[i].B - B).norm() / B.norm();
            worst = std::max(worst, err);
            // MBM's polyhedron field is closed form too (~1e-14 here); the CSV's
            // 10 significant digits per component bound the comparison.
            CHECK(err <= 1e-9);
        }
        std::printf("magField points (%s): max |B - B_cuboid| / |B| = %.2e\n", set.c_str(), worst);
        const std::string vtp = slurp(c.path("postProcessing/magField/" + set + ".vtp"));
        CHECK(vtp.find("NumberOfPoints=\"5\" NumberOfVerts=\"5\"") != std::string::npos);
    }
    // The same two points as a line: the rows are identical, digit for digit.
    const auto line = readCsv(c.path("postProcessing/magField/line.csv"));
    const auto list = readCsv(c.path("postProcessing/magField/inline.csv"));
    REQUIRE(line.size() == 2);
    CHECK(line[0].text == list[0].text);
    CHECK(line[1].text == list[1].text);
}

TEST_CASE("magField type points: bad input names the file, line or key", "[magField][badInput]") {
    struct Bad {
        std::string what, set, file, text, message;
    };
    const std::vector<Bad> cases = {
        {"missing file", "{name: p, type: points, file: nope.csv}", "", "",
         "fieldDict.yaml:2:[0-9]+: sets\\[0\\].file: cannot open the points file .*nope.csv \\(not found"},
        {"bad row", "{name: p, type: points, file: bad.csv}", "bad.csv", "x,y,z\n0,0,0.01\n0.01,0.02\n",
         "bad.csv:3: sets\\[0\\].file: expected a row 'x,y,z' of three finite numbers \\(m\\), got '0.01,0.02'"},
        {"not a number", "{name: p, type: points, file: bad.csv}", "bad.csv", "0,0,0.01\n0,abc,0\n",
         "bad.csv:2: sets\\[0\\].file: expected a row 'x,y,z' .*got '0,abc,0'"},
        {"four columns", "{name: p, type: points, file: bad.csv}", "bad.csv", "0,0,0.01,1\n",
         "bad.csv:1: sets\\[0\\].file: expected a row 'x,y,z'"},
        {"header only", "{name: p, type: points, file: bad.csv}", "bad.csv", "x,y,z\n\n",
         "sets\\[0\\].file: the points file .*bad.csv holds no x,y,z rows"},
        {"empty list", "{name: p, type: points, points: []}", "", "",
         "fieldDict.yaml:2:[0-9]+: sets\\[0\\].points: expected a non-empty list of points"},
        {"bad item", "{name: p, type: points, points: [[0, 0, 1], [0, 1]]}", "", "",
         "fieldDict.yaml:2:[0-9]+: sets\\[0\\].points\\[1\\]: expected a point \\[x, y, z\\]"},
        {"both forms", "{name: p, type: points, points: [[0, 0, 1]], file: a.csv}", "", "",
         "sets\\[0\\]: both 'points' and 'file' given: type points takes exactly one"},
        {"neither form", "{name: p, type: points}", "", "", "sets\\[0\\]: neither 'points' nor 'file' given"},
    };
    for (const Bad& b : cases) {
        INFO(b.what);
        magtest::TempCase c;
        cubeCase(c, "  - " + b.set + "\n");
        if (!b.file.empty()) c.write(b.file, b.text);
        std::string log;
        CHECK(runMagField(c, log) == 1);
        INFO(log);
        CHECK(std::regex_search(log, std::regex(b.message)));
    }
}
