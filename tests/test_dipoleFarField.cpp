// The bulk far field (DipoleFarField.hpp) against the pair-by-pair definition:
// the grid finds exactly the pairs a brute-force test calls near; the bulk sum
// equals the sum of dipolePairWrench over the other pairs; it conserves momentum
// and angular momentum; it is bit-identical for any thread count; and
// MagneticSystem with the hybrid gives what calling interaction() on every pair
// gives.
#include "bodyFixture.hpp"

#include <DipoleFarField.hpp>
#include <magFoam/InductionModel.hpp>
#include <magFoam/MagneticSystem.hpp>
#include <magFoam/Threads.hpp>

#include <catch2/catch.hpp>
#include <spdlog/fmt/fmt.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

using mag::FarFieldBody;
using mag::Vec3;
using mag::Wrench;

namespace {

// N bodies in a 0.3 m box, moments ~1 A m^2 in random directions, reach 0..3 cm,
// a few of them never dipole pairs (reach +inf), every fifth fixed.
std::vector<FarFieldBody> randomBodies(std::size_t n, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-0.15, 0.15), r(0.0, 0.03);
    std::normal_distribution<double> g;
    std::vector<FarFieldBody> out;
    for (std::size_t i = 0; i < n; ++i) {
        const double reach = i % 37 == 3 ? std::numeric_limits<double>::infinity() : r(rng);
        out.push_back({Vec3(u(rng), u(rng), u(rng)), Vec3(g(rng), g(rng), g(rng)), reach, i % 5 == 0});
    }
    out[1].position = out[2].position;  // coincident bodies: near, never divided by zero
    return out;
}

struct RestoreThreads {
    int n = mag::threads();
    ~RestoreThreads() { mag::setThreads(n); }
};

} // namespace

TEST_CASE("far field: the grid finds exactly the near pairs", "[farField]") {
    const auto bodies = randomBodies(300, 1);
    for (bool skip : {false, true}) {
        std::vector<std::pair<std::size_t, std::size_t>> brute;
        for (std::size_t i = 0; i < bodies.size(); ++i)
            for (std::size_t j = i + 1; j < bodies.size(); ++j) {
                if (skip && bodies[i].fixed && bodies[j].fixed) continue;
                const double d = (bodies[i].position - bodies[j].position).norm();
                if (!(d > bodies[i].reach + bodies[j].reach)) brute.emplace_back(i, j);
            }
        const auto grid = mag::nearPairs(bodies, skip);
        CHECK(grid == brute);
        CHECK(grid.size() > 300);  // not trivially empty: the inf-reach bodies alone give ~2400
    }
}

TEST_CASE("far field: the bulk sum equals the pair-by-pair dipole wrenches", "[farField]") {
    const auto bodies = randomBodies(300, 2);
    const std::size_t n = bodies.size();
    for (bool skip : {false, true}) {
        INFO((skip ? "fixed pairs skipped" : "all pairs"));
        std::vector<Wrench> bulk(n), pairwise(n);
        const std::uint64_t count = mag::addDipoleFarField(bodies, skip, bulk);
        std::uint64_t expected = 0;
        for (std::size_t i = 0; i < n; ++i)
            for (std::size_t j = 0; j < n; ++j) {
                if (i == j || (skip && bodies[i].fixed && bodies[j].fixed)) continue;
                if (!mag::isDipolePair(bodies[i], bodies[j])) continue;
                pairwise[i] += mag::dipolePairWrench(bodies[j].moment, bodies[i].moment,
                                                     bodies[i].position - bodies[j].position);
                expected += i < j;
            }
        CHECK(count == expected);
        CHECK(expected > n * (n - 1) / 4);  // most pairs are dipole pairs
        double fScale = 0, tScale = 0, eScale = 0;
        for (const auto& w : pairwise)
            fScale = std::max(fScale, w.force.norm()), tScale = std::max(tScale, w.torque.norm()),
            eScale = std::max(eScale, std::abs(w.energy));
        // Same formula, different rounding (vector lanes, no FMA, the terms
        // grouped differently); sums of a few hundred terms of mixed sign:
        // 1e-12 of the largest body's value is ~100x the rounding seen.
        for (std::size_t i = 0; i < n; ++i) {
            INFO("body " << i);
            CHECK((bulk[i].force - pairwise[i].force).norm() <= 1e-12 * fScale);
            CHECK((bulk[i].torque - pairwise[i].torque).norm() <= 1e-12 * tScale);
            CHECK(std::abs(bulk[i].energy - pairwise[i].energy) <= 1e-12 * eScale);
            CHECK(bulk[i].mechanicalTorque == Vec3::Zero());
        }
    }
}

