// The `Bullet` rigid-body backend (modules/rigidBody/Bullet), with the ODE
// backend's contract: the exact motion of its integrator in free flight,
// bodies resting on the ground without gaining energy, restitution and
// friction against their closed forms, fixed bodies, a magnet-like stack,
// determinism and exact restarts, a NaN guard and bad input.
#include "backendFixture.hpp"
#include "magnetChainFixture.hpp"

#include <magFoam/Parts.hpp>

#include <catch2/catch.hpp>

#include <regex>
#include <sstream>

using Catch::Matchers::Contains;
using namespace backendtest;

TEST_CASE("Bullet: a wrench in free space gives the integrator's exact motion", "[bulletBackend]") {
    // Bullet's step is semi-implicit Euler as ODE's; rotation by the
    // exponential map, the same sum for a fixed axis (a cube: no gyroscopic term).
    checkExactFreeFlight("Bullet", GENERATE(1, 4));
}

TEST_CASE("Bullet: bodies dropped on the ground come to rest on it without gaining energy", "[bulletBackend]") {
    // Each body falls 5 cm (tilted 0.3 rad, so boxes land on an edge) onto z = 0.
    struct Case {
        const char* name;
        Body body;
        double restLow, restHigh;  // COM height at rest, m
        double tilt;
        const char* collision;
        double speed = 1e-5, spin = 1e-3;  // at rest: below these (m/s, rad/s)
    };
    const Body icosphere = ball("ico", 0.01, Kind::mesh);
    double nearFace = 1;
    for (int t = 0; t < icosphere.shape->mesh.nTriangles(); ++t)
        nearFace = std::min(nearFace, icosphere.shape->mesh.normal(t).dot(icosphere.shape->mesh.corner(t, 0)));
    const Body L = makeBody("L", makeL(0.01, 0.01), mag::ShapeKind{});
    std::vector<Case> cases = {{"box", cube("box", 0.02), 0.01, 0.01, 0.3, "auto"},
                               {"sphere", ball("ball", 0.01, Kind::sphere), 0.01, 0.01, 0, "auto"},
                               {"cylinder", rod("rod", 0.01, 0.03), 0.015, 0.015, 0, "auto"},
                               // The 320-face icosphere creeps on at 0.34 mm/s (measured,
                               // steady from 5 s to 10 s): contacts found anew every
                               // sub-step give its near-round hull no friction anchor
                               // (docs/rigid-bodies.md#bullet). Polyhedra with larger
                               // faces rest to 1e-8 m/s.
                               {"icosphere as convex hull", icosphere, nearFace, 0.01, 0.3, "auto", 1e-3, 0.1},
                               {"box as GImpact mesh", cube("box", 0.02, Kind::mesh), 0.01, 0.01, 0.3, "mesh"},
                               {"L prism (concave: GImpact)", L, 0.005, 0.005, 0.0, "auto"}};
    for (Case& c : cases) {
        DYNAMIC_SECTION(c.name) {
            auto rb = backend(std::string("type: Bullet\ngravity: [0, 0, -9.81]\nground: {height: 0}\ncollisionShapes: ") +
                              c.collision + "\n");
            std::vector<Body> bodies = {c.body};
            Body& b = bodies[0];
            b.orientation = Quat(Eigen::AngleAxisd(c.tilt, Vec3(1, 0.4, 0).normalized()));
            b.position = Vec3(0, 0, 0.05 - lowestZ(b));
            rb->setup(bodies);
            const Run run = simulate(*rb, bodies, Vec3(0, 0, -9.81), Vec3::Zero(), 1e-3, 3000);
            INFO(c.name << ": rest height " << b.position.z() << " in [" << c.restLow << ", " << c.restHigh
                        << "], speed " << b.velocity.norm() << ", spin " << b.angularVelocity.norm()
                        << ", energy rise " << run.energyRise << "\n"
                        << rb->describe());
            // At the contact height to the margin (1e-5 m; hulls and meshes
            // rest on it) and the split impulse's allowed penetration (1e-5 m).
            CHECK(b.position.z() > c.restLow - 2e-5);
            CHECK(b.position.z() < c.restHigh + 2e-5);
            CHECK(b.velocity.norm() < c.speed);
            CHECK(b.angularVelocity.norm() < c.spin);
            // A contact never adds energy (round-off of E ~ 0.05 J).
            CHECK(run.energyRise < 1e-9);
        }
    }
}

