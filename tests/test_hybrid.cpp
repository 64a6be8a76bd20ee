// Tests of the hybrid field evaluator (modules/fields/hybrid, paper Sec. 5 and
// Algorithm 1) and of its GJK distance, against independent references:
//   - the Akoun-Yonnet closed-form force (reference/oracles/akounYonnet.hpp) for the
//     defaults on the paper's Fig. 4 cubes;
//   - the pure near/far evaluators, selected by name, for the switch decisions;
//   - a brute-force polytope distance (all vertex-triangle and edge-edge pairs) for GJK.
#include <magFoam/SurfaceMesh.hpp>

#include <catch2/catch.hpp>

#include "../modules/fields/hybrid/Gjk.hpp"
#include "bodyFixture.hpp"
#include "oracles/akounYonnet.hpp"

#include <magFoam/Body.hpp>
#include <magFoam/Error.hpp>
#include <magFoam/FieldEvaluator.hpp>
#include <magFoam/MeshPrimitives.hpp>
#include <magFoam/ShapeFactory.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <random>
#include <regex>
#include <string>
#include <vector>

using mag::Body;
using mag::Quat;
using mag::Vec3;
using Catch::Matchers::Contains;

namespace {

using magtest::axisAngle;
using magtest::boxShape;
using magtest::field;
using magtest::magnet;
using magtest::sphereShape;

double relErr(const Vec3& a, const Vec3& ref) { return (a - ref).norm() / ref.norm(); }

// The Fig. 4 pair: two 1 cm cubes, Br = 1 T along +z, coaxial, face gap d (m).
const Vec3 cubeSize(0.01, 0.01, 0.01);
struct CubePair {
    Body bottom, top;
    Vec3 reference; // Akoun-Yonnet force on top
};
CubePair cubePair(double gap) {
    static const auto shape = boxShape(cubeSize);
    CubePair p{magnet("bottom", shape, Vec3::Zero(), Vec3::UnitZ()),
               magnet("top", shape, Vec3(0, 0, 0.01 + gap), Vec3::UnitZ()), Vec3::Zero()};
    p.reference = oracle::akounYonnetForce(cubeSize, p.bottom.position, cubeSize, p.top.position, 1.0, 1.0);
    return p;
}

// The paper's gaps (Figs. 4, 5), in m.
const std::vector<double> paperGaps = {0.0002, 0.0005, 0.001, 0.002, 0.005, 0.01, 0.02, 0.05};

// Counters from stats(): pairs near/far, points near/far.
struct Counts {
    long nearPairs, farPairs, nearPoints, farPoints;
};
Counts counts(const mag::FieldEvaluator& f) {
    const mag::FieldStats s = f.stats();
    auto c = [&](const char* name) { return static_cast<long>(s.count(name)); };
    return {c("nearPairs"), c("farPairs"), c("nearPoints"), c("farPoints")};
}

// --- brute-force distance between two convex triangle meshes (world vertices) ---------

double segmentDistance(const Vec3& p1, const Vec3& q1, const Vec3& p2, const Vec3& q2) {
    // Minimise |p1 + s d1 - p2 - t d2| over [0,1]^2 by sampling the candidates exactly:
    // interior stationary point, and the four edges of the parameter square.
    const Vec3 d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
    auto dist = [&](double s, double t) { return (r + s * d1 - t * d2).norm(); };
    auto clamp01 = [](double x) { return std::clamp(x, 0.0, 1.0); };
    const double a = d1.dot(d1), e = d2.dot(d2), b = d1.dot(d2), c = d1.dot(r), f = d2.dot(r);
    double best = std::numeric_limits<double>::infinity();
    const double den = a * e - b * b;
    if (den > 1e-30 * a * e) {
        const double s = (b * f - c * e) / den, t = (a * f - b * c) / den;
        if (s >= 0 && s <= 1 && t >= 0 && t <= 1) best = dist(s, t);
    }
    for (double s : {0.0, 1.0}) best = std::min(best, dist(s, clamp01((f + s * b) / e)));
    for (double t : {0.0, 1.0}) best = std::min(best, dist(clamp01((t * b - c) / a), t));
    return best;
}

std::vector<Vec3> worldVertices(const Body& b) {
    std::vector<Vec3> v;
    for (const Vec3& p : b.shape->mesh.vertices) v.push_back(b.toWorld(p));
    return v;
}

double bruteForceDistance(const Body& A, const Body& B) {
    const auto va = worldVertices(A), vb = worldVertices(B);
    const auto& ta = A.shape->mesh.triangles;
    const auto& tb = B.shape->mesh.triangles;
    double best = std::numeric_limits<double>::infinity();
    for (const Vec3& p : va)
        for (const auto& t : tb) best = std::min(best, (p - mag::closestPointOnTriangle(p, vb[t[0]], vb[t[1]], vb[t[2]])).norm());
    for (const Vec3& p : vb)
        for (const auto& t : ta) best = std::min(best, (p - mag::closestPointOnTriangle(p, va[t[0]], va[t[1]], va[t[2]])).norm());
    for (const auto& s : ta)
        for (int i = 0; i < 3; ++i)
            for (const auto& t : tb)
                for (int j = 0; j < 3; ++j)
                    best = std::min(best, segmentDistance(va[s[i]], va[s[(i + 1) % 3]], vb[t[j]], vb[t[(j + 1) % 3]]));
    return best;
}

double gjkDistance(const Body& a, const Body& b) {
    const mag::gjk::PlacedPoints pa{a.shape->mesh.vertices, a.orientation.toRotationMatrix(), a.position};
    const mag::gjk::PlacedPoints pb{b.shape->mesh.vertices, b.orientation.toRotationMatrix(), b.position};
    return mag::gjk::distance(pa, pb);
}

} // namespace

