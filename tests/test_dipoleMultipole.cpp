// The fast multipole far field (DipoleMultipole.hpp) against its definition, the
// sum of dipolePairWrench() over every dipole pair: the same pairs (counted
// exactly), and each body's force, torque and energy within the expansion's error
// relative to the sum of the magnitudes of its pair terms. Also: bit-identical for
// any thread count, clouds of any shape (clusters, coincident bodies, a line),
// fixed bodies, and the farField settings' errors.
#include "bodyFixture.hpp"

#include <DipoleMultipole.hpp>
#include <magFoam/Error.hpp>
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

struct RestoreThreads {
    int n = mag::threads();
    ~RestoreThreads() { mag::setThreads(n); }
};

// Uniform cloud in a cube of edge `box` with moments ~1 A m^2 in random
// directions and reach in [0, maxReach); every 37th body never a dipole pair,
// every fifth fixed, two coincident.
std::vector<FarFieldBody> cloud(std::size_t n, double box, double maxReach, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-0.5 * box, 0.5 * box), r(0.0, maxReach);
    std::normal_distribution<double> g;
    std::vector<FarFieldBody> out;
    for (std::size_t i = 0; i < n; ++i) {
        const double reach = i % 37 == 3 ? std::numeric_limits<double>::infinity() : r(rng);
        out.push_back({Vec3(u(rng), u(rng), u(rng)), Vec3(g(rng), g(rng), g(rng)), reach, i % 5 == 0});
    }
    out[1].position = out[2].position;
    return out;
}

// The definition, pair by pair, with each body's scale: the sums of |F| and |T|
// of its pair terms (what the dipole approximation's own error is relative to).
struct Reference {
    std::vector<Wrench> w;
    std::vector<double> forceScale, torqueScale, energyScale;
    std::uint64_t pairs = 0;
};
Reference reference(const std::vector<FarFieldBody>& b, bool skip) {
    const std::size_t n = b.size();
    Reference r;
    r.w.resize(n), r.forceScale.assign(n, 0), r.torqueScale.assign(n, 0), r.energyScale.assign(n, 0);
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = 0; j < n; ++j) {
            if (i == j || (skip && b[i].fixed && b[j].fixed) || !mag::isDipolePair(b[i], b[j])) continue;
            const Wrench w = mag::dipolePairWrench(b[j].moment, b[i].moment, b[i].position - b[j].position);
            r.w[i] += w;
            r.forceScale[i] += w.force.norm(), r.torqueScale[i] += w.torque.norm();
            r.energyScale[i] += std::abs(w.energy);
            r.pairs += i < j;
        }
    return r;
}

struct Errors {
    double force = 0, torque = 0, energy = 0;
};
Errors relativeErrors(const std::vector<Wrench>& got, const Reference& ref) {
    Errors e;
    for (std::size_t i = 0; i < got.size(); ++i) {
        if (ref.forceScale[i] == 0) {
            CHECK(got[i].force.norm() == 0);
            continue;
        }
        e.force = std::max(e.force, (got[i].force - ref.w[i].force).norm() / ref.forceScale[i]);
        e.torque = std::max(e.torque, (got[i].torque - ref.w[i].torque).norm() / ref.torqueScale[i]);
        e.energy = std::max(e.energy, std::abs(got[i].energy - ref.w[i].energy) / ref.energyScale[i]);
    }
    return e;
}

} // namespace

