// The `ODE` rigid-body backend (modules/rigidBody/ODE) against independent
// references: the exact solution of its integrator in free flight, the rest
// height of bodies on the ground, energy bookkeeping (a contact must never
// add energy), and determinism. The magnet-like scenes pull a 1 cm, 7.5 g cube
// onto a fixed one with 50 N (~680 g), as magnets do.
#include "backendFixture.hpp"

#include <catch2/catch.hpp>

#include <cstdio>

using Catch::Matchers::Contains;
using namespace backendtest;

TEST_CASE("ODE: a wrench in free space gives the integrator's exact motion", "[odeBackend]") {
    // ODE's dWorldStep is semi-implicit Euler; in finite rotation mode the
    // angle about a fixed axis is the same sum as the position's.
    checkExactFreeFlight("ODE", GENERATE(1, 4));
}

TEST_CASE("ODE: bodies dropped on the ground come to rest on it without gaining energy", "[odeBackend]") {
    // Each body falls 5 cm (tilted 0.3 rad, so boxes land on an edge) onto
    // the plane z = 0, and rests after 1 s at its half height, minus the
    // surface layer (1 um) that ODE leaves uncorrected.
    struct Case {
        const char* name;
        Body body;
        double restLow, restHigh; // COM height at rest without the layer, m
        double tilt;              // dropped tilted by this angle, rad
        const char* collision;
    };
    // An icosphere rests on a face, an edge or a vertex: between its nearest
    // face plane and its vertices (r) from the centre.
    const Body icosphere = ball("ico", 0.01, Kind::mesh);
    double nearFace = 1;
    for (int t = 0; t < icosphere.shape->mesh.nTriangles(); ++t)
        nearFace = std::min(nearFace, icosphere.shape->mesh.normal(t).dot(icosphere.shape->mesh.corner(t, 0)));
    // (The cylinder falls upright: landing tilted on its rim at 1 m/s kicks it
    // over (energy allows it), and lying on its side it rolls on for ever:
    // ODE has no rolling friction.)
    std::vector<Case> cases = {{"native box", cube("box", 0.02), 0.01, 0.01, 0.3, "auto"},
                               {"native sphere", ball("ball", 0.01, Kind::sphere), 0.01, 0.01, 0, "auto"},
                               {"native cylinder", rod("rod", 0.01, 0.03), 0.015, 0.015, 0, "auto"},
                               {"box as trimesh", cube("box", 0.02, Kind::mesh), 0.01, 0.01, 0.3, "mesh"},
                               {"icosphere as trimesh", icosphere, nearFace, 0.01, 0.3, "mesh"}};
    for (Case& c : cases) {
        DYNAMIC_SECTION(c.name) {
            auto rb = backend(std::string("type: ODE\ngravity: [0, 0, -9.81]\nground: {height: 0}\ncollisionShapes: ") +
                              c.collision + "\n");
            std::vector<Body> bodies = {c.body};
            Body& b = bodies[0];
            b.orientation = Quat(Eigen::AngleAxisd(c.tilt, Vec3(1, 0.4, 0).normalized()));
            b.position = Vec3(0, 0, 0.05 - lowestZ(b));
            rb->setup(bodies);
            const Run run = simulate(*rb, bodies, Vec3(0, 0, -9.81), Vec3::Zero(), 1e-3, 3000);
            INFO(c.name << ": rest height " << b.position.z() << " in [" << c.restLow << ", " << c.restHigh
                        << "] - 1e-6, speed " << b.velocity.norm() << ", spin " << b.angularVelocity.norm()
                        << ", energy rise " << run.energyRise);
            // At rest in contact: ODE corrects no penetration shallower than
            // its surface layer (1 um), so the lowest point ends inside that
            // layer, touching (> 0) and not deeper (+ 1e-7 for the LCP's
            // softness). Where in the layer depends on how the body tipped:
            // friction holds a tilt of up to layer / size (measured 0.2-1 um).
            CHECK(-lowestZ(b) > 0);
            CHECK(-lowestZ(b) < 1e-6 + 1e-7);
            // On a face (box), on the sphere's bottom, or between the
            // icosphere's nearest face and its vertices.
            CHECK(b.position.z() > c.restLow - 1e-6 - 1e-7);
            CHECK(b.position.z() < c.restHigh + 1e-7);
            // At rest: ~1e-9 m/s measured; 1e-6 m/s is far below any motion.
            CHECK(b.velocity.norm() < 1e-6);
            CHECK(b.angularVelocity.norm() < 1e-4);
            // A contact never adds energy: the tolerance is round-off of E ~ 0.05 J.
            CHECK(run.energyRise < 1e-12);
        }
    }
}