TEST_CASE("Bullet: restitution and friction follow their closed forms", "[bulletBackend]") {
    SECTION("a ball bounces to e^2 of its drop height") {
        // Dropped from 5 cm: impact at 0.99 m/s, above bounceVelocity.
        const double e = 0.5;
        auto rb = backend("type: Bullet\ngravity: [0, 0, -9.81]\nground: {height: 0}\ncontact: {restitution: " +
                          std::to_string(e) + "}\nsubSteps: 10\n");
        std::vector<Body> bodies = {ball("ball", 0.005, Kind::sphere)};
        bodies[0].position = Vec3(0, 0, 0.055);
        rb->setup(bodies);
        std::vector<Wrench> w(1);
        double peak = 0;
        bool bounced = false;
        for (int n = 0; n < 300; ++n) {
            rb->step(bodies, w, 1e-3);
            if (bodies[0].velocity.z() > 0) bounced = true;
            if (bounced) peak = std::max(peak, bodies[0].position.z() - 0.005);
            if (bounced && bodies[0].velocity.z() < 0) break;
        }
        INFO("bounce height " << peak << " m, expected " << e * e * 0.05);
        // Within the sub-step's discretisation of the impact (h = 1e-4 s at
        // ~1 m/s: 1e-4 m of 0.0125 m) and of the apex.
        CHECK(std::abs(peak - e * e * 0.05) < 0.02 * e * e * 0.05);
    }
    SECTION("a box on the ground sticks below the friction angle and slides above it") {
        const double mu = 0.5, g = 9.81;
        for (double degrees : {20.0, 35.0}) {
            const double t = degrees * mag::pi / 180;
            // Gravity tilted by t along x: the ground is an incline.
            std::ostringstream yaml;
            yaml.precision(17);
            yaml << "type: Bullet\ngravity: [" << g * std::sin(t) << ", 0, " << -g * std::cos(t)
                 << "]\nground: {height: 0}\ncontact: {friction: " << mu << ", restitution: 0}\n";
            auto rb = backend(yaml.str());
            std::vector<Body> bodies = {cube("box", 0.01)};
            bodies[0].position = Vec3(0, 0, 0.005);
            rb->setup(bodies);
            std::vector<Wrench> w(1);
            const double T = 0.3;
            for (int n = 0; n < 300; ++n) rb->step(bodies, w, 1e-3);
            const double slid = bodies[0].position.x();
            const double a = std::max(0.0, g * (std::sin(t) - mu * std::cos(t)));
            INFO(degrees << " deg: slid " << slid << " m, closed form " << 0.5 * a * T * T);
            if (a == 0) {
                CHECK(std::abs(slid) < 1e-6);
            } else {
                // Semi-implicit Euler's a T h / 2 beside the parabola: 0.3 %.
                CHECK(std::abs(slid - 0.5 * a * T * T) < 0.01 * 0.5 * a * T * T);
            }
        }
    }
}

TEST_CASE("Bullet: fixed bodies never move, a cube pulled onto a fixed cube by 50 N rests", "[bulletBackend]") {
    {
        auto rb = backend("type: Bullet\ngravity: [0, 0, -9.81]\n");
        std::vector<Body> bodies = {cube("base", 0.01), cube("hammer", 0.01)};
        Body& base = bodies[0];
        base.fixed = true;
        base.position = Vec3(0.001, 0.002, 0.003);
        base.orientation = Quat(Eigen::AngleAxisd(0.2, Vec3::UnitZ()));
        const Vec3 p0 = base.position;
        const Quat q0 = base.orientation;
        bodies[1].position = Vec3(0.001, 0.002, 0.0145);
        bodies[1].velocity = Vec3(0, 0, -2);
        rb->setup(bodies);
        std::vector<Wrench> w(2);
        w[0].force = Vec3(100, 0, 0);
        for (int n = 0; n < 200; ++n) rb->step(bodies, w, 1e-3);
        CHECK(base.position == p0);
        CHECK(base.orientation.coeffs() == q0.coeffs());
        CHECK(base.velocity == Vec3::Zero());
        CHECK(bodies[1].position.z() > 0.0085);  // bounced off and fell back onto it
    }
    const double dt = GENERATE(1e-4, 1e-3);
    const double tilt = GENERATE(0.0, 0.3);
    const Stack s = stack("type: Bullet\ngravity: [0, 0, -9.81]\n", cube("top", 0.01), dt, tilt, 0.002);
    INFO("dt " << dt << " tilt " << tilt << ": penetration " << s.penetration << " (deepest " << s.deepest
               << "), speed " << s.speed << ", spin " << s.spin << ", energy rise " << s.run.energyRise
               << ", max speed " << s.run.maxSpeed << "\n"
               << s.describe);
    // In contact within the split impulse's threshold (1e-5 m).
    CHECK(std::abs(s.penetration) < 2e-5);
    CHECK(s.speed < 1e-4);
    CHECK(s.spin < 1e-2);
    CHECK(s.run.energyRise < 1e-9);
    CHECK(s.run.maxSpeed < 4 * s.impactSpeed);
}