TEST_CASE("hybrid defaults follow Akoun-Yonnet within 0.5 % at every Fig. 4 gap", "[hybrid]") {
    // Defaults: near MBM (gauss n = 10), far EDM n = 2, bounding-sphere switch with
    // threshold 1. 0.5 %: the accuracy asked of the defaults; the measured worst case
    // is documented in HybridField.cpp.
    auto f = field("type: hybrid\n");
    for (double gap : paperGaps) {
        const CubePair p = cubePair(gap);
        const mag::Wrench w = f->interaction(p.bottom, p.top);
        INFO("gap " << gap * 100 << " cm: " << w.force.transpose() << " vs " << p.reference.transpose());
        CHECK(relErr(w.force, p.reference) < 5e-3);
    }
    // Bounding-sphere gap = (1 + d) - 2 (0.866) cm < 0.866 cm: d < 1.598 cm is near,
    // so six gaps are near and two (2, 5 cm) far.
    const Counts c = counts(*f);
    CHECK(c.nearPairs == 6);
    CHECK(c.farPairs == 2);
    CHECK_THAT(f->describe(), Contains("switch boundingSphere, threshold 1") && Contains("near: MBM") &&
                                  Contains("far: EDM (n=2"));
}

TEST_CASE("hybrid picks near below the threshold and far above", "[hybrid]") {
    // Each result must be bit-for-bit the one of the pure evaluator it delegates to
    // (same code, same input), and the counters must say which one ran.
    auto nearModel = field("type: EDM\nn: 4\n"); // near/far are selected by name: any type
    auto farModel = field("type: EDM\nn: 1\n");
    for (double threshold : {0.0, 0.5, 1.0, 3.0}) {
        auto f = field("type: hybrid\nnear: {type: EDM, n: 4}\nfar: {type: EDM, n: 1}\nswitch: {threshold: " +
                       std::to_string(threshold) + "}\n");
        const double R = cubePair(0).bottom.shape->boundingRadius;
        long expectNear = 0, expectFar = 0;
        for (double gap : paperGaps) {
            const CubePair p = cubePair(gap);
            const double sphereGap = p.top.position.z() - 2 * R;
            const bool isNear = sphereGap < threshold * R;
            (isNear ? expectNear : expectFar) += 1;
            const Vec3 F = f->interaction(p.bottom, p.top).force;
            const Vec3 ref = (isNear ? nearModel : farModel)->interaction(p.bottom, p.top).force;
            INFO("threshold " << threshold << " gap " << gap);
            CHECK(F == ref);
        }
        const Counts c = counts(*f);
        CHECK(c.nearPairs == expectNear);
        CHECK(c.farPairs == expectFar);
    }
}

