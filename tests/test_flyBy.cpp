// Energy through the hybrid's tier switch (docs/physics.md#hybrid-switch): a
// permanent rod slung past a fixed cube magnet on the `free` backend conserves
// the total energy with the hybrid at its default settings as with MBM alone,
// and the blended switch is the exact gradient of its blended energy (finite
// differences, both switch types and the dipole band).
#include "bodyFixture.hpp"
#include "caseFixture.hpp"

#include <DipoleFarField.hpp>
#include <magFoam/Body.hpp>
#include <magFoam/FieldEvaluator.hpp>

#include <catch2/catch.hpp>

#include <oracles/akounYonnet.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <regex>
#include <sstream>
#include <string>

using mag::Body;
using mag::Vec3;

namespace {

struct FlyBy {
    double drift = 0;      // (E_end - E_0) / peak kinetic energy, from energy.csv
    double excursion = 0;  // largest (E - E_0) / peak kinetic energy over the written rows
    double peakKinetic = 0;
    std::map<std::string, std::uint64_t> counters;  // the log's "field counters"
    std::uint64_t count(const std::string& name) const {
        const auto it = counters.find(name);
        return it == counters.end() ? 0 : it->second;
    }
};

// A 4 x 4 x 12 mm N42 rod, magnetized across its long axis (body x, along its
// flight), flies at 5 m/s from 15 cm out past a fixed 1 cm N42 cube (magnetized
// z), aimed 16 mm beside the cube's centre: the cube's field turns it as it
// comes (up to ~370 rad/s), pulls it to 2.9 mm from the cube (no contact) and
// slings it off 40 degrees from its course; it leaves 14 cm out, spinning. On
// the way in and out it crosses the hybrid's dipole reach (12.2 cm at the
// default ratio 8), the dipole band below it, and the near/far switch with its
// band (centre distances 2.4-2.6 cm). Free backend, no gravity, no contacts;
// 3,000 steps, well under a second per run.
//
// Magnetized along its long axis, the rod stays in the cube's mid-plane
// without torque and its path is mirror-symmetric, so the energy a sharp
// switch gains on the way in it gives back on the way out (measured before
// the blend: 5e-6 of the peak kinetic energy); magnetized across, it turns, and
// enters and leaves the switch in other orientations: 2.6e-3.
const std::string kRod = "  - {name: rod, geometry: {box: {size: [0.004, 0.004, 0.012]}}, material: N42, magnetization: [1, 0, 0],\n"
                         "     position: [-0.15, 0.016, 0], velocity: [5, 0, 0]}\n";

// `rod`: the flying body's entry of bodies.yaml; `induction`: magSchemes' key, if any.
FlyBy flyBy(const std::string& field, double deltaT = 2e-5, const std::string& rod = kRod,
            const std::string& induction = "") {
    magtest::TempCase c;
    std::ostringstream control;
    control << "endTime: 0.06\ndeltaT: " << deltaT << "\nwriteInterval: 0.0005\n";
    c.write("system/controlDict.yaml", control.str());
    c.write("system/magSchemes.yaml", "field: " + field + "\n" + (induction.empty() ? "" : "induction: " + induction + "\n"));
    c.write("constant/materials.yaml", "N42: {model: permanent, Br: 1.3, density: 7500}\n"
                                       "steel: {model: soft, chi: 1000, Js: 2.0, density: 7850}\n");
    c.write("constant/bodies.yaml",
            "bodies:\n"
            "  - {name: magnet, geometry: {box: {size: [0.01, 0.01, 0.01]}}, material: N42, magnetization: [0, 0, 1],\n"
            "     position: [0, 0, 0], motion: fixed}\n" + rod);
    c.write("constant/rigidBody.yaml", "type: free\ngravity: [0, 0, 0]\n");
    REQUIRE(magtest::runApp(c.dir(), "magFoam") == 0);

    FlyBy r;
    const magtest::EnergyRecord e = magtest::readEnergyCsv(c.path("postProcessing/energy.csv"));
    REQUIRE(e.rows > 100);
    r.peakKinetic = e.peakKinetic;
    r.drift = e.drift();
    r.excursion = e.excursion();

    const std::string log = magtest::slurp(c.path("log"));
    std::smatch m;
    REQUIRE(std::regex_search(log, m, std::regex("field counters: ([^\n]*)")));
    const std::string list = m[1];
    const std::regex item("([A-Za-z.]+) ([0-9]+)");
    for (auto it = std::sregex_iterator(list.begin(), list.end(), item); it != std::sregex_iterator(); ++it)
        r.counters[(*it)[1]] = std::stoull((*it)[2]);
    return r;
}

} // namespace