TEST_CASE("ODE: a pair pressed together keeps zero angular momentum and rests on the ground", "[odeBackend]") {
    checkPressedPair("ODE");
}

TEST_CASE("ODE: rolling and spinning friction stop a ball as their closed forms say", "[odeBackend]") {
    checkRollingSpinning("ODE");
}

TEST_CASE("ODE: a bar pressed onto a convex block holds a torque", "[odeBackend]") {
    checkBarOnBlock("ODE");
}

TEST_CASE("ODE: fixed bodies never move", "[odeBackend]") {
    auto rb = backend("type: ODE\ngravity: [0, 0, -9.81]\n");
    std::vector<Body> bodies = {cube("base", 0.01), cube("hammer", 0.01)};
    Body& base = bodies[0];
    base.fixed = true;
    base.position = Vec3(0.001, 0.002, 0.003);
    base.orientation = Quat(Eigen::AngleAxisd(0.2, Vec3::UnitZ()));
    base.velocity = Vec3(1, 0, 0); // ignored: fixed bodies are written back at rest
    const Vec3 p0 = base.position;
    const Quat q0 = base.orientation;
    // The other body hits it at 2 m/s.
    bodies[1].position = Vec3(0.001, 0.002, 0.0145);
    bodies[1].velocity = Vec3(0, 0, -2);
    rb->setup(bodies);
    std::vector<Wrench> w(2);
    w[0].force = Vec3(100, 0, 0), w[0].torque = Vec3(0, 0, 1); // a wrench on a fixed body does nothing
    for (int n = 0; n < 200; ++n) rb->step(bodies, w, 1e-3);
    CHECK(base.position == p0);
    CHECK(base.orientation.coeffs() == q0.coeffs());
    CHECK(base.velocity == Vec3::Zero());
    CHECK(base.angularVelocity == Vec3::Zero());
    // The hammer bounced off and fell back onto it.
    CHECK(bodies[1].position.z() > 0.0085);
}

TEST_CASE("ODE: a cube pulled onto a fixed cube by 50 N comes to rest in contact", "[odeBackend]") {
    // 7.5 g pulled by 50 N: ~680 g. Released 0.5 mm above (2.6 m/s at impact).
    const double dt = GENERATE(1e-4, 1e-3);
    const bool asMesh = GENERATE(false, true);
    const double tilt = GENERATE(0.0, 0.3);
    const std::string yaml = std::string("type: ODE\ngravity: [0, 0, -9.81]\ncollisionShapes: ") +
                             (asMesh ? "mesh" : "auto") + "\n";
    const Stack s = stack(yaml, cube("top", 0.01, asMesh ? Kind::mesh : Kind::box), dt, tilt, 0.002);
    INFO((asMesh ? "trimesh" : "box") << " dt " << dt << " tilt " << tilt << ": penetration " << s.penetration
                                      << " (deepest " << s.deepest << ")"
                                      << ", speed " << s.speed << ", spin " << s.spin << ", energy rise "
                                      << s.run.energyRise << ", max speed " << s.run.maxSpeed << ", lateral "
                                      << s.lateral << "\n"
                                      << s.describe);
    // In contact, its lowest corner inside the 1 um surface layer that ODE
    // leaves uncorrected (+ 0.5 um); friction holds the tilt with which it
    // came to rest, up to layer / size (measured 0.48..1.20 um deep).
    CHECK(s.penetration > 0);
    CHECK(s.penetration < 1.5e-6);
    // At rest (measured <= 2e-7 m/s, 1e-5 rad/s).
    CHECK(s.speed < 1e-5);
    CHECK(s.spin < 1e-3);
    // No energy gained: contacts, restitution and penetration correction only
    // take energy out (round-off of E ~ 0.5 J).
    CHECK(s.run.energyRise < 1e-9);
    // No point ever moves faster than the impact plus the tumble of a tilted
    // landing (|v| + |w| r, r the bounding radius): 4x impact (measured 3.3x).
    CHECK(s.run.maxSpeed < 4 * s.impactSpeed);
    // Sideways: a tilted cube shifts by < 3 mm as it tips flat; a flat one stays.
    CHECK(s.lateral < (tilt > 0 ? 3e-3 : 1e-6));
}

