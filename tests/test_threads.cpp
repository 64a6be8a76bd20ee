// Worker threads: MagneticSystem::wrenches gives bit-identical results for 1, 2
// and 3 threads, for MBM (pairs in parallel, and one pair's sample blocks in
// parallel), EDM and the hybrid (near, far and dipole pairs); parallelFor
// rethrows the first exception by index.
#include <magFoam/Body.hpp>
#include <magFoam/FieldEvaluator.hpp>
#include <magFoam/InductionModel.hpp>
#include <magFoam/MagneticSystem.hpp>
#include <magFoam/MeshPrimitives.hpp>
#include <magFoam/ShapeFactory.hpp>
#include <magFoam/Threads.hpp>

#include <catch2/catch.hpp>

#include <atomic>
#include <cstdlib>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

using mag::Body;
using mag::Quat;
using mag::Vec3;

namespace {

std::shared_ptr<const mag::Shape> box(const Vec3& size) {
    mag::ShapeKind kind;
    kind.kind = mag::ShapeKind::Kind::box;
    kind.size = size;
    return mag::makeShape(mag::makeBox(size), kind);
}

Body magnet(const std::string& name, std::shared_ptr<const mag::Shape> shape, const Vec3& position, std::mt19937& rng,
            bool fixed = false) {
    std::uniform_real_distribution<double> u(-1, 1);
    Body b;
    b.name = name;
    b.shape = std::move(shape);
    b.material.Br = 1.2;
    b.material.density = 7500;
    b.magnetizationBody = Vec3(u(rng), u(rng), 1.0).normalized() * (1.2 / mag::mu0);
    b.position = position;
    b.orientation = Quat(Eigen::AngleAxisd(3.0 * u(rng), Vec3(u(rng), u(rng), u(rng) + 2).normalized()));
    b.fixed = fixed;
    return b;
}

// A cluster of touching-close magnets (near pairs), one a few cm away (far), two
// far beyond 8 (R1 + R2) (dipole pairs under the hybrid's default), one fixed.
std::vector<Body> scene() {
    std::mt19937 rng(7);
    const auto cube = box(Vec3::Constant(0.01));
    const auto bar = box(Vec3(0.02, 0.006, 0.008));
    return {magnet("a", cube, Vec3(0, 0, 0), rng, true), magnet("b", cube, Vec3(0.0005, 0.001, 0.0125), rng),
            magnet("c", bar, Vec3(0.014, -0.002, 0.004), rng), magnet("d", cube, Vec3(-0.04, 0.01, 0.02), rng),
            magnet("e", bar, Vec3(0.3, 0.05, 0.0), rng), magnet("f", cube, Vec3(-0.1, 0.35, 0.1), rng)};
}

std::vector<mag::Wrench> wrenchesWith(int threads, const std::string& field, const std::vector<Body>& bodies,
                                      bool skipFixed) {
    mag::setThreads(threads);
    const mag::MagneticSystem system(mag::FieldEvaluator::New(mag::Dict::fromString(field, "test_threads")),
                                     mag::InductionModel::New(mag::Dict::fromString("type: none\n", "test_threads")));
    return system.wrenches(bodies, skipFixed);
}

void requireIdentical(const std::vector<mag::Wrench>& a, const std::vector<mag::Wrench>& b) {
    REQUIRE(a.size() == b.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
        INFO("body " << i);
        // Exact equality, component by component: the partition and the order of
        // every sum are fixed, whatever the thread count.
        CHECK(a[i].force == b[i].force);
        CHECK(a[i].torque == b[i].torque);
        CHECK(a[i].mechanicalTorque == b[i].mechanicalTorque);
        CHECK(a[i].energy == b[i].energy);
    }
}

struct RestoreThreads {
    int n = mag::threads();
    ~RestoreThreads() { mag::setThreads(n); }
};

} // namespace

