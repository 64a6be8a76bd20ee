// magFoam end to end: restart equals a continuous run, the VTK output is
// valid XML with the right counts, and signals stop the run cleanly.
#include "caseFixture.hpp"

#include <magFoam/Dictionary.hpp>
#include <magFoam/ResultsWriter.hpp>

#include <catch2/catch.hpp>

#include <csignal>
#include <cstdlib>
#include <fstream>
#include <initializer_list>
#include <regex>
#include <sstream>
#include <sys/wait.h>
#include <unistd.h>

namespace {

std::string app(const std::string& name) { return magtest::appPath(name); }

// magFoam in `dir`, its output in log.run.
int runFoam(const std::filesystem::path& dir) { return magtest::runApp(dir, "magFoam", "log.run"); }

using magtest::slurp;

// Two attracting cubes, the upper one falling onto the fixed lower one.
void fallingCubes(magtest::TempCase& c, const std::string& backend, double endTime, const std::string& extra = "") {
    c.twoCubes(0.004, "{type: MBM, quadrature: {type: gauss, n: 4}}");
    c.write("system/controlDict.yaml", "endTime: " + std::to_string(endTime) +
                                           "\ndeltaT: 0.001\nwriteInterval: 0.005\n" + extra);
    c.write("constant/rigidBody.yaml", "type: " + backend + "\ngravity: [0, 0, -9.81]\n");
}

// fallingCubes on the free backend with the test plugins `libs` (libmag<name>.so
// of the test plugin folder) loaded and the uniform test field with `fieldKeys`.
void testPluginCubes(magtest::TempCase& c, const std::string& fieldKeys,
                     std::initializer_list<const char*> libs = {"TestField"}) {
    std::string list;
    for (const char* lib : libs) list += (list.empty() ? "" : ", ") + magtest::testPluginDir() + "/libmag" + lib + ".so";
    fallingCubes(c, "free", 0.01, "libs: [" + list + "]\n");
    c.write("system/magSchemes.yaml", "field: {type: testUniformField, B0: [0, 0, 0]" + fieldKeys + "}\n");
}

struct State {
    std::vector<double> values;
};

State finalState(const std::filesystem::path& caseDir) {
    const auto folder = mag::latestTimeFolder(caseDir);
    REQUIRE(folder.has_value());
    const auto d = mag::Dict::fromFile(*folder / "bodies.yaml");
    State s;
    s.values.push_back(d.get<double>("time"));
    for (const auto& b : d.list("bodies")) {
        for (const char* k : {"position", "velocity", "angularVelocity"})
            for (double x : b.get<std::vector<double>>(k)) s.values.push_back(x);
        for (double x : b.get<std::vector<double>>("orientation")) s.values.push_back(x);
    }
    return s;
}

} // namespace

TEST_CASE("restart: 0->T equals 0->T/2 plus a restart to T", "[solver]") {
    for (const std::string backend : {"free", "ODE"}) {
        INFO("backend " << backend);
        magtest::TempCase whole, split;
        fallingCubes(whole, backend, 0.04);
        fallingCubes(split, backend, 0.02);
        REQUIRE(runFoam(whole.dir()) == 0);
        REQUIRE(runFoam(split.dir()) == 0);
        split.write("system/controlDict.yaml", "endTime: 0.04\ndeltaT: 0.001\nwriteInterval: 0.005\n"
                                               "startFrom: latestTime\n");
        REQUIRE(runFoam(split.dir()) == 0);
        const State a = finalState(whole.dir()), b = finalState(split.dir());
        REQUIRE(a.values.size() == b.values.size());
        // The restart file holds 17 significant digits, so the continued run
        // starts from bit-identical state: 1e-9 relative is the bar.
        for (std::size_t i = 0; i < a.values.size(); ++i)
            CHECK(b.values[i] == Approx(a.values[i]).epsilon(1e-9).margin(1e-12));
        // CSV rows are not duplicated by the restart.
        const std::string csv = slurp(split.path("postProcessing/energy.csv"));
        CHECK(std::count(csv.begin(), csv.end(), '\n') == 1 + 9);
    }
}