TEST_CASE("hybrid evaluate() uses the near model close to the source only", "[hybrid]") {
    // Points within (threshold + 1) R of the source COM take the near model.
    auto f = field("type: hybrid\nswitch: {threshold: 1.0}\n");
    auto mbm = field("type: MBM\n");
    auto edm = field("type: EDM\nn: 2\n");
    const Body s = magnet("s", boxShape(cubeSize), Vec3(0.001, 0.002, 0.003), Vec3(1, 0, 1), axisAngle(30, Vec3(0, 1, 1)));
    const double R = s.shape->boundingRadius;
    std::vector<Vec3> pts = {Vec3(0.008, 0, 0), Vec3(0, 0, 1.9 * R), Vec3(0, 2.1 * R, 0), Vec3(0.05, 0.02, -0.03)};
    for (Vec3& p : pts) p += s.position;
    std::vector<Vec3> B(4), A(4), H(4), Bn(4), An(4), Hn(4), Bf(4), Af(4), Hf(4);
    f->evaluate(s, pts, B, A, H);
    mbm->evaluate(s, pts, Bn, An, Hn);
    edm->evaluate(s, pts, Bf, Af, Hf);
    for (int i = 0; i < 4; ++i) {
        const bool isNear = i < 2;
        INFO("point " << i);
        CHECK(B[i] == (isNear ? Bn[i] : Bf[i])); // bit-for-bit: same code, same input
        CHECK(A[i] == (isNear ? An[i] : Af[i]));
        CHECK(H[i] == (isNear ? Hn[i] : Hf[i]));
    }
    const Counts c = counts(*f);
    CHECK(c.nearPoints == 2);
    CHECK(c.farPoints == 2);
}

TEST_CASE("a held body's pairs keep the orientation they have while it moves", "[hybrid][sleeping]") {
    // The solver marks sleeping bodies fixed in its view of the scene, so that
    // their pairs with each other and with fixed bodies are skipped, and held
    // (docs/dynamics.md#sleeping). A pair is evaluated once, sampling the
    // moving body (FieldEvaluator::orientedPair); with a coarse rule the two
    // orientations differ by the rule's error (Newton's third law holds only
    // to it), so a body that fell asleep saw its neighbour's wrench jump and
    // was woken in the next step, again and again (measured in Fig. 8 with
    // islands of touching clips). Held, the pair keeps its orientation and
    // the awake body's wrench is the same, bit for bit.
    auto f = field("type: hybrid\nnear: {type: MBM, quadrature: {type: regular, n: 1}}\n");
    const auto big = boxShape(Vec3(0.01, 0.01, 0.01)), small = boxShape(Vec3(0.004, 0.004, 0.004));
    std::vector<Body> moving{magnet("awake", big, Vec3::Zero(), Vec3::UnitZ()),
                             magnet("sleeper", small, Vec3(0.002, 0.001, 0.008), Vec3(1, 0, 1),
                                    axisAngle(20, Vec3(1, 1, 0)))};
    const std::vector<std::size_t> both{0, 1};
    std::vector<mag::Wrench> ref(2), held(2), fixedOnly(2);
    f->addWrenches(moving, both, true, ref);
    std::vector<Body> view = moving;
    view[1].fixed = true;
    view[1].held = true;
    f->addWrenches(view, both, true, held);
    CHECK(held[0].force == ref[0].force);
    CHECK(held[0].totalTorque() == ref[0].totalTorque());
    CHECK(held[0].energy == ref[0].energy);
    // Fixed without being held the pair turns round: the test can tell.
    view[1].held = false;
    f->addWrenches(view, both, true, fixedOnly);
    INFO("the other orientation differs by " << relErr(fixedOnly[0].force, ref[0].force));
    CHECK(relErr(fixedOnly[0].force, ref[0].force) > 1e-3);
}