TEST_CASE("far field: momentum and angular momentum are conserved", "[farField]") {
    const auto bodies = randomBodies(200, 3);
    std::vector<Wrench> w(bodies.size());
    (void)mag::addDipoleFarField(bodies, false, w);
    Vec3 F = Vec3::Zero(), L = Vec3::Zero();
    double fScale = 0, lScale = 0;
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        F += w[i].force;
        const Vec3 l = w[i].torque + bodies[i].position.cross(w[i].force);
        L += l;
        fScale += w[i].force.norm(), lScale += l.norm();
    }
    // Each pair's terms cancel analytically; what is left is rounding.
    CHECK(F.norm() <= 1e-13 * fScale);
    CHECK(L.norm() <= 1e-13 * lScale);
}

TEST_CASE("far field: bit-identical for 1, 2 and 3 threads, NaN stays out", "[farField][threads]") {
    RestoreThreads restore;
    auto bodies = randomBodies(250, 4);
    bodies[7].position = Vec3(std::nan(""), 0, 0);
    std::vector<std::vector<Wrench>> results;
    for (int t : {1, 2, 3}) {
        mag::setThreads(t);
        results.emplace_back(bodies.size());
        (void)mag::addDipoleFarField(bodies, true, results.back());
    }
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        INFO("body " << i);
        CHECK(results[0][i].force.allFinite());
        for (int k : {1, 2}) {
            CHECK(results[0][i].force == results[k][i].force);
            CHECK(results[0][i].torque == results[k][i].torque);
            CHECK(results[0][i].energy == results[k][i].energy);
        }
    }
    // A body at NaN is no one's dipole partner (its pairs go the near way).
    CHECK(results[0][7].force == Vec3::Zero());
}

TEST_CASE("far field: MagneticSystem with the hybrid equals interaction() on every pair", "[farField][hybrid]") {
    // 60 cubes of 1 cm on a 4 x 4 x 4 lattice of 5 cm with 4 left out, one fixed:
    // hybrid defaults (reach 8 R) make neighbours EDM pairs and the rest dipole pairs.
    std::mt19937 rng(5);
    std::normal_distribution<double> g;
    const auto cube = magtest::boxShape(Vec3::Constant(0.01));
    std::vector<mag::Body> bodies;
    for (int i = 0; i < 64; ++i) {
        if (i % 16 == 5) continue;
        const Vec3 p = 0.05 * Vec3(i % 4, (i / 4) % 4, i / 16);
        bodies.push_back(magtest::magnet(fmt::format("m{}", i), cube, p, Vec3(g(rng), g(rng), g(rng)),
                                         mag::Quat(g(rng), g(rng), g(rng), g(rng))));
    }
    bodies[0].fixed = true;
    const auto field = "{type: hybrid, near: {type: MBM, quadrature: {type: gauss, n: 4}}}";
    const mag::MagneticSystem system(magtest::field(field),
                                     mag::InductionModel::New(mag::Dict::fromString("type: none\n", "test")));
    const auto got = system.wrenches(bodies);
    const mag::FieldStats counts = system.fieldEvaluator().stats();
    INFO(counts.format());
    // The dipole pairs: centre distance > 8 (R1 + R2) (hybrid defaults).
    int dipolePairs = 0;
    const double R = cube->boundingRadius;
    for (std::size_t i = 0; i < bodies.size(); ++i)
        for (std::size_t j = i + 1; j < bodies.size(); ++j)
            dipolePairs += (bodies[i].position - bodies[j].position).norm() > 16 * R;
    CHECK(dipolePairs > 800);
    CHECK(counts.count("dipolePairs") == static_cast<std::uint64_t>(dipolePairs));
    // Reference: every pair through the evaluator's own interaction(), target the
    // later body, the source the reaction (as MagneticSystem does for near pairs).
    const auto reference = magtest::field(field);
    std::vector<Wrench> want(bodies.size());
    for (std::size_t i = 0; i < bodies.size(); ++i)
        for (std::size_t j = i + 1; j < bodies.size(); ++j) {
            const Wrench w = reference->interaction(bodies[i], bodies[j]);
            want[j] += w;
            Wrench r;
            r.force = -w.force;
            r.torque = -w.totalTorque() - (bodies[j].position - bodies[i].position).cross(w.force);
            r.energy = w.energy;
            want[i] += r;
        }
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        INFO("body " << i);
        // Only the summation order of the dipole pairs differs.
        CHECK((got[i].force - want[i].force).norm() <= 1e-12 * want[i].force.norm());
        CHECK((got[i].totalTorque() - want[i].totalTorque()).norm() <= 1e-12 * want[i].totalTorque().norm());
        CHECK(got[i].energy == Approx(want[i].energy).epsilon(1e-12));
    }
}