TEST_CASE("ODE: trimesh-trimesh contacts rest stably", "[odeBackend]") {
    SECTION("two icospheres attracted centre to centre") {
        auto rb = backend("type: ODE\n");
        std::vector<Body> bodies = {ball("fixed", 0.005, Kind::mesh), ball("free", 0.005, Kind::mesh)};
        bodies[0].fixed = true;
        bodies[1].position = Vec3(0.001, 0.0005, 0.0105);
        rb->setup(bodies);
        std::vector<Wrench> w(2);
        double maxSpeed = 0;
        const double F = 50;
        double work = 0; // of the central force, = -change of its potential F |r|
        const double r0 = bodies[1].position.norm();
        for (int n = 0; n < 2000; ++n) {
            w[1].force = -F * bodies[1].position.normalized();
            rb->step(bodies, w, 1e-4);
            maxSpeed = std::max(maxSpeed, bodies[1].velocity.norm());
            const double E = 0.5 * bodies[1].mass() * bodies[1].velocity.squaredNorm() +
                             0.5 * bodies[1].angularVelocity.dot(bodies[1].inertiaWorld() * bodies[1].angularVelocity) +
                             F * (bodies[1].position.norm() - r0);
            work = std::max(work, E);
        }
        const Body& b = bodies[1];
        INFO("centre distance " << b.position.norm() << ", speed " << b.velocity.norm() << ", max speed " << maxSpeed
                                << ", energy rise " << work << "\n"
                                << rb->describe());
        // In contact: the centre distance lies between twice the inscribed
        // radius (the nearest face plane; less the 1 um layer) and twice the
        // vertex radius, wherever the facets nest (measured 9.968 mm).
        double inscribed = 1;
        for (int t = 0; t < b.shape->mesh.nTriangles(); ++t)
            inscribed = std::min(inscribed, b.shape->mesh.normal(t).dot(b.shape->mesh.corner(t, 0)));
        CHECK(b.position.norm() < 0.01);
        CHECK(b.position.norm() > 2 * inscribed - 1e-6);
        CHECK(b.velocity.norm() < 1e-5);
        // Never faster than the impact, sqrt(2 F/m gap) (3.8 m/s), + 5%.
        CHECK(maxSpeed < 1.05 * std::sqrt(2 * F / b.mass() * (r0 - 0.01)));
        CHECK(work < 1e-9);
    }
    SECTION("a cube given as a mesh lands tilted and shifted on another") {
        // The scene that throws the upper cube away without the correction
        // ([odeArtefact] below).
        const Stack s = stack("type: ODE\ngravity: [0, 0, -9.81]\ncollisionShapes: mesh\n",
                              cube("top", 0.01, Kind::mesh), 1e-4, 0.2, 0.002);
        INFO("penetration " << s.penetration << ", speed " << s.speed << ", max speed " << s.run.maxSpeed
                            << ", lateral " << s.lateral);
        CHECK(s.run.maxSpeed < 4 * s.impactSpeed);
        CHECK(s.lateral < 3e-3);
        CHECK(s.speed < 1e-5);
        // As for the boxes: resting inside the 1 um layer.
        CHECK(s.penetration > 0);
        CHECK(s.penetration < 1.5e-6);
        CHECK(s.run.energyRise < 1e-9);
    }
    SECTION("non-convex: an L lands on a cube, a cube is pressed into the L's corner") {
        mag::ShapeKind k;
        k.kind = Kind::mesh;
        const Stack onCube = stack("type: ODE\ngravity: [0, 0, -9.81]\ncollisionShapes: mesh\n",
                                   makeBody("L", makeL(0.004, 0.01), k), 1e-4, 0.3, 0.003);
        INFO("L on cube: penetration " << onCube.penetration << ", speed " << onCube.speed);
        CHECK(onCube.speed < 1e-5);
        CHECK(onCube.penetration > 0);
        CHECK(onCube.penetration < 1.5e-6);
        CHECK(onCube.run.energyRise < 1e-9);

        // A 6 mm cube pushed by 50 N diagonally into the inner corner of a
        // fixed L: two walls, two contact normals, on one pair of meshes.
        auto rb = backend("type: ODE\ngravity: [0, 0, -9.81]\ncollisionShapes: mesh\n");
        std::vector<Body> bodies = {makeBody("L", makeL(0.01, 0.01), k), cube("cube", 0.006, Kind::mesh)};
        bodies[0].fixed = true;
        const Vec3 corner = bodies[0].toWorld(bodies[0].shape->mesh.vertices[3]) + Vec3(0, 0, 0.005);
        bodies[1].position = corner + Vec3(0.0035, 0.0035, 0);
        rb->setup(bodies);
        const Vec3 F = -50 * Vec3(1, 1, 0).normalized();
        const Run run = simulate(*rb, bodies, Vec3(0, 0, -9.81), F, 1e-4, 2000);
        const Vec3 rest = bodies[1].position - corner;
        INFO("cube in corner at " << rest.transpose() << ", speed " << bodies[1].velocity.norm() << ", energy rise "
                                  << run.energyRise);
        // Against both walls (3 mm from each, within the 1 um layer), held by
        // friction against gravity (mu 50 N >> 16 mN), at rest.
        CHECK(std::abs(rest.x() - 0.003) < 1.5e-6);
        CHECK(std::abs(rest.y() - 0.003) < 1.5e-6);
        CHECK(std::abs(rest.z()) < 1e-4);
        CHECK(bodies[1].velocity.norm() < 1e-5);
        CHECK(run.energyRise < 1e-9);
    }
}

