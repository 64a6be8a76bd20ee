// kernel: cost per point of the MBM closed-form field (paper Eqs. 9-15), the
// face-by-face reference (MBMReference) against the blocked SIMD kernel
// (evaluate()), for the outputs the wrench requests (B, insideFraction and
// S = sum_p W_p n_p, which gives A: "A+B") and for B alone, on meshes of
// several sizes. Points: uniform in a cube of twice the bounding radius about
// the centroid (about a third inside a cube-shaped body); single thread.
//
// The blocked kernel is timed in every copy this CPU runs (KernelPath.hpp: avx2
// and avx512 in the default x86-64 build; CSV column isa), or only in the one
// MAG_KERNEL names where it is set to other than auto. The log names the copy
// evaluate() uses by default.
//
//   kernel:
//     meshes: [cube, icosphere80, icosphere320, cylinder]
//     points: 4096
//     minSeconds: 0.2      # per timing
//     repeats: 3           # the fastest of these timings (the machine may be shared)
#include "BenchMBM.hpp"

#include "KernelPath.hpp"
#include "MBMReference.hpp"
#include "PolyhedronField.hpp"

#include <magFoam/Error.hpp>
#include <magFoam/Log.hpp>
#include <magFoam/MeshPrimitives.hpp>

#include <algorithm>
#include <cstdlib>
#include <random>

namespace mag::bench {

namespace {

SurfaceMesh kernelMesh(const std::string& name) {
    if (name == "cube") return makeBox(Vec3::Constant(0.01));
    if (name == "icosphere80") return makeIcosphere(0.005, 1);
    if (name == "icosphere320") return makeIcosphere(0.005, 2);
    if (name == "cylinder") return makeCylinder(0.005, 0.01, 32);
    throw InputError("kernel: unknown mesh '" + name +
                     "'; valid meshes: cube, icosphere80, icosphere320, cylinder");
}

// Largest difference of a and b relative to the scale.
double maxRelDiff(const std::vector<Vec3>& a, const std::vector<Vec3>& b, double scale) {
    double d = 0;
    for (std::size_t i = 0; i < a.size(); ++i) d = std::max(d, (a[i] - b[i]).norm() / scale);
    return d;
}

// The copies of the blocked kernel to time: MAG_KERNEL's where it forces one, else
// every copy this CPU runs (narrowest first).
std::vector<std::string> kernelPathsToTime() {
    const char* env = std::getenv("MAG_KERNEL");
    if (env && *env && std::string(env) != "auto") return {mbm::kernelPath()};
    std::vector<std::string> paths;
    for (const std::string& p : mbm::kernelPaths())
        if (mbm::kernelPathSupported(p)) paths.push_back(p);
    return paths;
}

} // namespace

void kernelStudy(const Dict& study, const std::filesystem::path& caseDir) {
    const auto meshes = study.get<std::vector<std::string>>(
        "meshes", {"cube", "icosphere80", "icosphere320", "cylinder"});
    const int nPoints = study.get<int>("points", 4096);
    const double minSeconds = study.get<double>("minSeconds", 0.2);
    const int repeats = std::max(1, study.get<int>("repeats", 3));
    study.reportUnused();
    if (nPoints < 1) study.fail("points", "kernel: points must be >= 1");
    const std::string defaultPath = mbm::kernelPath(); // MAG_KERNEL, or the widest
    const std::vector<std::string> paths = kernelPathsToTime();
    std::string timed;
    for (const std::string& p : paths) timed += (timed.empty() ? "" : ", ") + p;
    spdlog::info("  blocked kernel: {} used by evaluate() ({} points per block); timing {}", defaultPath,
                 mbm::kernelWidth(), timed);
    auto csv = openCsv(caseDir, "kernel.csv", "mesh,triangles,outputs,path,isa,nsPerPoint,speedup,maxRelDiff");
    const Vec3 M = Vec3(0.2, -0.3, 1.0).normalized() * (1.2 / mbm::mu0); // 1.2 T, oblique
    for (const std::string& name : meshes) {
        const SurfaceMesh mesh = kernelMesh(name);
        const mbm::PolyhedronTables tables(mesh.vertices, mesh.triangles);
        const double R = tables.boundingRadius();
        std::mt19937 rng(1);
        std::uniform_real_distribution<double> uni(-2.0 * R, 2.0 * R);
        std::vector<Vec3> pts(static_cast<std::size_t>(nPoints));
        for (Vec3& p : pts) p = tables.centroid() + Vec3(uni(rng), uni(rng), uni(rng));
        const std::size_t n = pts.size();
        std::vector<Vec3> Bf(n), Sf(n), Br(n), Sr(n);
        std::vector<double> ff(n), fr(n);
        for (const bool withS : {true, false}) {
            const mbm::FieldOutputs fast = withS ? mbm::FieldOutputs{Bf, {}, ff, {}, Sf} : mbm::FieldOutputs{Bf, {}, {}, {}, {}};
            const mbm::FieldOutputs ref = withS ? mbm::FieldOutputs{Br, {}, fr, {}, Sr} : mbm::FieldOutputs{Br, {}, {}, {}, {}};
            double tRef = 1e300;
            std::vector<double> tFast(paths.size(), 1e300);
            for (int r = 0; r < repeats; ++r) { // interleaved, so that all see the same load
                tRef = std::min(tRef, secondsPerCall([&] { mbm::reference::evaluate(tables, M, pts, ref); }, minSeconds));
                for (std::size_t k = 0; k < paths.size(); ++k) {
                    mbm::setKernelPath(paths[k]);
                    tFast[k] = std::min(tFast[k], secondsPerCall([&] { mbm::evaluate(tables, M, pts, fast); }, minSeconds));
                }
            }
            const char* outputs = withS ? "A+B" : "B";
            const double nsRef = 1e9 * tRef / n;
            csv << name << ',' << mesh.nTriangles() << ',' << outputs << ",reference,scalar," << nsRef << ",1," << 0 << '\n';
            for (std::size_t k = 0; k < paths.size(); ++k) {
                mbm::setKernelPath(paths[k]);
                mbm::evaluate(tables, M, pts, fast);
                // B relative to mu0 |M|, S to the bounding radius (its size inside the body)
                double diff = maxRelDiff(Bf, Br, mbm::mu0 * M.norm());
                if (withS) {
                    diff = std::max(diff, maxRelDiff(Sf, Sr, R));
                    for (std::size_t i = 0; i < n; ++i) diff = std::max(diff, std::abs(ff[i] - fr[i]));
                }
                const double nsFast = 1e9 * tFast[k] / n;
                csv << name << ',' << mesh.nTriangles() << ',' << outputs << ",fast," << paths[k] << ',' << nsFast
                    << ',' << nsRef / nsFast << ',' << diff << '\n';
                spdlog::info("  {:13s} {:4d} triangles {:3s}: reference {:8.1f} ns/point, fast ({:6s}) {:7.1f} "
                             "ns/point, speed-up {:5.2f}, max rel. diff {:.1e}",
                             name, mesh.nTriangles(), outputs, nsRef, paths[k], nsFast, nsRef / nsFast, diff);
            }
            mbm::setKernelPath(defaultPath);
        }
    }
}

} // namespace mag::bench