TEST_CASE("multipole far field: the dipole pairs' sum, to the expansion's accuracy", "[multipole]") {
    // 3000 bodies, reach up to 2 cm in a 1 m box (translations at every level) and
    // up to 8.6 cm at 3 cm spacing (the scaling benchmark's crowding: many cell
    // pairs fail only the reach test and go direct).
    struct Scene {
        const char* name;
        std::vector<FarFieldBody> bodies;
    };
    const Scene scenes[] = {{"sparse", cloud(3000, 1.0, 0.02, 1)}, {"crowded", cloud(3000, 0.03 * std::cbrt(3000.0), 0.086, 2)}};
    for (const Scene& scene : scenes)
        for (bool skip : {false, true}) {
            INFO(scene.name << (skip ? ", fixed pairs skipped" : ", all pairs"));
            const Reference ref = reference(scene.bodies, skip);
            std::vector<double> errors;
            for (int p : {6, 8, 10, 12, 14}) {
                INFO("order " << p);
                std::vector<Wrench> got(scene.bodies.size());
                mag::MultipoleSettings s;
                s.order = p;
                CHECK(mag::addDipoleFarFieldMultipole(scene.bodies, skip, got, s) == ref.pairs);
                const Errors e = relativeErrors(got, ref);
                // The default p = 12, theta = 0.5 is meant to keep every body's error
                // below 1e-4 of its pairs' scale, 10x below the dipole tier's own
                // tolerance (DipoleFarField.hpp); measured 7e-6 (sparse) and 3.3e-5
                // (crowded) for the force, less for torque and energy.
                if (p == 12) {
                    CHECK(e.force < 1e-4);
                    CHECK(e.torque < 1e-4);
                    CHECK(e.energy < 1e-4);
                }
                errors.push_back(e.force);
            }
            // Raising the order must pay: theta^2 = 1/4 per two orders, less the
            // growth of the derivatives' constants; measured 2.2-7x per step and
            // 140-200x from p = 6 to 14.
            for (std::size_t k = 1; k < errors.size(); ++k) CHECK(errors[k] < errors[k - 1] / 1.5);
            CHECK(errors.back() < errors.front() / 50);
        }
}

TEST_CASE("multipole far field: bit-identical for any thread count", "[multipole]") {
    const RestoreThreads restore;
    const auto bodies = cloud(4000, 1.0, 0.02, 3);
    std::vector<std::vector<Wrench>> runs;
    for (int t : {1, 2, 3}) {
        mag::setThreads(t);
        std::vector<Wrench> w(bodies.size());
        mag::addDipoleFarFieldMultipole(bodies, true, w);
        runs.push_back(std::move(w));
    }
    for (std::size_t r = 1; r < runs.size(); ++r)
        for (std::size_t i = 0; i < bodies.size(); ++i) {
            REQUIRE(runs[r][i].force == runs[0][i].force);
            REQUIRE(runs[r][i].torque == runs[0][i].torque);
            REQUIRE(runs[r][i].energy == runs[0][i].energy);
        }
}

TEST_CASE("multipole far field: clusters, a line, coincident and unusable bodies", "[multipole]") {
    // Two dense clusters 10 m apart, a line of bodies between them (cells of very
    // different sizes and aspect), 100 bodies on one point (a leaf that cannot be
    // split), NaN and infinite-reach bodies (never in a pair).
    std::mt19937 rng(4);
    std::normal_distribution<double> g;
    std::vector<FarFieldBody> b;
    for (int c = 0; c < 2; ++c)
        for (int i = 0; i < 800; ++i)
            b.push_back({Vec3(10.0 * c + 0.05 * g(rng), 0.05 * g(rng), 0.05 * g(rng)), Vec3(g(rng), g(rng), g(rng)), 0.001, false});
    for (int i = 0; i < 400; ++i) b.push_back({Vec3(0.025 * i, 0.3, 0), Vec3(g(rng), g(rng), g(rng)), 0.0, i % 7 == 0});
    for (int i = 0; i < 100; ++i) b.push_back({Vec3(5, 5, 5), Vec3(g(rng), g(rng), g(rng)), 0.0, false});
    const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
    b.push_back({Vec3(nan, 0, 0), Vec3(1, 0, 0), 0.0, false});
    b.push_back({Vec3(0, 0, 0.01), Vec3(1, 0, 0), inf, false});
    for (bool skip : {false, true}) {
        const Reference ref = reference(b, skip);
        std::vector<Wrench> got(b.size());
        CHECK(mag::addDipoleFarFieldMultipole(b, skip, got) == ref.pairs);
        for (const Wrench& w : got) REQUIRE(w.force.allFinite());
        CHECK(got[b.size() - 2].force == Vec3::Zero());  // the NaN body takes no part
        CHECK(got[b.size() - 1].force == Vec3::Zero());  // nor the one never far from anything
        const Errors e = relativeErrors(got, ref);
        CHECK(e.force < 1e-4);
        CHECK(e.torque < 1e-4);
    }
}