TEST_CASE("ODE: runs are bit-identical, also with two backends interleaved", "[odeBackend]") {
    const std::string stepper = GENERATE(std::string("step"), std::string("quickStep"));
    const std::string yaml = "type: ODE\ngravity: [0, 0, -9.81]\nground: {height: 0}\nstepper: " + stepper +
                             "\nseed: 7\ncollisionShapes: mesh\n";
    auto scene = [] {
        std::vector<Body> bodies = {cube("a", 0.01, Kind::mesh), ball("b", 0.005, Kind::mesh), cube("c", 0.01),
                                    rod("d", 0.004, 0.02)};
        for (std::size_t i = 0; i < bodies.size(); ++i) {
            bodies[i].position = Vec3(0.003 * i, 0.002 * (i % 2), 0.012 * (i + 1));
            bodies[i].orientation = Quat(Eigen::AngleAxisd(0.4 * i, Vec3(1, 1, 0.5).normalized()));
        }
        return bodies;
    };
    std::vector<Wrench> w(4);
    w[1].force = Vec3(0.05, 0, -0.5);
    std::vector<Body> one = scene(), two = scene(), three = scene();
    auto a = backend(yaml), b = backend(yaml);
    a->setup(one);
    for (int n = 0; n < 300; ++n) a->step(one, w, 1e-3);
    // Two backends in one process, stepped alternately.
    a = backend(yaml);
    a->setup(two);
    b->setup(three);
    for (int n = 0; n < 300; ++n) a->step(two, w, 1e-3), b->step(three, w, 1e-3);
    for (std::size_t i = 0; i < one.size(); ++i) {
        INFO(stepper << " body " << one[i].name);
        CHECK(one[i].position == two[i].position);
        CHECK(one[i].orientation.coeffs() == two[i].orientation.coeffs());
        CHECK(one[i].velocity == two[i].velocity);
        CHECK(one[i].angularVelocity == two[i].angularVelocity);
        CHECK(two[i].position == three[i].position);
        CHECK(two[i].angularVelocity == three[i].angularVelocity);
    }
    // Something happened: the bodies fell and collided.
    CHECK(one[3].position.z() < 0.04);
}