TEST_CASE("VTK output: valid XML series with consistent counts", "[solver]") {
    magtest::TempCase c;
    fallingCubes(c, "free", 0.01);
    REQUIRE(runFoam(c.dir()) == 0);
    const std::string pvd = slurp(c.path("VTK/bodies.pvd"));
    const std::regex dataset("file=\"([^\"]+)\"");
    int files = 0;
    for (auto it = std::sregex_iterator(pvd.begin(), pvd.end(), dataset); it != std::sregex_iterator(); ++it) {
        ++files;
        const std::string vtp = slurp(c.path("VTK/" + (*it)[1].str()));
        REQUIRE(vtp.find("<VTKFile type=\"PolyData\"") != std::string::npos);
        REQUIRE(vtp.rfind("</VTKFile>") != std::string::npos);
        std::smatch m;
        REQUIRE(std::regex_search(vtp, m, std::regex("NumberOfPoints=\"(\\d+)\" NumberOfPolys=\"(\\d+)\"")));
        const int nPoints = std::stoi(m[1]), nPolys = std::stoi(m[2]);
        CHECK(nPoints == 2 * 8);   // two boxes, 8 vertices each
        CHECK(nPolys == 2 * 12);   // 12 triangles each
        // Every array has as many tuples as its owner (points or cells).
        const std::regex array("<DataArray type=\"Float64\" Name=\"(\\w+)\" NumberOfComponents=\"(\\d)\" "
                               "format=\"ascii\">([^<]*)</DataArray>");
        int arrays = 0;
        for (auto a = std::sregex_iterator(vtp.begin(), vtp.end(), array); a != std::sregex_iterator(); ++a) {
            std::istringstream values((*a)[3].str());
            int count = 0;
            for (double x; values >> x;) ++count;
            CHECK(count == std::stoi((*a)[2]) * nPolys);
            ++arrays;
        }
        CHECK(arrays == 8);  // body, part, magnetization, velocity, B, Bn, magB, traction
        CHECK(vtp.find("Name=\"bodyNames\" NumberOfTuples=\"2\"") != std::string::npos);
        std::smatch pts;
        REQUIRE(std::regex_search(vtp, pts, std::regex("<Points><DataArray[^>]*>([^<]*)</DataArray>")));
        std::istringstream values(pts[1].str());
        int count = 0;
        for (double x; values >> x;) ++count;
        CHECK(count == 3 * nPoints);
    }
    CHECK(files == 3);  // t = 0, 0.005, 0.01
    const std::string csv = slurp(c.path("postProcessing/bodies.csv"));
    CHECK(csv.rfind("time,body,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz,Fx,Fy,Fz,Tx,Ty,Tz\n", 0) == 0);
}

namespace {
// The numbers of the first DataArray after `marker` in a .vtp (std::regex
// recurses per character and overflows the stack on arrays this long).
std::vector<double> numbersAfter(const std::string& vtp, const std::string& marker) {
    const auto at = vtp.find(marker);
    REQUIRE(at != std::string::npos);
    const auto begin = vtp.find('>', at + marker.size()) + 1, end = vtp.find('<', begin);
    std::istringstream in(vtp.substr(begin, end - begin));
    std::vector<double> out;
    for (double x; in >> x;) out.push_back(x);
    return out;
}
std::vector<double> vtkArray(const std::string& vtp, const std::string& name) {
    return numbersAfter(vtp, "Name=\"" + name + "\" NumberOfComponents");
}
} // namespace