TEST_CASE("fly-by: a permanent rod slung past a magnet conserves energy through the hybrid's switch",
          "[flyBy][hybrid]") {
    // The bar, 1e-4 of the peak kinetic energy, is the issue's. What is left of
    // the drift is the adaptive quadrature's (its force is the gradient of its
    // energy to its tolerance, 1e-4, not exactly): measured 8.2e-7 (hybrid) and
    // 5.4e-7 (MBM) here; 5.4e-5 with MBM at tolerance 1e-2, 2.4e-7 at 1e-6. So the
    // bar leaves the default quadrature two orders of margin and still catches a
    // switch that jumps (below). The integrator's bounded O(dt) oscillation shows
    // in the excursion above the start, not in the drift: 6.3e-4 at this step,
    // 3.1e-4 at half of it, for both evaluators.
    const FlyBy hybrid = flyBy("{type: hybrid}");
    const FlyBy mbm = flyBy("{type: MBM}");
    INFO("hybrid drift " << hybrid.drift << " (excursion " << hybrid.excursion << "), MBM drift " << mbm.drift
                         << " (excursion " << mbm.excursion << "), peak kinetic energy " << hybrid.peakKinetic << " J");
    CHECK(std::abs(hybrid.drift) <= 1e-4);
    CHECK(std::abs(mbm.drift) <= 1e-4);
    // The rod went through every tier and both bands, each way.
    for (const char* name : {"dipolePairs", "dipoleBandPairs", "farPairs", "nearBandPairs", "nearPairs"}) {
        INFO(name << " " << hybrid.count(name));
        CHECK(hybrid.count(name) > 20);
    }
    // The same scene with the sharp switch of before (both bands 0): the energy
    // jumps where the pair changes tier. EDM n = 2's energy is 1.9 % off MBM's
    // where the rod enters the near tier and 2.9 % where it leaves (turned):
    // +1.8e-5 J and +4.5e-5 J, 99 % of the drift, 2.6e-3 of the peak kinetic
    // energy at either step (measured). The bar above sees it.
    const FlyBy sharp = flyBy("{type: hybrid, switch: {band: 0}, dipoleBand: 0}");
    INFO("sharp switch drift " << sharp.drift);
    CHECK(std::abs(sharp.drift) > 1e-3);
    CHECK(sharp.count("nearBandPairs") == 0);
    CHECK(sharp.count("dipoleBandPairs") == 0);
    // Halving the step halves the integrator's oscillation; the drift stays.
    const FlyBy half = flyBy("{type: hybrid}", 1e-5);
    INFO("half the step: drift " << half.drift << ", excursion " << half.excursion);
    CHECK(std::abs(half.drift) <= 1e-4);
    CHECK(half.excursion < 0.7 * hybrid.excursion);
}

