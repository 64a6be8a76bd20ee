// The blocked SIMD field kernel (PolyhedronField: evaluate()) against the face-by-face
// reference (MBMReference: reference::evaluate(), paper Eqs. 9-15 term by term) and the
// scalar edge-major form (the single-point evaluate(), which never enters a block), on
// many meshes and point sets: random, grids through the body, points exactly on faces,
// edges and vertices, within rounding of them, far away, and point counts that are not
// a multiple of the SIMD width. Also the SIMD log and atan2 against the C library.
// Each check runs once per compiled copy of the blocked kernel (KernelPath.hpp: avx2
// and avx512 in the default x86-64 build), skipping with a warning the copies this CPU
// cannot run; the copies must give the same bits.
//
// Tolerance: 1e-12 relative to the field's scale (mu0 |M| for B, |M| R for phi, R for
// S, 1 for insideFraction; R the bounding radius). The three forms evaluate the same
// closed form with different grouping (omega_e once per edge or once per face, one
// atan2 per face or per triangle, the vector log/atan2 within 2 ulp of the C library):
// each of the <= ~1000 terms is at most ~40 (the regularized omega_e) times the scale,
// so rounding differences stay below ~1e-13 of the scale. Far away the field is a
// small difference of such terms; its absolute error is still that size. Any error in
// a formula or a lost lane shows as 1e-6 or more.
#include <catch2/catch.hpp>

#include "KernelPath.hpp"
#include "MBMReference.hpp"
#include "PartShapes.hpp"
#include "PolyhedronBlocks.hpp"
#include "PolyhedronField.hpp"
#include "PolyhedronTables.hpp"

#include <magFoam/Error.hpp>
#include <magFoam/MeshPrimitives.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <random>
#include <string>
#include <vector>

using namespace mag::mbm;

