// The linearly implicit magnetic torque (controlDict magneticStiffness:
// implicit, solvers/magFoam/ImplicitTorque.hpp, docs/dynamics.md#large-steps).
// Reference: a magnet in a uniform field, a rigid pendulum with the closed
// forms torque m x B and energy -m . B, integrated here with the backends'
// semi-implicit Euler; and the dropMagnet scene run by magFoam at a step 20 x
// above the explicit limit, where the explicit torque gains energy.
#include "bodyFixture.hpp"
#include "caseFixture.hpp"

#include <ImplicitTorque.hpp>
#include <magFoam/RigidBodyBackend.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <regex>

using namespace mag;

namespace {

// A 6 mm N42-like cube (|M| = 1 T / mu0 along z) turned by `degrees` about x.
Body swingingCube(double degrees) {
    return magtest::magnet("cube", magtest::boxShape(Vec3::Constant(0.006)), Vec3::Zero(), Vec3::UnitZ(),
                           magtest::axisAngle(degrees, Vec3::UnitX()));
}

// The cube's wrench in a uniform field B: torque m x B, energy -m . B.
Wrench uniformFieldWrench(const Body& b, const Vec3& B) {
    Wrench w;
    w.torque = b.magneticMoment().cross(B);
    w.energy = -b.magneticMoment().dot(B);
    return w;
}

struct Swing {
    double highestRise = 0; // highest total energy above the start, J
    double lastEnergy = 0, startEnergy = 0;
    double angle = 0;       // the tilt at the end, rad
};

// The free backend (semi-implicit Euler: spin first, then the turn by the new
// spin) for `steps` steps of dt, with the torque explicit or implicit.
Swing swing(double degrees, const Vec3& B, double dt, int steps, bool implicit, int subSteps = 1) {
    std::vector<Body> bodies{swingingCube(degrees)};
    Body& b = bodies[0];
    auto rb = RigidBodyBackend::New(Dict::fromString("type: free\ngravity: [0, 0, 0]\nintegrator: symplecticEuler\n"
                                                     "subSteps: " + std::to_string(subSteps) + "\n",
                                                     "constant/rigidBody.yaml"));
    rb->setup(bodies);
    auto energy = [&] {
        return 0.5 * b.angularVelocity.dot(b.inertiaWorld() * b.angularVelocity) - b.magneticMoment().dot(B);
    };
    Swing s;
    s.startEnergy = energy();
    for (int k = 0; k < steps; ++k) {
        const std::vector<Wrench> w{uniformFieldWrench(b, B)};
        if (implicit) REQUIRE(rb->setTiltStiffness(solver::tiltStiffnesses(bodies, w)));
        rb->step(bodies, w, dt);
        s.highestRise = std::max(s.highestRise, energy() - s.startEnergy);
    }
    s.lastEnergy = energy();
    s.angle = std::acos(std::clamp(b.magnetization().normalized().dot(B.normalized()), -1.0, 1.0));
    return s;
}

} // namespace

TEST_CASE("implicit torque: the tilt stiffness of an aligned moment is -U across it, none along it", "[implicit]") {
    Body b = swingingCube(0);
    Wrench w;
    w.energy = -2e-3;
    w.ownEnergy = -1e-3;
    const Mat3 S = solver::tiltStiffness(b, w);
    // S = (m . B)(1 - m^ m^T) with m . B = -U = 3e-3 J: exact to rounding.
    CHECK(S(0, 0) == Approx(3e-3).epsilon(1e-14));
    CHECK(S(1, 1) == Approx(3e-3).epsilon(1e-14));
    CHECK(std::abs(S(2, 2)) < 1e-18);
    CHECK(std::abs(S(0, 1)) < 1e-18);
    // An anti-aligned (unstable) moment gets no implicit part.
    w.energy = 2e-3, w.ownEnergy = 0;
    CHECK(solver::tiltStiffness(b, w).isZero(0.0));
}

