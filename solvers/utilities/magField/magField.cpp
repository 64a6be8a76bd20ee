// magField: the total field of a case's bodies (induction converged first)
// sampled on lines, axis-aligned planes, boxes and lists of points
// (system/fieldDict.yaml):
//
//   sets:
//     - {name: axis, type: line, start: [0, 0, -0.02], end: [0, 0, 0.02], points: 101}
//     - {name: section, type: plane, normal: y, centre: [0, 0, 0], size: [0.02, 0.02], points: [101, 101]}
//     - {name: cloud, type: box, min: [-0.01, -0.01, -0.01], max: [0.01, 0.01, 0.01], points: [21, 21, 21]}
//     - {name: probes, type: points, points: [[0, 0, 0.01], [0, 0, 0.02]]}
//     - {name: sensors, type: points, file: sensors.csv}
//
// type points takes exactly one of `points` (a non-empty list of [x, y, z], m)
// or `file` (a CSV relative to the case: x,y,z per line in m, optionally
// after one header line in which no field is a number; blank lines skipped).
//
// Writes postProcessing/magField/<name>.csv (x,y,z,Bx,By,Bz,magB,Ax,Ay,Az,Hx,Hy,Hz)
// and <name>.vtp (line: a polyline; points: vertices) or <name>.vti (plane,
// box: VTK image data).
#include <magFoam/ArgList.hpp>
#include <magFoam/Case.hpp>
#include <magFoam/Error.hpp>
#include <magFoam/Log.hpp>
#include <magFoam/MagneticSystem.hpp>
#include <magFoam/OutputFile.hpp>
#include <magFoam/Threads.hpp>
#include <magFoam/VtkWriter.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

using namespace mag;