TEST_CASE("GJK distance equals the brute-force polytope distance", "[hybrid][gjk]") {
    // Random rotated boxes and icospheres (convex meshes: their triangles are their
    // hull faces), separated; 1e-9 relative: GJK stops at relTol 1e-10 of the distance.
    std::mt19937 rng(42);
    std::uniform_real_distribution<double> u(-1, 1);
    const std::vector<std::shared_ptr<const mag::Shape>> shapes = {
        boxShape(Vec3(0.01, 0.01, 0.01)), boxShape(Vec3(0.03, 0.004, 0.008)), sphereShape(0.006, 1),
        sphereShape(0.004, 2)};
    int tested = 0;
    for (int trial = 0; trial < 60; ++trial) {
        const auto& sa = shapes[trial % shapes.size()];
        const auto& sb = shapes[(trial / shapes.size()) % shapes.size()];
        const Body a = magnet("a", sa, 0.01 * Vec3(u(rng), u(rng), u(rng)), Vec3::UnitZ(),
                              axisAngle(180 * u(rng), Vec3(u(rng), u(rng), u(rng))));
        const Body b = magnet("b", sb, 0.03 * Vec3(u(rng), u(rng), u(rng)), Vec3::UnitZ(),
                              axisAngle(180 * u(rng), Vec3(u(rng), u(rng), u(rng))));
        const double brute = bruteForceDistance(a, b);
        const double gjk = gjkDistance(a, b);
        if (brute < 1e-4) continue; // overlapping or nearly (the brute force is not 0 inside)
        ++tested;
        INFO("trial " << trial << ": gjk " << gjk << " brute " << brute);
        CHECK(std::abs(gjk - brute) <= 1e-9 * brute);
    }
    CHECK(tested > 20);
    // Axis-aligned boxes: the exact distance is the norm of the per-axis gaps (1e-12:
    // GJK ends on the exact vertex-vertex pair here; only rounding remains).
    const auto box = boxShape(Vec3(0.01, 0.02, 0.005));
    const Body a = magnet("a", box, Vec3::Zero(), Vec3::UnitZ());
    const Body b = magnet("b", box, Vec3(0.013, 0.025, -0.009), Vec3::UnitZ());
    CHECK(gjkDistance(a, b) == Approx(std::sqrt(0.003 * 0.003 + 0.005 * 0.005 + 0.004 * 0.004)).epsilon(1e-12));
    // Overlapping and touching hulls: distance 0.
    const Body c = magnet("c", box, Vec3(0.005, 0.01, 0.001), Vec3::UnitZ(), axisAngle(30, Vec3(1, 1, 1)));
    CHECK(gjkDistance(a, c) == 0);
    CHECK(gjkDistance(a, a) == 0);
}

TEST_CASE("hybrid gjk switch sees elongated bodies as far where bounding spheres cannot", "[hybrid][gjk]") {
    // Two parallel 10 cm x 5 mm x 5 mm bars, 2 cm apart (hull gap 1.5 cm): their bounding
    // spheres (R = 5 cm) overlap, so boundingSphere says near; GJK says far at threshold
    // 0.2 (1.5 cm >= 0.2 x 5 cm) and near at threshold 0.4 (1.5 cm < 2 cm). The
    // far case without the blending band (with it, 1 to 2.25 cm is the band).
    const auto bar = boxShape(Vec3(0.1, 0.005, 0.005));
    const Body a = magnet("a", bar, Vec3::Zero(), Vec3::UnitZ());
    const Body b = magnet("b", bar, Vec3(0, 0.02, 0), Vec3::UnitZ());
    auto sphere = field("type: hybrid\nswitch: {type: boundingSphere, threshold: 0.2}\n");
    auto gjkFar = field("type: hybrid\nswitch: {type: gjk, threshold: 0.2, band: 0}\n");
    auto gjkNear = field("type: hybrid\nswitch: {type: gjk, threshold: 0.4}\n");
    sphere->interaction(a, b);
    gjkFar->interaction(a, b);
    gjkNear->interaction(a, b);
    CHECK(counts(*sphere).nearPairs == 1);
    CHECK(counts(*gjkFar).farPairs == 1);
    CHECK(counts(*gjkNear).nearPairs == 1);
    // Far apart: both switches say far (GJK is not even run).
    const Body c = magnet("c", bar, Vec3(0, 0.5, 0), Vec3::UnitZ());
    gjkNear->interaction(a, c);
    CHECK(counts(*gjkNear).farPairs == 1);
}