namespace {

constexpr double kTolerance = 1e-12;
const Vec3 kM = Vec3(0.3, -0.5, 0.8).normalized() * (1.2 / mu0); // ~1.2 T, oblique

PolyhedronTables tablesOf(const mag::SurfaceMesh& m) { return PolyhedronTables(m.vertices, m.triangles); }

// body(path) once per copy of the blocked kernel this CPU runs, evaluate() switched to
// it; the copies it cannot run are skipped with a warning. The copy in use before is
// restored afterwards.
template <class Body>
void forEachKernelPath(Body&& body) {
    struct Restore {
        std::string path = kernelPath();
        ~Restore() { setKernelPath(path); }
    } restore;
    for (const std::string& path : kernelPaths()) {
        if (!kernelPathSupported(path)) {
            WARN("kernel path " << path << " skipped: this CPU cannot run it");
            continue;
        }
        setKernelPath(path);
        INFO("kernel path " << path);
        body(path);
    }
}

// The avx2 and avx512 copies evaluate the same operations per lane, both with FMA
// (SimdMath.hpp): the same bits.
bool sameBitsExpected(const std::string& a, const std::string& b) {
    auto fused = [](const std::string& p) { return p == "avx2" || p == "avx512"; };
    return fused(a) && fused(b);
}

struct Fields {
    std::vector<Vec3> B, A, S;
    std::vector<double> f, phi;
    explicit Fields(std::size_t n) : B(n), A(n), S(n), f(n), phi(n) {}
    FieldOutputs all() { return {B, A, f, phi, S}; }
};

// Largest difference of a and b over the set, relative to the scales above.
struct Diff {
    double B = 0, A = 0, S = 0, f = 0, phi = 0;
    double max() const { return std::max({B, A, S, f, phi}); }
};

Diff compare(const Fields& a, const Fields& b, double R, bool withS = true) {
    const double sB = mu0 * kM.norm(), sPhi = kM.norm() * R;
    Diff d;
    for (std::size_t i = 0; i < a.B.size(); ++i) {
        d.B = std::max(d.B, (a.B[i] - b.B[i]).norm() / sB);
        d.f = std::max(d.f, std::abs(a.f[i] - b.f[i]));
        if (!withS) continue;
        d.A = std::max(d.A, (a.A[i] - b.A[i]).norm() / (sB * R));
        d.S = std::max(d.S, (a.S[i] - b.S[i]).norm() / R);
        d.phi = std::max(d.phi, std::abs(a.phi[i] - b.phi[i]) / sPhi);
    }
    return d;
}

bool allFinite(const Fields& x) {
    for (std::size_t i = 0; i < x.B.size(); ++i)
        if (!x.B[i].allFinite() || !x.A[i].allFinite() || !x.S[i].allFinite() ||
            !std::isfinite(x.f[i]) || !std::isfinite(x.phi[i]))
            return false;
    return true;
}

// Fast (blocked), reference (face by face) and scalar (one point per call) agree, for
// every copy of the blocked kernel, and the copies agree bit for bit.
void checkAgreement(const PolyhedronTables& t, const std::vector<Vec3>& pts, const std::string& what) {
    INFO(what << ", " << pts.size() << " points");
    const double R = t.boundingRadius();
    Fields ref(pts.size());
    reference::evaluate(t, kM, pts, ref.all());
    CHECK(allFinite(ref));
    std::optional<std::pair<std::string, Fields>> first;
    forEachKernelPath([&](const std::string& path) {
        Fields fast(pts.size()), scalar(pts.size());
        evaluate(t, kM, pts, fast.all());
        for (std::size_t i = 0; i < pts.size(); ++i) {
            const PointField p = evaluate(t, kM, pts[i]);
            scalar.B[i] = p.B;
            scalar.A[i] = p.A;
            scalar.S[i] = p.S;
            scalar.f[i] = p.insideFraction;
            scalar.phi[i] = p.scalarPotential;
        }
        // B only and B with S (the wrench's request) take other instantiations.
        Fields bOnly(pts.size()), bfS(pts.size());
        evaluate(t, kM, pts, FieldOutputs{bOnly.B, {}, bOnly.f, {}, {}});
        evaluate(t, kM, pts, FieldOutputs{bfS.B, {}, bfS.f, {}, bfS.S});
        bfS.A = fast.A;
        bfS.phi = fast.phi;
        CHECK(allFinite(fast));
        const Diff fr = compare(fast, ref, R), sr = compare(scalar, ref, R), fs = compare(fast, scalar, R);
        const Diff bo = compare(bOnly, fast, R, false), bs = compare(bfS, fast, R);
        if (fr.max() > kTolerance) {
            std::size_t w = 0;
            double wd = 0;
            for (std::size_t i = 0; i < pts.size(); ++i)
                if (std::abs(fast.f[i] - ref.f[i]) + (fast.B[i] - ref.B[i]).norm() / (mu0 * kM.norm()) > wd)
                    wd = std::abs(fast.f[i] - ref.f[i]) + (fast.B[i] - ref.B[i]).norm() / (mu0 * kM.norm()), w = i;
            std::printf("worst point %zu (%.17g, %.17g, %.17g) f fast %.17g ref %.17g\n", w, pts[w].x(), pts[w].y(), pts[w].z(), fast.f[w], ref.f[w]);
        }
        std::printf("%-44s %-6s fast-ref %.1e (B %.1e S %.1e f %.1e)  scalar-ref %.1e  fast-scalar %.1e\n",
                    what.c_str(), path.c_str(), fr.max(), fr.B, fr.S, fr.f, sr.max(), fs.max());
        CHECK(fr.max() <= kTolerance);
        CHECK(sr.max() <= kTolerance);
        CHECK(fs.max() <= kTolerance);
        CHECK(bo.max() == 0.0); // same lanes, same operations
        CHECK(bs.max() == 0.0);
        if (!first) {
            first.emplace(path, std::move(fast));
        } else if (sameBitsExpected(first->first, path)) {
            INFO("against kernel path " << first->first);
            CHECK(compare(fast, first->second, R).max() == 0.0);
        }
    });
}

struct Sets {
    std::vector<std::pair<std::string, std::vector<Vec3>>> sets;
    void add(const std::string& name, std::vector<Vec3> p) { sets.emplace_back(name, std::move(p)); }
};

// Point sets around a mesh of bounding radius R and centroid c.
Sets pointSets(const PolyhedronTables& t, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> uni(-1.0, 1.0), u01(0.0, 1.0);
    const auto& V = t.vertices();
    const double R = t.boundingRadius();
    const Vec3 c = t.centroid();
    Sets s;
    std::vector<Vec3> p;
    for (int i = 0; i < 1001; ++i) p.push_back(c + 1.5 * R * Vec3(uni(rng), uni(rng), uni(rng)));
    s.add("random in 1.5 R", p);
    // grid through the body whose lines hit vertex coordinates (so faces and edges)
    p.clear();
    Vec3 lo = V[0], hi = V[0];
    for (const Vec3& v : V) {
        lo = lo.cwiseMin(v);
        hi = hi.cwiseMax(v);
    }
    const int n = 12;
    for (int i = 0; i <= n; ++i)
        for (int j = 0; j <= n; ++j)
            for (int k = 0; k <= n; ++k) {
                const Vec3 w(double(i) / n, double(j) / n, double(k) / n);
                p.push_back(lo + (hi - lo).cwiseProduct(w * 1.25 - Vec3::Constant(0.125)));
            }
    s.add("grid through the body", p);
    // exactly on faces (barycentric points of the triangles), on edges, at vertices
    p.clear();
    for (const PolyTriangle& tri : t.triangles())
        for (int q = 0; q < 3; ++q) {
            double a = u01(rng), b = u01(rng);
            if (a + b > 1) a = 1 - a, b = 1 - b;
            const Vec3 &r0 = V[tri.v[0]], &r1 = V[tri.v[1]], &r2 = V[tri.v[2]];
            p.push_back(r0 + a * (r1 - r0) + b * (r2 - r0));
        }
    s.add("on faces", p);
    p.clear();
    for (const PolyEdge& e : t.edges())
        for (double x : {0.5, u01(rng), 1e-7, 1.0 - 1e-9}) p.push_back(V[e.v0] + x * e.delta);
    s.add("on edges", p);
    p.assign(V.begin(), V.end());
    s.add("at vertices", p);
    // near the boundary: off faces, edges (and their extensions) and vertices by 1e-15..1e-3 R
    p.clear();
    for (const PolyEdge& e : t.edges()) {
        const PolyFace& f0 = t.faces()[e.face0];
        for (double d : {1e-15, 1e-13, 1e-11, 1e-9, 1e-7, 1e-5, 1e-3}) {
            const Vec3 off = d * R * Vec3(uni(rng), uni(rng), uni(rng)).normalized();
            p.push_back(V[e.v0] + u01(rng) * e.delta + off);        // near the edge
            p.push_back(V[e.v0] + (1.0 + d) * e.delta + d * R * f0.normal); // beyond its end
            p.push_back(V[e.v1] + off);                              // near a vertex
            p.push_back(f0.centroid + d * R * (uni(rng) > 0 ? 1.0 : -1.0) * f0.normal); // off a face
        }
    }
    s.add("near faces, edges and vertices", p);
    p.clear();
    for (int i = 0; i < 203; ++i)
        p.push_back(c + 1e3 * R * Vec3(uni(rng), uni(rng), uni(rng)).normalized());
    s.add("far, 1e3 R", p);
    // everything interleaved, so that blocks mix special and ordinary lanes
    p.clear();
    for (const auto& [name, q] : s.sets) p.insert(p.end(), q.begin(), q.end());
    std::shuffle(p.begin(), p.end(), rng);
    s.add("all, shuffled", p);
    return s;
}

void checkMesh(const mag::SurfaceMesh& m, const std::string& name, unsigned seed) {
    const PolyhedronTables t = tablesOf(m);
    for (const auto& [set, pts] : pointSets(t, seed).sets) checkAgreement(t, pts, name + ": " + set);
}

} // namespace