namespace {

struct SampleSet {
    std::string name, type;
    std::vector<Vec3> points;
    Vec3 origin = Vec3::Zero(), spacing = Vec3::Zero();
    std::array<int, 3> dims{1, 1, 1};
};

int count(const Dict& d, const std::string& key, int value) {
    if (value < 1 || value > 100000) d.fail(key, "point counts must be 1..100000");
    return value;
}

constexpr std::size_t maxPoints = 20000000;

// A number that fills the whole text (strtod, surrounding blanks allowed).
bool parseNumber(std::string text, double& x) {
    const auto a = text.find_first_not_of(" \t\r"), b = text.find_last_not_of(" \t\r");
    if (a == std::string::npos) return false;
    text = text.substr(a, b - a + 1);
    char* end = nullptr;
    x = std::strtod(text.c_str(), &end);
    return end == text.c_str() + text.size() && std::isfinite(x);
}

std::vector<std::string> splitCommas(const std::string& line) {
    std::vector<std::string> out;
    std::stringstream ss(line);
    for (std::string f; std::getline(ss, f, ',');) out.push_back(f);
    if (!line.empty() && line.back() == ',') out.emplace_back();
    return out;
}

// x,y,z rows of a CSV file (m); a first line without any number is a header.
std::vector<Vec3> readPointsFile(const Dict& d, const std::filesystem::path& caseDir) {
    const std::string rel = d.get<std::string>("file");
    const std::filesystem::path file = caseDir / rel;
    std::ifstream in(file);
    if (!in) d.fail("file", "cannot open the points file " + file.string() + " (not found or unreadable)");
    std::vector<Vec3> points;
    std::string line;
    bool first = true;
    for (int lineNo = 1; std::getline(in, line); ++lineNo) {
        if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
        const std::vector<std::string> fields = splitCommas(line);
        Vec3 p;
        int numbers = 0;
        bool ok = fields.size() == 3;
        for (std::size_t k = 0; k < fields.size(); ++k) {
            double x;
            const bool isNumber = parseNumber(fields[k], x);
            numbers += isNumber;
            if (k < 3) p[int(k)] = x;
            ok = ok && isNumber;
        }
        if (first && numbers == 0) {  // header
            first = false;
            continue;
        }
        first = false;
        if (!ok) {
            std::string shown = line;
            if (!shown.empty() && shown.back() == '\r') shown.pop_back();
            if (shown.size() > 60) shown = shown.substr(0, 57) + "...";
            throw InputError(file.string() + ":" + std::to_string(lineNo) + ": " + d.keyPath("file") +
                             ": expected a row 'x,y,z' of three finite numbers (m), got '" + shown + "'");
        }
        points.push_back(p);
        if (points.size() > maxPoints) d.fail("file", file.string() + " holds more than 2e7 points");
    }
    if (points.empty()) d.fail("file", "the points file " + file.string() + " holds no x,y,z rows");
    return points;
}

// An inline list [[x, y, z], ...] (m); each bad item is named with its position.
std::vector<Vec3> readPointsList(const Dict& d) {
    const YAML::Node list = d.node()["points"];
    if (!list.IsSequence() || list.size() == 0)
        d.fail("points", "expected a non-empty list of points [[x, y, z], ...] (m)");
    if (list.size() > maxPoints) d.fail("points", "more than 2e7 points");
    std::vector<Vec3> points;
    for (std::size_t i = 0; i < list.size(); ++i) {
        const YAML::Node& item = list[i];
        Vec3 p;
        bool ok = item.IsSequence() && item.size() == 3;
        for (int k = 0; ok && k < 3; ++k) ok = item[k].IsScalar() && parseNumber(item[k].Scalar(), p[k]);
        if (!ok) {
            const YAML::Mark m = item.Mark();
            const std::string at = m.is_null() ? d.where("points")
                                               : d.file() + ":" + std::to_string(m.line + 1) + ":" +
                                                     std::to_string(m.column + 1);
            throw InputError(at + ": " + d.keyPath("points") + "[" + std::to_string(i) +
                             "]: expected a point [x, y, z] of three finite numbers (m)");
        }
        points.push_back(p);
    }
    return points;
}

SampleSet readSet(const Dict& d, const std::filesystem::path& caseDir) {
    SampleSet s;
    s.name = d.get<std::string>("name");
    s.type = d.getWord("type", {"line", "plane", "box", "points"});
    if (s.type == "points") {
        const bool inList = d.has("points"), inFile = d.has("file");
        if (inList == inFile)
            d.failHere(std::string(inList ? "both 'points' and 'file' given" : "neither 'points' nor 'file' given") +
                       ": type points takes exactly one, a list [[x, y, z], ...] or a CSV file of x,y,z rows");
        s.points = inList ? readPointsList(d) : readPointsFile(d, caseDir);
    } else if (s.type == "line") {
        const Vec3 a = d.get<Vec3>("start"), b = d.get<Vec3>("end");
        const int n = count(d, "points", d.get<int>("points"));
        for (int i = 0; i < n; ++i) s.points.push_back(n == 1 ? a : Vec3(a + (b - a) * (double(i) / (n - 1))));
    } else {
        Vec3 lo, hi;
        if (s.type == "plane") {
            const std::string normal = d.getWord("normal", {"x", "y", "z"});
            const int k = normal[0] - 'x';
            const Vec3 c = d.get<Vec3>("centre");
            const auto size = d.get<std::vector<double>>("size");
            const auto pts = d.get<std::vector<double>>("points");
            if (size.size() != 2 || size[0] <= 0 || size[1] <= 0)
                d.fail("size", "expected two positive lengths [along the first, second in-plane axis]");
            if (pts.size() != 2) d.fail("points", "expected two point counts");
            const int i1 = (k + 1) % 3, i2 = (k + 2) % 3;
            const int u = std::min(i1, i2), v = std::max(i1, i2);  // in-plane axes in x, y, z order
            lo = hi = c;
            lo[u] -= size[0] / 2, hi[u] += size[0] / 2, lo[v] -= size[1] / 2, hi[v] += size[1] / 2;
            s.dims[u] = count(d, "points", int(pts[0])), s.dims[v] = count(d, "points", int(pts[1]));
            s.dims[k] = 1;
        } else {
            lo = d.get<Vec3>("min"), hi = d.get<Vec3>("max");
            const auto pts = d.get<std::vector<double>>("points");
            if (pts.size() != 3) d.fail("points", "expected three point counts [nx, ny, nz]");
            if ((hi - lo).minCoeff() < 0) d.fail("max", "max must not be below min");
            for (int k = 0; k < 3; ++k) s.dims[k] = count(d, "points", int(pts[k]));
        }
        s.origin = lo;
        for (int k = 0; k < 3; ++k) s.spacing[k] = s.dims[k] > 1 ? (hi[k] - lo[k]) / (s.dims[k] - 1) : 1.0;
        if (long(s.dims[0]) * s.dims[1] * s.dims[2] > 20000000) d.failHere("more than 2e7 points");
        for (int z = 0; z < s.dims[2]; ++z)
            for (int y = 0; y < s.dims[1]; ++y)
                for (int x = 0; x < s.dims[0]; ++x)
                    s.points.push_back(lo + Vec3(x * s.spacing.x(), y * s.spacing.y(), z * s.spacing.z()));
    }
    d.reportUnused();
    return s;
}

vtk::PointField vectorField(const std::string& name, const std::vector<Vec3>& v) {
    vtk::PointField f{name, 3, {}};
    for (const auto& x : v) f.values.insert(f.values.end(), {x.x(), x.y(), x.z()});
    return f;
}

int run(const ArgList& args) {
    Case c = Case::read(args.caseDir(), args.schemesFile());
    setThreads(args, c);
    MagneticSystem system(c);
    const Dict dict = Dict::fromFile(c.dir() / "system/fieldDict.yaml");
    std::vector<SampleSet> sets;
    for (const Dict& d : dict.list("sets")) sets.push_back(readSet(d, c.dir()));
    dict.reportUnused();

    system.converge(c.bodies());
    const auto outDir = c.dir() / "postProcessing/magField";
    makeFolder(outDir);
    for (const auto& s : sets) {
        const std::size_t n = s.points.size();
        std::vector<Vec3> B(n), A(n), H(n);
        const auto t0 = std::chrono::steady_clock::now();
        system.field(c.bodies(), s.points, B, A, H);
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

        std::string csv = "x,y,z,Bx,By,Bz,magB,Ax,Ay,Az,Hx,Hy,Hz\n";
        char line[512];
        vtk::PointField magB{"magB", 1, {}};
        for (std::size_t i = 0; i < n; ++i) {
            const Vec3& p = s.points[i];
            std::snprintf(line, sizeof line, "%.9g,%.9g,%.9g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g\n",
                          p.x(), p.y(), p.z(), B[i].x(), B[i].y(), B[i].z(), B[i].norm(), A[i].x(), A[i].y(), A[i].z(),
                          H[i].x(), H[i].y(), H[i].z());
            csv += line;
            magB.values.push_back(B[i].norm());
        }
        writeFileAtomically(outDir / (s.name + ".csv"), csv);
        const std::vector<vtk::PointField> fields = {vectorField("B", B), magB, vectorField("A", A),
                                                     vectorField("H", H)};
        if (s.type == "line")
            vtk::writePolyLine(outDir / (s.name + ".vtp"), s.points, fields);
        else if (s.type == "points")
            vtk::writeVertices(outDir / (s.name + ".vtp"), s.points, fields);
        else
            vtk::writeImageData(outDir / (s.name + ".vti"), s.origin, s.spacing, s.dims, fields);
        // The evaluation alone (B, A and H), without the files: what the Python
        // module's benchmark compares against (docs/python.md#performance).
        spdlog::info("{}: {} {}points -> {} (field {:.3f} ms, {:.4g} points/s)", s.name, n,
                     s.type == "points" ? "" : s.type + " ", (outDir / s.name).string() + ".{csv,vt*}", 1e3 * seconds,
                     seconds > 0 ? n / seconds : 0.0);
    }
    return 0;
}

} // namespace

int main(int argc, char** argv) {
    ArgList args("magField", "Sample B, |B|, A and H of a case's bodies on the sets (lines, planes, boxes, point "
                             "lists) of system/fieldDict.yaml.");
    args.withThreads().withSchemes();
    args.outputs(R"(  postProcessing/magField/<set>.csv   one row per point, world frame:
      x y z [m], Bx By Bz [T], magB [T], Ax Ay Az [T m], Hx Hy Hz [A/m]
  postProcessing/magField/<set>.vtp (line, points) or .vti (plane, box)   the same fields for ParaView
)");
    if (!args.parse(argc, argv)) return args.exitCode();
    return runGuarded(args, run);
}