TEST_CASE("multipole far field: method choice and settings", "[multipole]") {
    const auto bodies = cloud(600, 1.0, 0.02, 5);
    std::vector<Wrench> direct(bodies.size()), viaAuto(bodies.size()), viaMultipole(bodies.size());
    mag::addDipoleFarField(bodies, false, direct);
    mag::FarFieldSettings s;  // auto: direct up to multipoleAbove bodies
    CHECK(mag::addDipoleFarField(bodies, false, viaAuto, s) > 0);
    for (std::size_t i = 0; i < bodies.size(); ++i) REQUIRE(viaAuto[i].force == direct[i].force);
    s.multipoleAbove = 100;  // 600 bodies: now the multipole sum
    mag::addDipoleFarField(bodies, false, viaMultipole, s);
    bool differs = false;
    for (std::size_t i = 0; i < bodies.size(); ++i) differs = differs || viaMultipole[i].force != direct[i].force;
    CHECK(differs);

    const auto read = [](const std::string& text) {
        return mag::FarFieldSettings::read(mag::Dict::fromString(text, "magSchemes.yaml"));
    };
    CHECK(read("{}").method == mag::FarFieldSettings::Method::automatic);
    const auto m = read("{method: multipole, order: 12, theta: 0.4, leafSize: 16, directPairs: 0}");
    CHECK(m.method == mag::FarFieldSettings::Method::multipole);
    CHECK(m.multipole.order == 12);
    CHECK(m.multipole.theta == 0.4);
    CHECK(m.multipole.leafSize == 16);
    CHECK(m.multipole.directPairs == 0);
    CHECK(read("{method: direct}").describe() == "direct");
    CHECK_THROWS_WITH(read("{method: tree}"), Catch::Contains("method") && Catch::Contains("multipole"));
    CHECK_THROWS_WITH(read("{order: 1}"), Catch::Contains("order"));
    CHECK_THROWS_WITH(read("{theta: 1.5}"), Catch::Contains("theta"));
    CHECK_THROWS_WITH(read("{leafSize: 0}"), Catch::Contains("leafSize"));
    CHECK_THROWS_WITH(read("{directPairs: -1}"), Catch::Contains("directPairs"));
    CHECK_THROWS_WITH(read("{ordr: 8}"), Catch::Contains("order"));
}

TEST_CASE("multipole far field: MagneticSystem sums the dipole pairs by the method set", "[multipole][hybrid]") {
    // 343 cubes of 1 cm on a 7 x 7 x 7 lattice of 4 cm, random orientations; hybrid
    // defaults (dipole pairs beyond 8 (R1 + R2) = 13.9 cm): ~45k dipole pairs.
    std::mt19937 rng(6);
    std::normal_distribution<double> g;
    const auto cube = magtest::boxShape(Vec3::Constant(0.01));
    std::vector<mag::Body> bodies;
    for (int i = 0; i < 343; ++i)
        bodies.push_back(magtest::magnet(fmt::format("m{}", i), cube, 0.04 * Vec3(i % 7, (i / 7) % 7, i / 49),
                                         Vec3(g(rng), g(rng), g(rng)), mag::Quat(g(rng), g(rng), g(rng), g(rng))));
    bodies[0].fixed = bodies[100].fixed = true;
    auto system = [&](const std::string& farField) {
        const std::string field = "{type: hybrid, near: {type: MBM, quadrature: {type: gauss, n: 2}}, farField: " + farField + "}";
        return mag::MagneticSystem(magtest::field(field),
                                   mag::InductionModel::New(mag::Dict::fromString("type: none\n", "test")));
    };
    const auto direct = system("{method: direct}"), multipole = system("{method: multipole}");
    const auto want = direct.wrenches(bodies, true), got = multipole.wrenches(bodies, true);
    const mag::FieldStats countsDirect = direct.fieldEvaluator().stats(), countsMultipole = multipole.fieldEvaluator().stats();
    for (const char* name : {"dipolePairs", "nearPairs", "farPairs"}) {  // the same pairs, near and dipole
        INFO(name);
        CHECK(countsDirect.count(name) == countsMultipole.count(name));
    }
    // Scale: each body's dipole pair terms (the multipole sum's error is relative to these).
    std::vector<FarFieldBody> far;
    for (const auto& b : bodies) far.push_back(mag::farFieldBody(b, 8 * b.shape->boundingRadius));  // hybrid defaults
    const Reference ref = reference(far, true);
    CHECK(ref.pairs > 40000);
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        INFO("body " << i);
        CHECK((got[i].force - want[i].force).norm() <= 1e-4 * ref.forceScale[i]);
        CHECK((got[i].torque - want[i].torque).norm() <= 1e-4 * ref.torqueScale[i]);
    }
}