namespace {

// U(pose) of the pair through `f` (energy of interaction(source, target)).
double energyAt(const mag::FieldEvaluator& f, const Body& source, const Body& target) {
    return f.interaction(source, target).energy;
}

// Relative difference of the wrench from minus the central finite differences
// of the energy, in the target's position and rotation (about its centre).
struct Consistency {
    double force, torque;
};
Consistency consistency(const mag::FieldEvaluator& f, const Body& source, const Body& target) {
    const mag::Wrench w = f.interaction(source, target);
    const double h = 1e-7, a = 1e-6;  // m, rad
    Vec3 grad, rot;
    for (int i = 0; i < 3; ++i) {
        Body p = target, m = target;
        p.position[i] += h, m.position[i] -= h;
        grad[i] = (energyAt(f, source, p) - energyAt(f, source, m)) / (2 * h);
        Body pr = target, mr = target;
        pr.orientation = (mag::Quat(Eigen::AngleAxisd(a, Vec3::Unit(i))) * target.orientation).normalized();
        mr.orientation = (mag::Quat(Eigen::AngleAxisd(-a, Vec3::Unit(i))) * target.orientation).normalized();
        rot[i] = (energyAt(f, source, pr) - energyAt(f, source, mr)) / (2 * a);
    }
    return {(w.force + grad).norm() / w.force.norm(), (w.totalTorque() + rot).norm() / w.totalTorque().norm()};
}

} // namespace

TEST_CASE("hybrid bands: the blended wrench is minus the gradient of the blended energy", "[flyBy][hybrid]") {
    // Tiers that are exact gradients of their own energies (EDM: sums of point
    // dipoles) and far apart from each other (n = 3 against n = 1 or the single
    // dipole, for a tilted 3:1 rod), so that the weight's own term,
    // -(U_far - U_near) grad s, is large. Central differences of step 1e-7 m and
    // 1e-6 rad; measured agreement ~1e-8.
    const auto cube = magtest::boxShape(Vec3(0.01, 0.01, 0.01));
    const auto rod = magtest::boxShape(Vec3(0.004, 0.004, 0.012));
    const Body source = magtest::magnet("cube", cube, Vec3::Zero(), Vec3(0, 0, 1));
    const double Rc = cube->boundingRadius, Rr = rod->boundingRadius, R = std::max(Rc, Rr);
    const Vec3 dir = Vec3(0.3, 1, 0.2).normalized();
    const auto tilt = magtest::axisAngle(35, Vec3(1, -2, 0.5));
    auto rodAt = [&](double distance) { return magtest::magnet("rod", rod, distance * dir, Vec3(1, 0.2, 0), tilt); };
    auto check = [&](const mag::FieldEvaluator& f, const Body& target, const char* what, const char* counter) {
        const std::uint64_t before = f.stats().count(counter);
        const mag::Wrench w = f.interaction(source, target);
        REQUIRE(f.stats().count(counter) == before + 1);  // in the band
        const Consistency c = consistency(f, source, target);
        INFO(what << ": force " << c.force << ", torque " << c.torque << " (|F| " << w.force.norm() << " N)");
        CHECK(c.force < 1e-6);
        CHECK(c.torque < 1e-6);
    };
    // Bounding spheres: gap in [R, 1.25 R) is the band; 1.12 R is inside.
    auto sphere = magtest::field("{type: hybrid, near: {type: EDM, n: 3}, far: {type: EDM, n: 1}}");
    check(*sphere, rodAt(Rc + Rr + 1.12 * R), "near/far band, bounding spheres", "nearBandPairs");
    // Far/dipole: ratio 3, centre distances in (2.25, 3] (Rc + Rr); 2.6 is inside
    // and far by the switch (gap 1.6 (Rc + Rr) > 1.25 R).
    auto dipole = magtest::field("{type: hybrid, far: {type: EDM, n: 3}, dipoleRatio: 3}");
    check(*dipole, rodAt(2.6 * (Rc + Rr)), "far/dipole band", "dipoleBandPairs");
    // GJK: the weight depends on the rod's orientation too (through its closest
    // point), so the blend adds a torque. Threshold 0.3, band 0.25: hull gaps in
    // [0.3 R, 0.55 R); bisect for the distance whose hull gap is 0.425 R.
    double lo = Rc + Rr - 0.5 * R, hi = Rc + Rr + 2 * R;
    auto probe =
        magtest::field("{type: hybrid, near: {type: EDM, n: 1}, switch: {type: gjk, threshold: 0.425, band: 0}}");
    for (int i = 0; i < 60; ++i) {
        const double mid = 0.5 * (lo + hi);
        const std::uint64_t near = probe->stats().count("nearPairs");
        (void)probe->interaction(source, rodAt(mid));
        (probe->stats().count("nearPairs") > near ? lo : hi) = mid;
    }
    auto gjk = magtest::field(
        "{type: hybrid, near: {type: EDM, n: 3}, far: {type: EDM, n: 1}, switch: {type: gjk, threshold: 0.3}}");
    check(*gjk, rodAt(lo), "near/far band, GJK", "nearBandPairs");
}