TEST_CASE("implicit torque: a magnet swinging in a uniform field, stable and consistent", "[implicit]") {
    // 6 mm cube, |m| = 0.172 A m^2, in 0.5 T along z: omega = sqrt(|m| B / I)
    // = 1.4e3 rad/s, the explicit step's limit omega dt < 2 at 1.4 ms.
    const Vec3 B(0, 0, 0.5);
    const Body cube = swingingCube(0);
    const double I = cube.inertiaWorld()(0, 0);
    const double omega = std::sqrt(cube.magneticMoment().norm() * B.norm() / I);

    SECTION("at omega dt = 5 the explicit torque gains energy without bound, the implicit one never") {
        const double dt = 5.0 / omega;
        const Swing ex = swing(20, B, dt, 50, false), im = swing(20, B, dt, 50, true);
        // Explicit: the swing grows until the magnet tumbles (the start is
        // 20 degrees, m B (1 - cos 20 deg) = 5.2e-3 J above the aligned state).
        CHECK(ex.highestRise > 1e-3);
        // Implicit: backward Euler of the swing; the total energy only falls
        // (rounding of the 5.2e-3 J: 1e-15 J) and the swing dies out.
        CHECK(im.highestRise < 1e-15);
        CHECK(im.lastEnergy < im.startEnergy);
        CHECK(im.angle < 1e-6);
    }

    SECTION("in sub-steps the torque stays linearised about the step's start") {
        // 10 sub-steps of the same step: each sees the step's torque less S
        // times the turn since the step began. Without that term each sub-step
        // would restart from the step's torque, explicit over the step, and
        // the swing would grow as in the explicit case above.
        const double dt = 5.0 / omega;
        const Swing im = swing(20, B, dt, 50, true, 10);
        CHECK(im.highestRise < 1e-15);
        CHECK(im.angle < 1e-6);
    }

    SECTION("small steps: the implicit swing converges to the explicit one at first order") {
        // Half a period from 10 degrees, where the swing is at its far end;
        // the reference is the explicit step at omega dt = 1e-4 (second order:
        // its error ~1e-9 rad, far below). Backward Euler damps the swing by
        // ~(pi / 2) omega dt in half a period: first order.
        const double T = 0.5 * 2 * pi / omega;
        const double reference = swing(10, B, T / 31416, 31416, false).angle;
        const double e1 = std::abs(swing(10, B, T / 200, 200, true).angle - reference);
        const double e2 = std::abs(swing(10, B, T / 400, 400, true).angle - reference);
        const double e4 = std::abs(swing(10, B, T / 800, 800, true).angle - reference);
        // First order: halving dt halves the error (ratios 2 +- 0.2 allow the
        // second-order terms at omega dt = 0.016 - 0.004).
        CHECK(e1 / e2 == Approx(2.0).margin(0.2));
        CHECK(e2 / e4 == Approx(2.0).margin(0.2));
        CHECK(e4 < 0.01 * 10 * pi / 180); // within 1 % of the swing at 800 steps per half period
    }
}

namespace {

// dropMagnet's scene (a 6 mm cube dropped tilted onto a fixed disc magnet) at
// fixed steps of dt for 0.3 s, without sleeping; the audit's summary lines.
std::string dropAt(magtest::TempCase& c, const std::string& dt, const std::string& stiffness) {
    c.write("system/controlDict.yaml", "endTime: 0.3\ndeltaT: " + dt + "\nwriteInterval: 0.05\nmagneticStiffness: " +
                                           stiffness + "\n");
    c.write("system/magSchemes.yaml", "field: {type: MBM, quadrature: {type: gauss, n: 6}, overlap: amperian}\n");
    c.dropMagnet();
    REQUIRE(magtest::runApp(c.dir(), "magFoam", "log") == 0);
    return magtest::slurp(c.dir() / "log");
}

double riseAboveStart(const std::string& log) {
    std::smatch m;
    REQUIRE(std::regex_search(log, m, std::regex("at most ([-+0-9.e]+) J above the start")));
    return std::stod(m[1]);
}

bool atRest(const std::string& log) { return log.find("1 of 1 dynamic bodies at rest at the end") != std::string::npos; }

} // namespace

TEST_CASE("implicit torque: a magnet dropped on a disc at 2 ms steps comes to rest without energy gain", "[implicit]") {
    // 2 ms is 20 x the step the explicit torque needs here (omega ~ 2e3 rad/s
    // on the disc, docs/dynamics.md#large-steps); ODE splits each step into
    // sub-steps (maxTravel), over which the torque stays linearised about the
    // step's start.
    magtest::TempCase ex, im;
    const std::string exLog = dropAt(ex, "0.002", "explicit"), imLog = dropAt(im, "0.002", "implicit");
    // Explicit: 0.27 J above the start (the fall releases ~0.04 J), still
    // bouncing at the end, and the audit warns about the energy.
    CHECK(riseAboveStart(exLog) > 0.01);
    CHECK_FALSE(atRest(exLog));
    CHECK(exLog.find("rose") != std::string::npos);
    // Implicit: never above its start at any step (backward Euler of the
    // swing only removes energy), at rest on the disc.
    CHECK(riseAboveStart(imLog) == 0.0);
    CHECK(atRest(imLog));
    CHECK(imLog.find("rose") == std::string::npos);
    CHECK(imLog.find("torque:     implicit") != std::string::npos);
    // On the disc, a face down: its centre 3 mm above the disc's top (z = 4 mm)
    // less ODE's 1 um surface layer; turned about z only.
    std::smatch m;
    const std::string state = magtest::slurp(im.dir() / "0.3/bodies.yaml");
    REQUIRE(std::regex_search(state, m, std::regex("name: cube\\n +position: \\[([^,]+), ([^,]+), ([^\\]]+)\\]\\n"
                                                   " +orientation: \\[([^,]+), ([^,]+), ([^,]+), ")));
    CHECK(std::hypot(std::stod(m[1]), std::stod(m[2])) < 0.01); // within the disc's radius
    CHECK(std::stod(m[3]) == Approx(0.007).margin(2e-6));
    CHECK(std::hypot(std::stod(m[5]), std::stod(m[6])) < 1e-4);
}