TEST_CASE("VTK surfaces: per-face B, Bn, traction and velocity that add up to the body's force", "[solver]") {
    // Two 1 cm spheres (icospheres of 1280 faces), 5 mm apart, the upper one
    // thrown sideways and spinning. The traction (M.n) B at each face centre
    // times the face area, summed, is a one-point rule for the force of
    // Eq. 16; on faces ~0.9 mm across, 5 mm from the source, its error is
    // (h/d)^2 ~ 3e-2 of the field's variation, well under 1 % of the force.
    magtest::TempCase c;
    c.write("system/controlDict.yaml", "endTime: 0.001\ndeltaT: 0.001\nwriteInterval: 0.001\n");
    c.write("system/magSchemes.yaml", "field: {type: MBM, quadrature: {type: gauss, n: 6}}\n");
    c.write("constant/materials.yaml", "N: {model: permanent, Br: 1.0, density: 7500}\n");
    c.write("constant/rigidBody.yaml", "type: free\n");
    c.write("constant/bodies.yaml",
            "bodies:\n"
            "  - {name: lower, geometry: {sphere: {radius: 0.005, subdivisions: 3}}, material: N,\n"
            "     magnetization: [0, 0, 1], position: [0, 0, 0], motion: fixed}\n"
            "  - {name: upper, geometry: {sphere: {radius: 0.005, subdivisions: 3}}, material: N,\n"
            "     magnetization: [0, 0, 1], position: [0.002, 0, 0.015], velocity: [0.1, 0, 0],\n"
            "     angularVelocity: [0, 0, 5]}\n");
    REQUIRE(runFoam(c.dir()) == 0);
    const std::string vtp = slurp(c.path("VTK/bodies_1.vtp"));
    const auto body = vtkArray(vtp, "body"), traction = vtkArray(vtp, "traction"), B = vtkArray(vtp, "B");
    const auto Bn = vtkArray(vtp, "Bn"), magB = vtkArray(vtp, "magB"), V = vtkArray(vtp, "velocity");
    // Geometry of the faces from the file itself.
    std::vector<mag::Vec3> pts;
    const auto xyz = numbersAfter(vtp, "<Points><DataArray");
    REQUIRE(xyz.size() == 3 * 2 * 642);  // an icosphere of 1280 faces has 642 vertices
    for (std::size_t i = 0; i + 2 < xyz.size(); i += 3) pts.emplace_back(xyz[i], xyz[i + 1], xyz[i + 2]);
    std::vector<int> conn;
    for (double k : numbersAfter(vtp, "Name=\"connectivity\"")) conn.push_back(static_cast<int>(k));
    const std::size_t faces = conn.size() / 3;
    REQUIRE(faces == 2 * 1280);
    REQUIRE(body.size() == faces);
    REQUIRE(traction.size() == 3 * faces);

    // The upper body's state and force at the write time, from bodies.csv.
    const std::string csv = slurp(c.path("postProcessing/bodies.csv"));
    std::istringstream rows(csv);
    std::string line, last;
    while (std::getline(rows, line))
        if (line.find(",upper,") != std::string::npos) last = line;
    std::vector<double> row;
    {
        std::stringstream ss(last);
        for (std::string f; std::getline(ss, f, ',');) row.push_back(f == "upper" ? 0 : std::stod(f));
    }
    REQUIRE(row.size() == 21);
    const mag::Vec3 x(row[2], row[3], row[4]), v(row[9], row[10], row[11]), w(row[12], row[13], row[14]);
    const mag::Vec3 F(row[15], row[16], row[17]);

    mag::Vec3 sum = mag::Vec3::Zero();
    double worstV = 0, worstBn = 0;
    for (std::size_t k = 0; k < faces; ++k) {
        const mag::Vec3 a = pts[conn[3 * k]], b = pts[conn[3 * k + 1]], cc = pts[conn[3 * k + 2]];
        const mag::Vec3 area = 0.5 * (b - a).cross(cc - a);
        const mag::Vec3 Bk(B[3 * k], B[3 * k + 1], B[3 * k + 2]);
        CHECK(magB[k] == Approx(Bk.norm()).epsilon(1e-8));
        worstBn = std::max(worstBn, std::abs(Bn[k] - Bk.dot(area.normalized())));
        if (body[k] != 1) continue;
        sum += area.norm() * mag::Vec3(traction[3 * k], traction[3 * k + 1], traction[3 * k + 2]);
        const mag::Vec3 centre = (a + b + cc) / 3.0;
        worstV = std::max(worstV, (mag::Vec3(V[3 * k], V[3 * k + 1], V[3 * k + 2]) - (v + w.cross(centre - x))).norm());
    }
    INFO("force " << F.transpose() << ", sum of tractions " << sum.transpose());
    CHECK(F.norm() > 0.1);
    CHECK((sum - F).norm() < 0.01 * F.norm());
    CHECK(worstBn < 1e-6);  // B.n with the face's own normal (10 digits written)
    CHECK(worstV < 1e-6);   // v + w x r of the face centre
}