TEST_CASE("hybrid bands: pairs outside the bands are those of one tier, bit for bit", "[flyBy][hybrid]") {
    auto f = magtest::field("{type: hybrid, near: {type: EDM, n: 3}, far: {type: EDM, n: 1}}");
    auto nearModel = magtest::field("{type: EDM, n: 3}");
    auto farModel = magtest::field("{type: EDM, n: 1}");
    const auto cube = magtest::boxShape(Vec3(0.01, 0.01, 0.01));
    const double R = cube->boundingRadius;
    const Body s = magtest::magnet("s", cube, Vec3::Zero(), Vec3(0, 0, 1));
    const Vec3 dir = Vec3(1, 0.5, -0.2).normalized();
    // Centre distances: sphere gap just below the threshold R (near), just past
    // the band's end 1.25 R (far), just inside the dipole band's start 6 (2 R) (far).
    for (const auto& [distance, near] : {std::pair{2.999 * R, true}, {3.2501 * R, false}, {11.999 * R, false}}) {
        const Body t = magtest::magnet("t", cube, distance * dir, Vec3(0.3, 1, 0));
        const mag::Wrench w = f->interaction(s, t), ref = (near ? nearModel : farModel)->interaction(s, t);
        INFO("centre distance " << distance / R << " R");
        CHECK(w.force == ref.force);
        CHECK(w.torque == ref.torque);
        CHECK(w.mechanicalTorque == ref.mechanicalTorque);
        CHECK(w.energy == ref.energy);
        CHECK(w.fieldIntegral == ref.fieldIntegral);
    }
    CHECK(f->stats().count("nearBandPairs") == 0);
    CHECK(f->stats().count("dipoleBandPairs") == 0);
    CHECK_THROWS_WITH(magtest::field("{type: hybrid, switch: {band: -1}}"), Catch::Contains("band"));
    CHECK_THROWS_WITH(magtest::field("{type: hybrid, dipoleBand: 1}"), Catch::Contains("dipoleBand"));
}