TEST_CASE("ODE: a state changed between steps is taken over", "[odeBackend]") {
    auto rb = backend("type: ODE\nmaxTravel: 0\n");
    std::vector<Body> bodies = {cube("c", 0.01)};
    rb->setup(bodies);
    std::vector<Wrench> w(1);
    rb->step(bodies, w, 1e-3);
    bodies[0].position = Vec3(1, 2, 3), bodies[0].velocity = Vec3(1, 0, 0); // as a restart would
    rb->setState(bodies);
    rb->step(bodies, w, 1e-3);
    CHECK((bodies[0].position - Vec3(1.001, 2, 3)).norm() < 1e-15); // one 1 mm step: round-off
    CHECK(bodies[0].velocity == Vec3(1, 0, 0));
}

TEST_CASE("ODE: collision shapes follow the body kinds", "[odeBackend]") {
    std::vector<Body> bodies = {cube("box", 0.01), cube("meshBox", 0.01, Kind::mesh), ball("ball", 0.005, Kind::sphere),
                                ball("ico", 0.005, Kind::mesh), rod("rod", 0.003, 0.01)};
    // A box mesh turned in its body frame is still recognised as a box.
    mag::SurfaceMesh turned = mag::makeBox(Vec3(0.01, 0.02, 0.005));
    mag::rotate(turned, Quat(Eigen::AngleAxisd(0.5, Vec3(1, 2, 3).normalized())));
    mag::ShapeKind k;
    bodies.push_back(makeBody("turnedBox", turned, k));
    for (std::size_t i = 0; i < bodies.size(); ++i) bodies[i].position = Vec3(0.05 * i, 0, 0);
    auto rb = backend("type: ODE\n");
    rb->setup(bodies);
    CHECK_THAT(rb->describe(), Contains("collision shapes: 3 box, 1 cylinder, 1 sphere, 1 trimesh"));
    auto all = backend("type: ODE\ncollisionShapes: mesh\n");
    all->setup(bodies);
    CHECK_THAT(all->describe(), Contains("collision shapes: 6 trimesh"));

    // The turned box rests flat on the ground at its half height along z'.
    std::vector<Body> one = {bodies.back()};
    one[0].position = Vec3(0, 0, 0.02);
    one[0].orientation = Quat(Eigen::AngleAxisd(-0.5, Vec3(1, 2, 3).normalized()));
    auto g = backend("type: ODE\ngravity: [0, 0, -9.81]\nground: {}\n");
    g->setup(one);
    simulate(*g, one, Vec3(0, 0, -9.81), Vec3::Zero(), 1e-3, 500);
    CHECK(std::abs(one[0].position.z() - (0.0025 - 1e-6)) < 1e-7); // the layer deep, as in the drop test
}