TEST_CASE("Bullet: a pair pressed together keeps zero angular momentum and rests on the ground", "[bulletBackend]") {
    checkPressedPair("Bullet");
}

TEST_CASE("Bullet: rolling and spinning friction stop a ball as their closed forms say", "[bulletBackend]") {
    checkRollingSpinning("Bullet");
}

TEST_CASE("Bullet: a bar pressed onto a convex block holds a torque", "[bulletBackend]") {
    checkBarOnBlock("Bullet");
}

TEST_CASE("Bullet: four magnets that fall into a chain come to rest on the ground", "[bulletBackend]") {
    // tutorials/magnetChain on Bullet, the tilt swing explicit (Bullet does
    // not take the implicit one).
    auto run = [](const std::string& extra) {
        return magtest::magnetChainAtRest([&](std::string& control, std::string& rigid) {
            control = std::regex_replace(control, std::regex("\\nmagneticStiffness:[^\\n]*"), "");
            rigid = "type: Bullet\ngravity: [0, 0, -9.81]\nground: {height: 0}\n"
                    "contact: {friction: 0.5, restitution: 0.1}\n" + extra;
        });
    };
    // Measured: at rest to 6e-6 m/s at the end. Before friction saw the
    // torques and held in both directions, no solver count brought them to
    // rest (Fig. 7 with 500 sweeps: still 0.46 m/s).
    CHECK(run("") == 4);
    // Bullet's usual 50 sweeps leave them moving at 0.2 m/s: the default of
    // 1000 is needed, and this fails if 50 ever suffices.
    CHECK(run("solverIterations: 50\n") == 0);
}

namespace {

std::vector<Body> pile() {
    std::vector<Body> bodies = {cube("a", 0.01), ball("b", 0.005, Kind::mesh), cube("c", 0.01, Kind::mesh),
                                rod("d", 0.004, 0.02), makeBody("L", makeL(0.006, 0.006), mag::ShapeKind{})};
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        bodies[i].position = Vec3(0.003 * i, 0.002 * (i % 2), 0.012 * (i + 1));
        bodies[i].orientation = Quat(Eigen::AngleAxisd(0.4 * i, Vec3(1, 1, 0.5).normalized()));
    }
    return bodies;
}

void requireSame(const std::vector<Body>& x, const std::vector<Body>& y) {
    for (std::size_t i = 0; i < x.size(); ++i) {
        INFO("body " << x[i].name);
        CHECK(x[i].position == y[i].position);
        CHECK(x[i].orientation.coeffs() == y[i].orientation.coeffs());
        CHECK(x[i].velocity == y[i].velocity);
        CHECK(x[i].angularVelocity == y[i].angularVelocity);
    }
}

} // namespace

TEST_CASE("Bullet: runs are bit-identical and restart bit for bit", "[bulletBackend]") {
    const std::string yaml = "type: Bullet\ngravity: [0, 0, -9.81]\nground: {height: 0}\n";
    std::vector<Wrench> w(5);
    w[1].force = Vec3(0.05, 0, -0.5);
    std::vector<Body> one = pile(), two = pile(), three = pile();
    auto a = backend(yaml), b = backend(yaml);
    a->setup(one);
    for (int n = 0; n < 400; ++n) a->step(one, w, 1e-3);
    // Two backends in one process, stepped alternately.
    a = backend(yaml);
    a->setup(two);
    b->setup(three);
    for (int n = 0; n < 400; ++n) a->step(two, w, 1e-3), b->step(three, w, 1e-3);
    requireSame(one, two);
    requireSame(two, three);
    CHECK(one[4].position.z() < 0.03);  // the pile fell and collided

    // A restart at step 250 (a new backend, the bodies' state and the
    // backend's state file) continues bit for bit.
    std::vector<Body> first = pile();
    auto c = backend(yaml);
    c->setup(first);
    for (int n = 0; n < 250; ++n) c->step(first, w, 1e-3);
    std::ostringstream state;
    c->writeState(state, first);
    std::vector<Body> second = pile();
    for (std::size_t i = 0; i < second.size(); ++i) static_cast<mag::BodyState&>(second[i]) = first[i];
    auto d = backend(yaml);
    d->setup(pile());
    d->setState(second);
    d->readState(mag::Dict::fromString(state.str(), "0.25/rigidBody.yaml"), second);
    for (int n = 250; n < 400; ++n) d->step(second, w, 1e-3);
    requireSame(one, second);
}