TEST_CASE("hybrid bands: force error and cost in the band (report)", "[flyBy][hybrid][.report]") {
    // Not a check: the numbers of docs/physics.md#hybrid-switch. Two 1 cm, 1 T
    // cubes, coaxial, against Akoun-Yonnet through the band, by band width; the
    // time of one band pair against a pure near and a pure far one.
    const Vec3 size(0.01, 0.01, 0.01);
    const auto cube = magtest::boxShape(size);
    const double R = cube->boundingRadius;
    const Body bottom = magtest::magnet("bottom", cube, Vec3::Zero(), Vec3::UnitZ());
    auto timeOf = [](const mag::FieldEvaluator& e, const Body& a, const Body& b) {
        int reps = 0;
        double elapsed = 0;
        const auto t0 = std::chrono::steady_clock::now();
        while (elapsed < 0.2) {
            (void)e.interaction(a, b);
            ++reps;
            elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        }
        return 1e6 * elapsed / reps;
    };
    for (double band : {0.0, 0.25, 0.5, 1.0}) {
        auto f = magtest::field("{type: hybrid, switch: {band: " + std::to_string(band) + "}}");
        double worst = 0;
        for (double x = -0.1; x <= 1.1001; x += 0.05) {
            const double centre = 2 * R + R + x * std::max(band, 0.25) * R;
            const Body top = magtest::magnet("top", cube, Vec3(0, 0, centre), Vec3::UnitZ());
            const Vec3 F = f->interaction(bottom, top).force;
            const Vec3 ay = oracle::akounYonnetForce(size, bottom.position, size, top.position, 1.0, 1.0);
            worst = std::max(worst, (F - ay).norm() / ay.norm());
        }
        std::printf("band %.2f R: largest force error against Akoun-Yonnet over the band %.2e\n", band, worst);
    }
    // The fly-by's rod beside the cube, tilted, magnetized obliquely, against
    // MBM at tolerance 1e-7: EDM n = 2 is far rougher for it than for a cube.
    const auto rod = magtest::boxShape(Vec3(0.004, 0.004, 0.012));
    const double Rr = rod->boundingRadius;
    auto exact = magtest::field("{type: MBM, quadrature: {type: adaptive, tolerance: 1e-7}}");
    for (double band : {0.0, 0.25, 0.5, 1.0}) {
        auto f = magtest::field("{type: hybrid, switch: {band: " + std::to_string(band) + "}}");
        double worst = 0, worstEnergy = 0;
        for (double x = -0.1; x <= 1.1001; x += 0.05) {
            const double centre = R + Rr + R + x * std::max(band, 0.25) * R;
            const Body t = magtest::magnet("rod", rod, Vec3(0, centre, 0), Vec3(1, 0.3, -1),
                                           magtest::axisAngle(30, Vec3(1, 1, 0)));
            const mag::Wrench w = f->interaction(bottom, t), ref = exact->interaction(bottom, t);
            worst = std::max(worst, (w.force - ref.force).norm() / ref.force.norm());
            worstEnergy = std::max(worstEnergy, std::abs(w.energy - ref.energy) / std::abs(ref.energy));
        }
        std::printf("rod, band %.2f R: largest force error against MBM %.2e (energy %.2e)\n", band, worst, worstEnergy);
    }
    // The dipole band with dipoleTolerance: a cube and a cube or a 3:1 bar,
    // oblique, through the band, force error against MBM relative to the scale
    // of a dipole pair's force 3 mu0 |m_s| |m_t| / (4 pi d^4) (the tolerance's
    // measure): in the band ((0.75, 1] of the reach sum) and just outside it.
    const auto bar = magtest::boxShape(Vec3(0.03, 0.01, 0.01));
    auto reference = magtest::field("{type: MBM, quadrature: {type: gauss, n: 10}}");
    for (double tol : {1e-2, 1e-3})
        for (const auto& [name, shape] : {std::pair{"cube", cube}, std::pair{"bar", bar}}) {
            auto f = magtest::field("{type: hybrid, dipoleTolerance: " + std::to_string(tol) + "}");
            const Body s =
                magtest::magnet("s", shape, Vec3::Zero(), Vec3(0.2, 0.1, 1), magtest::axisAngle(25, Vec3(1, 2, 0)));
            auto reachOf = [&](const mag::Shape& sh) {
                return std::max(mag::dipoleReachFor(sh, tol), 2.25 * sh.boundingRadius);  // the hybrid's reach
            };
            double inBand = 0, outside = 0;
            for (double x = 0.6; x <= 1.2001; x += 0.02) {
                const double d = x * (reachOf(*shape) + reachOf(*cube));
                const Body t = magtest::magnet("t", cube, d * Vec3(0.3, -0.5, 0.8).normalized(), Vec3(-0.3, 0.4, 1),
                                               magtest::axisAngle(-40, Vec3(0, 1, 3)));
                const double scale = 3 * mag::mu0 * s.magneticMoment().norm() * t.magneticMoment().norm() /
                                     (4 * mag::pi * d * d * d * d);
                const double e = (f->interaction(s, t).force - reference->interaction(s, t).force).norm() / scale;
                double& worst = x > 0.75 && x <= 1 ? inBand : outside;
                worst = std::max(worst, e);
            }
            std::printf("dipoleTolerance %g, %s and cube: largest scaled force error in the dipole band %.2e, "
                        "outside it %.2e\n", tol, name, inBand, outside);
        }
    auto f = magtest::field("{type: hybrid}");
    const Body nearTop = magtest::magnet("top", cube, Vec3(0, 0, 2.9 * R), Vec3::UnitZ());
    const Body bandTop = magtest::magnet("top", cube, Vec3(0, 0, 3.12 * R), Vec3::UnitZ());
    const Body farTop = magtest::magnet("top", cube, Vec3(0, 0, 3.3 * R), Vec3::UnitZ());
    std::printf("one pair: near %.1f us, band %.1f us, far %.1f us\n", timeOf(*f, bottom, nearTop),
                timeOf(*f, bottom, bandTop), timeOf(*f, bottom, farTop));
}