TEST_CASE("hybrid keys are checked, also in nested dictionaries", "[hybrid][badInput]") {
    CHECK_THROWS_WITH(field("type: hybrid\nswitch: {type: sphere}\n"), Contains("boundingSphere") && Contains("gjk"));
    CHECK_THROWS_WITH(field("type: hybrid\nswitch: {threshold: 1, treshold: 2}\n"), Contains("treshold"));
    CHECK_THROWS_WITH(field("type: hybrid\nswitch: {threshold: -1}\n"), Contains("threshold"));
    CHECK_THROWS_WITH(field("type: hybrid\nnear: {type: MBN}\n"), Contains("unknown field evaluator type 'MBN'"));
    CHECK_THROWS_WITH(field("type: hybrid\nfar: {type: EDM, m: 2}\n"), Contains("m"));
    CHECK_THROWS_WITH(field("type: hybrid\nfarr: {type: EDM}\n"), Contains("farr"));
    // MBM's force form: a known word, and only with a potential's field
    CHECK_THROWS_WITH(field("type: hybrid\nnear: {type: MBM, quadrature: {type: regular, n: 1, form: sigma}}\n"),
                      Contains("form") && Contains("split") && Contains("surfaceCharge"));
    CHECK_THROWS_WITH(field("type: hybrid\nnear: {type: MBM, overlap: amperian, quadrature: {form: surfaceCharge}}\n"),
                      Contains("form") && Contains("overlap: charge or exterior"));
    CHECK_THAT(field("type: hybrid\nnear: {type: MBM, overlap: exterior, quadrature: {type: regular, n: 1, "
                     "form: surfaceCharge}}\n")->describe(),
               Contains("near: MBM (quadrature regular n=1 form=surfaceCharge, overlap exterior)"));
    // Any registered evaluator nests, hybrid included.
    CHECK_THAT(field("type: hybrid\nfar: {type: hybrid, far: {type: EDM, n: 1}}\n")->describe(),
               Contains("far: hybrid (") && Contains("far: EDM (n=1"));
}

TEST_CASE("hybrid error and cost per gap (report)", "[hybrid][.report]") {
    // Not a check: prints the numbers quoted in HybridField.cpp.
    auto f = field("type: hybrid\n");
    auto mbm = field("type: MBM\n");
    std::printf("hybrid defaults vs Akoun-Yonnet (coaxial 1 cm cubes, 1 T)\n");
    std::vector<double> gaps = paperGaps;
    for (double g : {0.012, 0.015, 0.0159, 0.016, 0.018}) gaps.push_back(g);
    std::sort(gaps.begin(), gaps.end());
    for (double gap : gaps) {
        const CubePair p = cubePair(gap);
        const Counts before = counts(*f);
        const Vec3 F = f->interaction(p.bottom, p.top).force;
        const bool isNear = counts(*f).nearPairs > before.nearPairs;
        auto timeOf = [&](const mag::FieldEvaluator& e) {
            int reps = 0;
            double elapsed = 0;
            const auto t0 = std::chrono::steady_clock::now();
            while (elapsed < 0.2) {
                e.interaction(p.bottom, p.top);
                ++reps;
                elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
            }
            return 1e6 * elapsed / reps;
        };
        std::printf(" gap %6.3f cm  %s  Fz %10.6f N  AY %10.6f N  error %+.2e  hybrid %8.2f us  MBM %8.2f us\n",
                    gap * 100, isNear ? "near" : "far ", F.z(), p.reference.z(), (F.z() - p.reference.z()) / std::abs(p.reference.z()),
                    timeOf(*f), timeOf(*mbm));
    }
    std::printf("%s\n", f->describe().c_str());
}