TEST_CASE("Bullet: a compound rests like the single body of its shape", "[bulletBackend][compound]") {
    // A 20 x 10 x 6 mm bar as one box and as two boxes of different density.
    mag::Material heavy, light;
    heavy.density = 7500, light.density = 1200;
    auto box = [](const Vec3& size) {
        mag::ShapeKind k;
        k.kind = Kind::box;
        k.size = size;
        return mag::makeShape(mag::makeBox(size), k);
    };
    const mag::CompoundLayout layout = mag::makeCompound(
        {mag::Part{box(Vec3(0.01, 0.01, 0.006)), heavy, Vec3(-0.005, 0, 0), Quat::Identity()},
         mag::Part{box(Vec3(0.01, 0.01, 0.006)), light, Vec3(0.005, 0, 0), Quat::Identity()}});
    Body bar;
    bar.name = "bar";
    bar.shape = layout.shape;
    bar.compound = layout.compound;
    bar.partMagnetization = {Vec3::Zero(), Vec3::Zero()};
    Body single = makeBody("single", mag::makeBox(Vec3(0.02, 0.01, 0.006)), mag::ShapeKind{});
    for (Body* b : {&bar, &single}) {
        b->orientation = Quat(Eigen::AngleAxisd(0.17, Vec3(1, 1, 0).normalized()));
        b->position = Vec3(0, 0, 0.008);
        std::vector<Body> bodies = {*b};
        auto rb = backend("type: Bullet\ngravity: [0, 0, -9.81]\nground: {height: 0}\n");
        rb->setup(bodies);
        simulate(*rb, bodies, Vec3(0, 0, -9.81), Vec3::Zero(), 5e-4, 500);
        INFO(b->name << ": z " << bodies[0].position.z() << "\n" << rb->describe());
        CHECK(std::abs(bodies[0].position.z() - 0.003) < 2e-5);
        CHECK(bodies[0].velocity.norm() < 1e-4);
        CHECK((bodies[0].orientation * Vec3::UnitZ()).z() > 1 - 1e-6);
    }
}

TEST_CASE("Bullet: a NaN wrench and bad dictionaries are clear errors", "[bulletBackend][badInput]") {
    auto rb = backend("type: Bullet\n");
    std::vector<Body> bodies = {cube("c", 0.01)};
    rb->setup(bodies);
    std::vector<Wrench> w(1);
    w[0].force = Vec3(0, std::nan(""), 0);
    CHECK_THROWS_WITH(rb->step(bodies, w, 1e-3), Contains("body 'c'") && Contains("not finite"));
    CHECK(bodies[0].position.allFinite());

    CHECK_THROWS_WITH(backend("type: Bullet\ncontact: {frictoin: 0.5}\n"),
                      Contains("rigidBody.yaml:2") && Contains("did you mean 'friction'"));
    CHECK_THROWS_WITH(backend("type: Bullet\ncontact: {restitution: 1.5}\n"), Contains("restitution must be in [0, 1]"));
    CHECK_THROWS_WITH(backend("type: Bullet\ncontact: {margin: 0}\n"), Contains("margin must be > 0"));
    CHECK_THROWS_WITH(backend("type: Bullet\ncontact: {spinningFriction: -1}\n"),
                      Contains("spinningFriction must be >= 0"));
    CHECK_THROWS_WITH(backend("type: Bullet\ncontact: {friction: 0, rollingFriction: 1e-5}\n"),
                      Contains("rollingFriction") && Contains("need friction > 0"));
    CHECK_THROWS_WITH(backend("type: Bullet\nsolverIterations: 0\n"), Contains("solverIterations must be 1..10000"));
    CHECK_THROWS_WITH(backend("type: Bullet\ncollisionShapes: convex\n"), Contains("valid values: auto, trimesh, mesh"));
    CHECK_THROWS_WITH(backend("type: Bullet\nccd: {sweptSphere: 2}\n"), Contains("(0, 1]"));
    CHECK_THROWS_WITH(backend("type: Bullet\nstepper: quickStep\n"), Contains("unknown key 'stepper'"));
}
