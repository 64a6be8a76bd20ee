// Test fixture: a temporary case folder written from YAML strings, removed
// when the fixture goes out of scope.
#pragma once

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <cstdlib>
#include <random>
#include <sstream>
#include <stdexcept>
#include <sys/wait.h>
#include <string>

namespace magtest {

// The build tree (set by CTest): apps in bin/, test plugins in tests/plugins/.
inline std::filesystem::path buildDir() {
    const char* d = std::getenv("MAG_BUILD_DIR");
    if (!d) throw std::runtime_error("MAG_BUILD_DIR is not set: run the tests through ctest");
    return d;
}
inline std::string testPluginDir() { return (buildDir() / "tests/plugins").string(); }
inline std::string appPath(const std::string& name) { return (buildDir() / "bin" / name).string(); }

// A file's whole text ("" when it cannot be read).
inline std::string slurp(const std::filesystem::path& p) {
    std::ifstream in(p);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

// Runs one of the build's apps (bin/<app>, then `arguments`) in `dir` with its
// output, stdout and stderr, in dir/<log>; the exit status.
inline int runApp(const std::filesystem::path& dir, const std::string& app, const std::string& log = "log",
                  const std::string& arguments = "") {
    const std::string cmd = "cd '" + dir.string() + "' && '" + appPath(app) + "'" +
                            (arguments.empty() ? "" : " " + arguments) + " > '" + log + "' 2>&1";
    const int status = std::system(cmd.c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

// The totals of postProcessing/energy.csv (time,kinetic,gravitational,
// magnetic,total): first and last total, the highest total and the peak
// kinetic energy (J), and the number of rows.
struct EnergyRecord {
    double first = 0, last = 0, highest = -1e300, peakKinetic = 0;
    int rows = 0;
    double drift() const { return (last - first) / peakKinetic; }        // of the peak kinetic energy
    double excursion() const { return (highest - first) / peakKinetic; } // the same, highest above the start
};
inline EnergyRecord readEnergyCsv(const std::filesystem::path& file) {
    std::istringstream csv(slurp(file));
    std::string line;
    std::getline(csv, line);  // the header
    EnergyRecord r;
    while (std::getline(csv, line)) {
        double v[5];
        std::istringstream row(line);
        for (double& x : v) {
            std::string cell;
            std::getline(row, cell, ',');
            x = std::stod(cell);
        }
        if (r.rows++ == 0) r.first = v[4];
        r.last = v[4], r.highest = std::max(r.highest, v[4]), r.peakKinetic = std::max(r.peakKinetic, v[1]);
    }
    return r;
}

class TempCase {
public:
    TempCase() {
        std::random_device rd;
        dir_ = std::filesystem::temp_directory_path() / ("magFoamTest-" + std::to_string(rd()) + std::to_string(rd()));
        std::filesystem::create_directories(dir_ / "system");
        std::filesystem::create_directories(dir_ / "constant/geometry");
    }
    ~TempCase() {
        std::error_code ec;
        std::filesystem::remove_all(dir_, ec);
    }
    TempCase(const TempCase&) = delete;
    TempCase& operator=(const TempCase&) = delete;

    const std::filesystem::path& dir() const { return dir_; }
    std::filesystem::path path(const std::string& rel) const { return dir_ / rel; }

    TempCase& write(const std::string& rel, const std::string& text) {
        std::filesystem::create_directories((dir_ / rel).parent_path());
        std::ofstream(dir_ / rel) << text;
        return *this;
    }

    // Two 1 cm N-type cubes along z, unit remanence, and a minimal controlDict.
    TempCase& twoCubes(double gap = 0.001, const std::string& field = "{type: MBM}") {
        write("system/controlDict.yaml", "endTime: 0.01\ndeltaT: 0.001\n");
        write("system/magSchemes.yaml", "field: " + field + "\n");
        write("constant/materials.yaml", "N: {model: permanent, Br: 1.0, density: 7500}\n");
        write("constant/bodies.yaml",
              "bodies:\n"
              "  - {name: bottom, geometry: {box: {size: [0.01, 0.01, 0.01]}}, material: N,\n"
              "     magnetization: [0, 0, 1], position: [0, 0, 0], motion: fixed}\n"
              "  - {name: top, geometry: {box: {size: [0.01, 0.01, 0.01]}}, material: N,\n"
              "     magnetization: [0, 0, 1], position: [0, 0, " +
                  std::to_string(0.01 + gap) + "]}\n");
        return *this;
    }

    // The dropMagnet tutorial's scene: a 6 mm N42 cube 2.5 cm above a fixed
    // disc magnet, tilted by 40 degrees, on ODE with a ground; `moreBodies`
    // (bodies.yaml list items) added, `rigidBodyExtra` appended to
    // rigidBody.yaml. controlDict and magSchemes are the caller's.
    TempCase& dropMagnet(const std::string& moreBodies = "", const std::string& rigidBodyExtra = "") {
        write("constant/materials.yaml", "N42: {model: permanent, Br: 1.3, density: 7500}\n");
        write("constant/bodies.yaml",
              "bodies:\n"
              "  - {name: disc, geometry: {cylinder: {radius: 0.01, height: 0.004, segments: 48}}, material: N42,\n"
              "     magnetization: [0, 0, 1], position: [0, 0, 0.002], motion: fixed}\n"
              "  - {name: cube, geometry: {box: {size: [0.006, 0.006, 0.006]}}, material: N42,\n"
              "     magnetization: [0, 0, 1], position: [0.003, 0, 0.025], orientation: {axis: [1, 0, 0], angle: 40}}\n" +
                  moreBodies);
        write("constant/rigidBody.yaml", "type: ODE\ngravity: [0, 0, -9.81]\nground: {height: 0}\n"
                                         "contact: {friction: 0.5, restitution: 0.1}\n" + rigidBodyExtra);
        return *this;
    }

private:
    std::filesystem::path dir_;
};

} // namespace magtest