TEST_CASE("fly-by: a compound with a soft part conserves energy", "[flyBy][compound]") {
    // The rod as a compound (docs/compound-bodies.md) of three 4 mm cubes: two
    // magnets (+x, and along y + z) and a steel cube, which the other parts
    // magnetize too (demag). Measured: drift 1.9e-6 (hybrid), excursion 1.9e-3
    // of the peak kinetic energy; the bar is the permanent rod's.
    const std::string rod = "  - name: rod\n"
                            "    parts:\n"
                            "      - {geometry: {box: {size: [0.004, 0.004, 0.004]}}, material: N42, magnetization: [1, 0, 0],"
                            " position: [0, 0, -0.004]}\n"
                            "      - {geometry: {box: {size: [0.004, 0.004, 0.004]}}, material: N42, magnetization: [0, 1, 1],"
                            " position: [0, 0, 0]}\n"
                            "      - {geometry: {box: {size: [0.004, 0.004, 0.004]}}, material: steel, position: [0, 0, 0.004]}\n"
                            "    position: [-0.15, 0.016, 0]\n"
                            "    velocity: [5, 0, 0]\n";
    const FlyBy r = flyBy("{type: hybrid}", 2e-5, rod, "{type: demag}");
    INFO("drift " << r.drift << " (excursion " << r.excursion << "), peak kinetic energy " << r.peakKinetic << " J");
    CHECK(std::abs(r.drift) <= 1e-4);
    CHECK(r.excursion < 5e-3);
    CHECK(r.count("nearPairs") > 0);  // it came close: the parts met the near tier
}

TEST_CASE("fly-by with the paper's coarse rule: the surfaceCharge form conserves energy, the split form does not",
          "[flyBy][mbm]") {
    // One midpoint per face (6 samples on the rod): the split form's force (Eqs.
    // 16-18) is no gradient of anything at this rule, and the rod leaves with
    // 7.5e-2 of its peak kinetic energy gained (measured; 6.9e-3 with 2 x 2
    // midpoints). The surfaceCharge form is the exact gradient of the sampled
    // energy (docs/physics.md#force-form): 2.8e-7 measured, what the integrator
    // leaves (the adaptive rule at 1e-4 leaves 5.4e-7, above). The bar 1e-5 keeps a
    // 36x margin and is 7,000x below the split form's drift.
    const std::string base = "{type: MBM, overlap: charge, quadrature: {type: regular, n: 1, form: ";
    const FlyBy split = flyBy(base + "split}}");
    const FlyBy sigma = flyBy(base + "surfaceCharge}}");
    INFO("split drift " << split.drift << ", surfaceCharge drift " << sigma.drift << " (excursion " << sigma.excursion
                        << "), peak kinetic energy " << sigma.peakKinetic << " J");
    CHECK(std::abs(sigma.drift) <= 1e-5);
    CHECK(std::abs(split.drift) > 1e-2);
}