TEST_CASE("kernel: SIMD log, log1p and atan2 within 2 ulp of the C library", "[mbm][kernel]") {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> e(-40.0, 40.0), u(-1.0, 1.0);
    auto ulps = [](double a, double ref) {
        if (a == ref) return 0.0;
        const double ulp = std::nextafter(std::abs(ref), INFINITY) - std::abs(ref);
        return std::abs(a - ref) / ulp;
    };
    const std::size_t n = 400000;
    std::vector<double> x(n), q(n), y(n), z(n);
    for (std::size_t i = 0; i < n; ++i) {
        x[i] = std::exp(e(rng) * ((i / 4) % 2 ? 1.0 : 1e-3)); // also near 1
        q[i] = std::exp(e(rng));
        y[i] = u(rng) * std::exp(0.3 * e(rng));
        z[i] = u(rng) * std::exp(0.3 * e(rng));
    }
    // each copy's own vector functions (PolyhedronBlocks.hpp)
    forEachKernelPath([&](const std::string&) {
        const blocks::BlockKernel& k = blocks::current();
        std::vector<double> lx(n), lq(n), at(n);
        k.elementary(x.data(), q.data(), y.data(), z.data(), n, lx.data(), lq.data(), at.data());
        double worstLog = 0, worstLog1p = 0, worstAtan2 = 0;
        for (std::size_t i = 0; i < n; ++i) {
            worstLog = std::max(worstLog, ulps(lx[i], std::log(x[i])));
            worstLog1p = std::max(worstLog1p, ulps(lq[i], std::log1p(q[i])));
            worstAtan2 = std::max(worstAtan2, ulps(at[i], std::atan2(y[i], z[i])));
        }
        CHECK(worstLog <= 2.0);
        CHECK(worstLog1p <= 2.0);
        CHECK(worstAtan2 <= 2.0);
        // signed zeros as in C (the kernel's principal values rely on them)
        const double y0[] = {0.0, -0.0, 0.0, -0.0}, x0[] = {0.0, 0.0, -0.0, -1.0};
        const double tiny[] = {1e-300, 1e-20, 1e-10, 1e300}, ones[] = {1.0, 1.0, 1.0, 1.0};
        double l0[4], lt[4], a[4];
        k.elementary(ones, tiny, y0, x0, 4, l0, lt, a);
        for (int l = 0; l < 4; ++l) {
            CHECK(a[l] == std::atan2(y0[l], x0[l]));
            CHECK(std::signbit(a[l]) == std::signbit(std::atan2(y0[l], x0[l])));
            CHECK(ulps(lt[l], std::log1p(tiny[l])) <= 1.0);
        }
    });
}