TEST_CASE("ODE: bad dictionaries are clear errors", "[odeBackend][badInput]") {
    CHECK_THROWS_WITH(backend("type: ODE\ncontact: {frictoin: 0.5}\n"),
                      Contains("rigidBody.yaml:2") && Contains("contact: unknown key 'frictoin'") &&
                          Contains("did you mean 'friction'"));
    CHECK_THROWS_WITH(backend("type: ODE\ncontact: {restitution: 1.5}\n"), Contains("restitution must be in [0, 1]"));
    CHECK_THROWS_WITH(backend("type: ODE\ncontact: {erp: 0}\n"), Contains("erp must be in (0, 1]"));
    CHECK_THROWS_WITH(backend("type: ODE\ncontact: {rollingFriction: -1e-5}\n"),
                      Contains("rollingFriction") && Contains("must be >= 0 (m: torque per normal force)"));
    CHECK_THROWS_WITH(backend("type: ODE\ncontact: {maxContacts: 0}\n"), Contains("maxContacts must be 1..64"));
    CHECK_THROWS_WITH(backend("type: ODE\nground: {hieght: 0}\n"), Contains("unknown key 'hieght'"));
    CHECK_THROWS_WITH(backend("type: ODE\nground: 0\n"), Contains("expected a mapping"));
    CHECK_THROWS_WITH(backend("type: ODE\nstepper: dantzig\n"), Contains("valid values: step, quickStep"));
    CHECK_THROWS_WITH(backend("type: ODE\niterations: 50\n"), Contains("stepper: quickStep only"));
    CHECK_THROWS_WITH(backend("type: ODE\ncollisionShapes: convex\n"), Contains("valid values: auto, trimesh, mesh"));
    CHECK_THROWS_WITH(backend("type: ODE\nsubsteps: 2\n"), Contains("did you mean 'subSteps'"));
}

// Not run by default: what the contact correction is for. ODE 0.16's own
// trimesh-trimesh contacts for the tilted, shifted cube of the test above.
TEST_CASE("ODE: trimesh-trimesh without the correction", "[.][odeArtefact]") {
    for (const char* on : {"true", "false"}) {
        const Stack s = stack(std::string("type: ODE\ngravity: [0, 0, -9.81]\ncollisionShapes: mesh\n"
                                          "contact: {meshCorrection: ") + on + "}\n",
                              cube("top", 0.01, Kind::mesh), 1e-4, 0.2, 0.002);
        std::printf("meshCorrection %-5s: max speed %.3g m/s (impact %.3g), lateral %.3g m, final speed %.3g m/s\n", on,
                    s.run.maxSpeed, s.impactSpeed, s.lateral, s.speed);
    }
}

// Not run by default: milliseconds per step for a few bodies (magFoam's
// solver adds the magnetic part). A heap of cubes or icospheres on the
// ground, each pulled down by 5 N, deltaT 1 ms, 0.3 s.
TEST_CASE("ODE: time per step", "[.][bench]") {
    for (const char* stepper : {"step", "quickStep"})
        for (const char* shapes : {"auto", "mesh"})
            for (int n : {2, 8, 27}) {
                auto rb = backend(std::string("type: ODE\ngravity: [0, 0, -9.81]\nground: {}\ncollisionShapes: ") + shapes +
                                  "\nstepper: " + stepper + "\n");
                std::vector<Body> bodies;
                for (int i = 0; i < n; ++i) {
                    bodies.push_back(i % 2 ? ball("b", 0.005, Kind::mesh) : cube("c", 0.01));
                    bodies.back().position = Vec3(0.012 * (i % 3), 0.012 * ((i / 3) % 3), 0.006 + 0.012 * (i / 9));
                }
                rb->setup(bodies);
                const Run run = simulate(*rb, bodies, Vec3(0, 0, -9.81), Vec3(0, 0, -5), 1e-3, 300);
                std::printf("%-9s %-4s %2d bodies (cubes and icospheres): %.3f ms per step\n", stepper, shapes, n,
                            1e3 * run.seconds);
                std::printf("    %s\n", rb->describe().c_str());
            }
}
