// magField: the total field of a case's bodies (induction converged first)
// sampled on lines, axis-aligned planes and boxes (system/fieldDict.yaml):
//
//   sets:
//     - {name: axis, type: line, start: [0, 0, -0.02], end: [0, 0, 0.02], points: 101}
//     - {name: section, type: plane, normal: y, centre: [0, 0, 0], size: [0.02, 0.02], points: [101, 101]}
//     - {name: cloud, type: box, min: [-0.01, -0.01, -0.01], max: [0.01, 0.01, 0.01], points: [21, 21, 21]}
//
// Writes postProcessing/magField/<name>.csv (x,y,z,Bx,By,Bz,magB,Ax,Ay,Az,Hx,Hy,Hz)
// and <name>.vtp (line) or <name>.vti (plane, box: VTK image data).
#include <magFoam/ArgList.hpp>
#include <magFoam/Case.hpp>
#include <magFoam/Error.hpp>
#include <magFoam/Log.hpp>
#include <magFoam/MagneticSystem.hpp>
#include <magFoam/Threads.hpp>
#include <magFoam/VtkWriter.hpp>

#include <cstdio>
#include <fstream>

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

SampleSet readSet(const Dict& d) {
    SampleSet s;
    s.name = d.get<std::string>("name");
    s.type = d.getWord("type", {"line", "plane", "box"});
    if (s.type == "line") {
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
    for (const Dict& d : dict.list("sets")) sets.push_back(readSet(d));
    dict.reportUnused();

    system.converge(c.bodies());
    const auto outDir = c.dir() / "postProcessing/magField";
    std::filesystem::create_directories(outDir);
    for (const auto& s : sets) {
        const std::size_t n = s.points.size();
        std::vector<Vec3> B(n), A(n), H(n);
        system.field(c.bodies(), s.points, B, A, H);

        std::ofstream csv(outDir / (s.name + ".csv"));
        csv << "x,y,z,Bx,By,Bz,magB,Ax,Ay,Az,Hx,Hy,Hz\n";
        char line[512];
        vtk::PointField magB{"magB", 1, {}};
        for (std::size_t i = 0; i < n; ++i) {
            const Vec3& p = s.points[i];
            std::snprintf(line, sizeof line, "%.9g,%.9g,%.9g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g\n",
                          p.x(), p.y(), p.z(), B[i].x(), B[i].y(), B[i].z(), B[i].norm(), A[i].x(), A[i].y(), A[i].z(),
                          H[i].x(), H[i].y(), H[i].z());
            csv << line;
            magB.values.push_back(B[i].norm());
        }
        const std::vector<vtk::PointField> fields = {vectorField("B", B), magB, vectorField("A", A),
                                                     vectorField("H", H)};
        if (s.type == "line")
            vtk::writePolyLine(outDir / (s.name + ".vtp"), s.points, fields);
        else
            vtk::writeImageData(outDir / (s.name + ".vti"), s.origin, s.spacing, s.dims, fields);
        spdlog::info("{}: {} {} points -> {}", s.name, n, s.type, (outDir / s.name).string() + ".{csv,vt*}");
    }
    return 0;
}

} // namespace

int main(int argc, char** argv) {
    ArgList args("magField", "Sample B, |B|, A and H of a case's bodies on the sets of system/fieldDict.yaml.");
    args.withThreads().withSchemes();
    args.outputs(R"(  postProcessing/magField/<set>.csv   one row per point, world frame:
      x y z [m], Bx By Bz [T], magB [T], Ax Ay Az [T m], Hx Hy Hz [A/m]
  postProcessing/magField/<set>.vtp (line) or .vti (plane, box)   the same fields for ParaView
)");
    if (!args.parse(argc, argv)) return args.exitCode();
    return runGuarded(args, run);
}