TEST_CASE("kernel: the copies of the blocked kernel and their selection", "[mbm][kernel]") {
    const std::vector<std::string> paths = kernelPaths();
    REQUIRE(!paths.empty());
    CHECK(kernelPathSupported(paths.front())); // the build's own flags
    CHECK_FALSE(kernelPathSupported("sse9"));
    const std::string before = kernelPath();
    // auto: the widest copy this CPU runs
    setKernelPath("auto");
    std::string widest;
    for (const std::string& p : paths)
        if (kernelPathSupported(p)) widest = p;
    CHECK(kernelPath() == widest);
    CHECK((kernelWidth() == 4 || kernelWidth() == 8));
    CHECK_THROWS_AS(setKernelPath("sse9"), mag::InputError);
    CHECK(kernelPath() == widest); // unchanged by a failed request
    for (const std::string& p : paths)
        if (!kernelPathSupported(p)) CHECK_THROWS_AS(setKernelPath(p), mag::InputError);
    setKernelPath(before);
}

TEST_CASE("kernel: fast, reference and scalar agree on a 12-triangle cube", "[mbm][kernel]") {
    checkMesh(mag::makeBox(Vec3(0.01, 0.01, 0.01)), "cube", 1);
}

TEST_CASE("kernel: fast, reference and scalar agree on a tilted, offset box", "[mbm][kernel]") {
    mag::SurfaceMesh m = mag::makeBox(Vec3(0.02, 0.01, 0.005));
    const Eigen::Matrix3d rot =
        Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
    for (Vec3& v : m.vertices) v = rot * v + Vec3(0.003, -0.001, 0.002);
    checkMesh(m, "tilted box", 2);
}

TEST_CASE("kernel: fast, reference and scalar agree on an icosphere and a cylinder",
          "[mbm][kernel]") {
    checkMesh(mag::makeIcosphere(0.01, 1), "icosphere 80", 3);
    checkMesh(mag::makeIcosphere(0.01, 2), "icosphere 320", 4);
    checkMesh(mag::makeCylinder(0.005, 0.02, 24), "cylinder 96", 5); // many-triangle caps
}

TEST_CASE("kernel: fast, reference and scalar agree on non-convex meshes", "[mbm][kernel]") {
    checkMesh(mag::makeBentPlate(0.02, 0.002, 0.03, 0.02, 90.0, 0.0), "L bracket (sharp)", 6);
    checkMesh(mag::makeBentPlate(), "L bracket (rounded)", 7);
    checkMesh(mag::makeWasher(0.01, 0.005, 0.002, 12), "washer (genus 1)", 8);
    checkMesh(mag::makeHexNut(), "hex nut (genus 1)", 9);
}