TEST_CASE("wrenches are bit-identical for 1, 2 and 3 threads", "[threads]") {
    RestoreThreads restore;
    const std::vector<Body> bodies = scene();
    for (const std::string field :
         {"{type: MBM, quadrature: {type: gauss, n: 6}}",
          "{type: MBM, quadrature: {type: regular, n: 7}, overlap: amperian}", "{type: EDM, n: 3}",
          "{type: hybrid, near: {type: MBM, quadrature: {type: gauss, n: 6}}}"}) {
        for (bool skipFixed : {false, true}) {
            INFO(field << (skipFixed ? ", fixed targets skipped" : ""));
            const auto one = wrenchesWith(1, field, bodies, skipFixed);
            // Not trivially zero: every body feels the others.
            for (const auto& w : one) CHECK(w.force.norm() > 0);
            requireIdentical(one, wrenchesWith(2, field, bodies, skipFixed));
            requireIdentical(one, wrenchesWith(3, field, bodies, skipFixed));
        }
    }
}

TEST_CASE("the hybrid scene has near, far and dipole pairs", "[threads]") {
    RestoreThreads restore;
    mag::setThreads(2);
    const mag::MagneticSystem system(mag::FieldEvaluator::New(mag::Dict::fromString("{type: hybrid}", "test_threads")),
                                     mag::InductionModel::New(mag::Dict::fromString("type: none\n", "test_threads")));
    (void)system.wrenches(scene());
    const mag::FieldStats s = system.fieldEvaluator().stats();
    INFO(s.format());
    // 15 pairs: a-b, a-c, b-c near; e and f are dipole pairs with everything
    // (e-f included); the rest (a-d, b-d, c-d) far.
    CHECK(s.count("dipolePairs") == 9);
    CHECK(s.count("nearPairs") == 3);
    CHECK(s.count("farPairs") == 3);
}

TEST_CASE("one MBM pair (two cubes) is bit-identical on any thread count", "[threads]") {
    // A single pair runs its sample blocks on the threads (600 samples: 19 blocks).
    RestoreThreads restore;
    std::mt19937 rng(3);
    const auto cube = box(Vec3::Constant(0.01));
    const std::vector<Body> bodies = {magnet("bottom", cube, Vec3::Zero(), rng, true),
                                      magnet("top", cube, Vec3(0.001, 0.0, 0.0102), rng)};
    for (const std::string field : {"{type: MBM}", "{type: MBM, quadrature: {type: regular, n: 20}}"}) {
        INFO(field);
        const auto one = wrenchesWith(1, field, bodies, true);
        CHECK(one[1].force.norm() > 1);
        requireIdentical(one, wrenchesWith(2, field, bodies, true));
        requireIdentical(one, wrenchesWith(3, field, bodies, true));
    }
}

TEST_CASE("one thread by default, setThreads: 0 is all cores, parallelFor visits every index and "
          "rethrows the first error",
          "[threads]") {
    // Every test case restores the count it found, so this is the library's default.
    if (!std::getenv("OMP_NUM_THREADS")) CHECK(mag::threads() == 1);
    RestoreThreads restore;
    CHECK(mag::setThreads(0) == mag::availableCores());
    CHECK(mag::setThreads(3) == 3);
    // More than the machine can start is capped (controlDict threads: 100000 crashed in OpenMP).
    CHECK(mag::setThreads(100000) == mag::maxThreads());
    CHECK(mag::maxThreads() >= mag::availableCores());
    CHECK(mag::setThreads(3) == 3);
    std::vector<std::atomic<int>> seen(100);
    mag::parallelFor(seen.size(), [&](std::size_t i) { seen[i] += 1; });
    for (const auto& s : seen) CHECK(s == 1);
    auto failing = [](std::size_t i) {
        if (i == 17 || i == 31) throw std::runtime_error(i == 17 ? "index 17" : "index 31");
    };
    CHECK_THROWS_WITH(mag::parallelFor(50, failing), "index 17");
}