TEST_CASE("SIGTERM writes the current state and exits 0", "[solver]") {
    magtest::TempCase c;
    fallingCubes(c, "free", 1000.0);
    const pid_t pid = fork();
    REQUIRE(pid >= 0);
    if (pid == 0) {
        if (chdir(c.dir().c_str()) != 0) _exit(99);
        std::freopen("log.run", "w", stdout);
        execl(app("magFoam").c_str(), "magFoam", static_cast<char*>(nullptr));
        _exit(98);
    }
    ::sleep(2);
    kill(pid, SIGTERM);
    int status = 0;
    waitpid(pid, &status, 0);
    REQUIRE(WIFEXITED(status));
    CHECK(WEXITSTATUS(status) == 0);
    const auto folder = mag::latestTimeFolder(c.dir());
    REQUIRE(folder.has_value());
    CHECK(std::stod(folder->filename().string()) > 0);
    CHECK_THAT(slurp(c.path("log.run")), Catch::Matchers::Contains("Stopped by signal"));
}

TEST_CASE("a non-finite wrench stops the run naming the body and step", "[solver][badInput]") {
    magtest::TempCase c;
    testPluginCubes(c, ", nanForce: true");
    const int rc = runFoam(c.dir());
    CHECK(rc == 1);
    const std::string log = slurp(c.path("log.run"));
    // The field's NaN force is there from the start: the first write refuses it
    // (nothing non-finite is ever written), naming body, quantity, time and step.
    CHECK_THAT(log, Catch::Matchers::Contains("not written: body 'bottom': force or torque at t = 0 s (step 0) is "
                                              "not finite"));
    for (const char* csv : {"postProcessing/bodies.csv", "postProcessing/energy.csv"})
        if (std::filesystem::exists(c.path(csv))) CHECK(slurp(c.path(csv)).find("nan") == std::string::npos);
    CHECK_FALSE(std::filesystem::exists(c.path("0/bodies.yaml")));
}

TEST_CASE("a rigid-body step that fails names the step and writes the last good state", "[solver][badInput]") {
    // An engine can give up inside its step (ODE's internal checks: a contact
    // without a normal stopped a Fig. 8 run in its quaternion normalization,
    // with no time and no state to look at). The test backend fails in its 4th
    // step after setting the dynamic bodies' velocity to 1000 m/s, as a step
    // half done can; no field, no gravity: nothing moves before.
    magtest::TempCase c;
    testPluginCubes(c, "", {"TestField", "FailingBackend"});
    c.write("constant/rigidBody.yaml", "type: testFailingBackend\nfailAtStep: 4\n");
    const int rc = runFoam(c.dir());
    CHECK(rc == 1);
    const std::string log = slurp(c.path("log.run"));
    CHECK_THAT(log, Catch::Matchers::Contains("the rigid-body step 4 (t = 0.003 to 0.004 s) failed: test backend "
                                              "failure in its step 4; last good state written to 0.003/"));
    std::vector<mag::Body> bodies(2);
    bodies[0].name = "bottom", bodies[1].name = "top";
    const mag::RestartState s = mag::readState(c.path("0.003/bodies.yaml"), bodies);
    CHECK(s.step == 3);
    CHECK(bodies[1].velocity.norm() == 0.0); // the state before the step, not the half-done one
    CHECK(slurp(c.path("postProcessing/bodies.csv")).find("1000") == std::string::npos);
}

TEST_CASE("a wrench that turns non-finite mid-run: the last good state is written, nothing non-finite",
          "[solver][badInput]") {
    magtest::TempCase c;
    // The top cube falls freely (no magnetic force); after 6 steps of 1 ms it
    // is faster than 0.05 m/s and the field's force on it turns NaN.
    testPluginCubes(c, ", nanAboveSpeed: 0.05");
    const int rc = runFoam(c.dir());
    CHECK(rc == 1);
    const std::string log = slurp(c.path("log.run"));
    CHECK_THAT(log, Catch::Matchers::Contains("non-finite state or wrench of body 'top' in step 7") &&
                        Catch::Matchers::Contains("last good state written to 0.006/ (its state only: its wrench "
                                                  "is not finite)"));
    // That state reads back, finite, and a restart from it is possible.
    std::vector<mag::Body> bodies(2);
    bodies[0].name = "bottom", bodies[1].name = "top";
    const mag::RestartState s = mag::readState(c.path("0.006/bodies.yaml"), bodies);
    CHECK(s.step == 6);
    CHECK(bodies[1].velocity.norm() == Approx(6 * 9.81e-3).epsilon(1e-12));
    for (const char* csv : {"postProcessing/bodies.csv", "postProcessing/energy.csv"}) {
        INFO(csv);
        CHECK(slurp(c.path(csv)).find("nan") == std::string::npos);
    }
}