TEST_CASE("kernel: any point count, any subset of outputs", "[mbm][kernel]") {
    const PolyhedronTables t = tablesOf(mag::makeIcosphere(0.01, 1));
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> uni(-0.02, 0.02);
    for (std::size_t n : {0, 1, 2, 3, 4, 5, 7, 8, 9, 13, 15, 16, 17, 63, 64, 65, 129}) {
        std::vector<Vec3> pts(n);
        for (Vec3& p : pts) p = Vec3(uni(rng), uni(rng), uni(rng));
        checkAgreement(t, pts, "count " + std::to_string(n));
    }
    // outputs requested one at a time equal the same outputs requested together
    std::vector<Vec3> pts(37);
    for (Vec3& p : pts) p = Vec3(uni(rng), uni(rng), uni(rng));
    forEachKernelPath([&](const std::string&) {
        Fields all(pts.size()), one(pts.size());
        evaluate(t, kM, pts, all.all());
        evaluate(t, kM, pts, FieldOutputs{{}, one.A, {}, {}, {}});
        evaluate(t, kM, pts, FieldOutputs{{}, {}, {}, one.phi, {}});
        evaluate(t, kM, pts, FieldOutputs{{}, {}, one.f, {}, {}});
        for (std::size_t i = 0; i < pts.size(); ++i) {
            CHECK(one.A[i] == all.A[i]);
            CHECK(one.phi[i] == all.phi[i]);
            CHECK(one.f[i] == all.f[i]);
        }
    });
    // the reference checks its output sizes like evaluate()
    std::vector<Vec3> shortB(3);
    CHECK_THROWS_AS(reference::evaluate(t, kM, pts, FieldOutputs{shortB, {}, {}, {}, {}}),
                    std::invalid_argument);
}

TEST_CASE("kernel: per-call tables reused only for the same tables, M and kernel path",
          "[mbm][kernel]") {
    // evaluate() keeps the per-call tables of its last call on this thread; each call
    // below changes one of what they depend on and must give the field of its own inputs
    const Vec3 M2 = Vec3(-0.6, 0.2, 0.1).normalized() * (0.9 / mu0);
    std::vector<Vec3> pts(29);
    std::mt19937 rng(12);
    std::uniform_real_distribution<double> uni(-0.02, 0.02);
    for (Vec3& p : pts) p = Vec3(uni(rng), uni(rng), uni(rng));
    auto check = [&](const PolyhedronTables& t, const Vec3& M) {
        std::vector<Vec3> B(pts.size()), Bref(pts.size());
        evaluate(t, M, pts, B);
        reference::evaluate(t, M, pts, FieldOutputs{Bref, {}, {}, {}, {}});
        double d = 0;
        for (std::size_t i = 0; i < pts.size(); ++i) d = std::max(d, (B[i] - Bref[i]).norm() / (mu0 * M.norm()));
        CHECK(d <= kTolerance);
    };
    const PolyhedronTables box = tablesOf(mag::makeBox(Vec3(0.01, 0.02, 0.01)));
    const PolyhedronTables sphere = tablesOf(mag::makeIcosphere(0.01, 1));
    forEachKernelPath([&](const std::string&) {
        check(box, kM);
        check(box, kM); // reused
        check(box, M2);
        check(sphere, M2);
        check(box, M2);
        const PolyhedronTables copy = box; // same contents, other storage
        check(copy, M2);
        // a new mesh built where the last one was (same address, maybe same buffers)
        std::optional<PolyhedronTables> slot(std::in_place, tablesOf(mag::makeBox(Vec3(0.01, 0.01, 0.01))));
        check(*slot, kM);
        slot.reset();
        slot.emplace(tablesOf(mag::makeBox(Vec3(0.03, 0.01, 0.005))));
        check(*slot, kM);
    });
    // and across a change of path (each copy keeps its own tables)
    const std::vector<std::string> paths = kernelPaths();
    const std::string before = kernelPath();
    for (const std::string& p : paths) {
        if (!kernelPathSupported(p)) continue;
        check(sphere, kM);
        setKernelPath(p);
        check(box, kM);
        check(sphere, kM);
    }
    setKernelPath(before);
}

TEST_CASE("kernel: non-finite points give non-finite fields in their lane only", "[mbm][kernel]") {
    const PolyhedronTables t = tablesOf(mag::makeBox(Vec3(0.01, 0.01, 0.01)));
    const double nan = std::numeric_limits<double>::quiet_NaN();
    std::vector<Vec3> pts = {Vec3(0.02, 0.0, 0.0), Vec3(nan, 0.0, 0.0), Vec3(0.0, 0.001, 0.0),
                             Vec3(0.0, 0.0, 0.03)};
    forEachKernelPath([&](const std::string&) {
        std::vector<Vec3> B(pts.size());
        evaluate(t, kM, pts, B);
        CHECK(B[0].allFinite());
        CHECK_FALSE(B[1].allFinite());
        CHECK(B[2].allFinite());
        CHECK(B[3].allFinite());
        CHECK((B[0] - evaluate(t, kM, pts[0]).B).norm() <= kTolerance * mu0 * kM.norm());
    });
}
