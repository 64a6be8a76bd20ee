// The adaptive step's proposal (solvers/magFoam/StepAudit.hpp,
// docs/dynamics.md#adaptive-time-step) on a thin plate, where the old bounds
// (spin x bounding radius, torque / smallest inertia) were up to 4x too short.
// References are closed forms of a box: its corners' distance from an axis,
// its principal inertias m (b^2 + c^2) / 12.
#include "bodyFixture.hpp"

#include <StepAudit.hpp>
#include <magFoam/Dictionary.hpp>

#include <catch2/catch.hpp>

#include <cmath>

using namespace mag;

namespace {

// A paperclip-like plate, 33 x 8 x 0.9 mm, magnetized along its length (x).
const Vec3 kSize(0.033, 0.008, 0.0009);

Body plate(const Quat& orientation = Quat::Identity()) {
    return magtest::magnet("plate", magtest::boxShape(kSize), Vec3::Zero(), Vec3::UnitX(), orientation);
}

solver::StepAudit audit(const Body& b) {
    return solver::StepAudit({b}, AuditSettings{}, 0.0, Vec3::Zero());
}

// The proposal aims at half the audit's travel (0.1) of the smallest edge.
constexpr double kTravel = 0.5 * 0.1 * 0.0009;

double principal(const Body& b, double e1, double e2) { return b.mass() * (e1 * e1 + e2 * e2) / 12.0; }

} // namespace

TEST_CASE("step proposal: a spin moves the surface by its distance from the spin axis", "[stepProposal]") {
    // Turned 30 degrees about z, so that the body and world frames differ.
    const Quat q = magtest::axisAngle(30, Vec3::UnitZ());
    Body b = plate(q);
    const double w = 50.0; // rad/s
    SECTION("about the long axis: the corners lie sqrt(4^2 + 0.45^2) mm from it") {
        b.angularVelocity = q * Vec3(w, 0, 0);
        const auto p = audit(b).stableDeltaT({b}, {Wrench{}});
        const double r = std::hypot(kSize.y(), kSize.z()) / 2;
        CHECK(p.deltaT == Approx(kTravel / (w * r)).epsilon(1e-12));
        CHECK(p.limit == "turn");
        CHECK(p.body == 0);
        // The bounding radius would have made it 4x shorter.
        CHECK(p.deltaT > 3.5 * kTravel / (w * b.shape->boundingRadius));
    }
    SECTION("about the normal: sqrt(16.5^2 + 4^2) mm") {
        b.angularVelocity = q * Vec3(0, 0, w);
        const auto p = audit(b).stableDeltaT({b}, {Wrench{}});
        CHECK(p.deltaT == Approx(kTravel / (w * std::hypot(kSize.x(), kSize.y()) / 2)).epsilon(1e-12));
    }
}

TEST_CASE("step proposal: a torque from rest turns the plate by I^-1 tau", "[stepProposal]") {
    const Quat q = magtest::axisAngle(-70, Vec3(1, 2, 3));
    Body b = plate(q);
    Wrench wr;
    SECTION("about the normal (largest inertia)") {
        const double tau = 2e-4; // N m
        wr.torque = q * Vec3(0, 0, tau);
        const double a = tau / principal(b, kSize.x(), kSize.y()) * std::hypot(kSize.x(), kSize.y()) / 2;
        // From rest, a dt^2 = travel.
        const auto p = audit(b).stableDeltaT({b}, {wr});
        CHECK(p.deltaT == Approx(std::sqrt(kTravel / a)).epsilon(1e-9));
        CHECK(p.limit == "turn");
        // tau / I_min would have made it sqrt(I_zz / I_xx) = 4.2x shorter.
        const double old = std::sqrt(kTravel / (tau / principal(b, kSize.y(), kSize.z()) * b.shape->boundingRadius));
        CHECK(p.deltaT == Approx(std::sqrt(principal(b, kSize.x(), kSize.y()) / principal(b, kSize.y(), kSize.z())) * old).epsilon(1e-3));
    }
    SECTION("about the long axis (smallest inertia)") {
        const double tau = 1e-6;
        wr.torque = q * Vec3(tau, 0, 0);
        const double a = tau / principal(b, kSize.y(), kSize.z()) * std::hypot(kSize.y(), kSize.z()) / 2;
        const auto p = audit(b).stableDeltaT({b}, {wr});
        CHECK(p.deltaT == Approx(std::sqrt(kTravel / a)).epsilon(1e-9));
    }
}

TEST_CASE("step proposal: tilt stiffness |U| about the axes normal to the moment", "[stepProposal]") {
    const Quat q = magtest::axisAngle(40, Vec3(0, 1, 1));
    Body b = plate(q);
    Wrench wr;
    wr.energy = -3e-3; // J: the moment aligned in a field, U = -m B
    const double twoPi = 2 * std::acos(-1.0);
    // Moment along x: the tilt axes are y and z; y has the smaller inertia
    // (33 x 0.9 mm against 33 x 8 mm), so the fastest swing is about y.
    const double omega = std::sqrt(3e-3 / principal(b, kSize.x(), kSize.z()));
    auto p = audit(b).stableDeltaT({b}, {wr});
    CHECK(p.deltaT == Approx(twoPi / omega / 20).epsilon(1e-9));
    CHECK(p.limit == "tilt stiffness");
    // Moment along y: the tilt axes are x (smallest inertia) and z.
    b.magnetizationBody = Vec3::UnitY() / mu0;
    p = audit(b).stableDeltaT({b}, {wr});
    CHECK(p.deltaT == Approx(twoPi / std::sqrt(3e-3 / principal(b, kSize.y(), kSize.z())) / 20).epsilon(1e-9));
    // Implicit tilt (magneticStiffness: implicit): the term is left out.
    p = audit(b).stableDeltaT({b}, {wr}, true);
    CHECK_FALSE(std::isfinite(p.deltaT));
}

TEST_CASE("step proposal: free flight and a pull name travel and force stiffness", "[stepProposal]") {
    Body b = plate();
    b.velocity = Vec3(0.3, 0, 0);
    auto p = audit(b).stableDeltaT({b}, {Wrench{}});
    CHECK(p.deltaT == Approx(kTravel / 0.3).epsilon(1e-12));
    CHECK(p.limit == "travel");
    Wrench wr;
    wr.force = Vec3(0, 0, 5.0); // N: omega^2 = F / (m size) = 5 / (m 0.9 mm)
    b.velocity = Vec3::Zero();
    p = audit(b).stableDeltaT({b}, {wr});
    const double travelStep = std::sqrt(kTravel / (5.0 / b.mass()));
    const double stiffStep = 2 * std::acos(-1.0) / std::sqrt(5.0 / (b.mass() * 0.0009)) / 20;
    CHECK(p.deltaT == Approx(std::min(travelStep, stiffStep)).epsilon(1e-9));
    CHECK(p.limit == (travelStep < stiffStep ? "travel" : "force stiffness"));
    // Fixed bodies propose nothing.
    b.fixed = true;
    CHECK_FALSE(std::isfinite(audit(b).stableDeltaT({b}, {wr}).deltaT));
}

TEST_CASE("step proposal: a body at rest that contacts hold moves by its net acceleration of the last step", "[stepProposal]") {
    // The plate pressed onto something by 0.5 N and turned about its long
    // axis by 0.01 N m, both of which the contact balances: over the last
    // step (0.1 ms) it did not move. The proposal then takes that net
    // acceleration (zero), not the magnetic wrench's, and only the force
    // stiffness is left.
    const Quat q = magtest::axisAngle(-70, Vec3(1, 2, 3));
    const Body b = plate(q);
    Wrench wr;
    wr.force = q * Vec3(0, 0, -0.5);
    wr.torque = q * Vec3(0.01, 0, 0);
    solver::StepAudit a = audit(b);
    const auto before = a.stableDeltaT({b}, {wr});
    CHECK(before.limit == "turn"); // I^-1 tau from rest: ~0.1 ms
    std::vector<BodyState> start(1, b);
    a.check(1, 1e-4, 1e-4, start, {b}, {wr}, 0.0);
    const auto held = a.stableDeltaT({b}, {wr});
    const double stiffStep = 2 * std::acos(-1.0) / std::sqrt(0.5 / (b.mass() * 0.0009)) / 20;
    CHECK(held.limit == "force stiffness");
    CHECK(held.deltaT == Approx(stiffStep).epsilon(1e-9));
    CHECK(held.deltaT > 3 * before.deltaT);

    // At rest but accelerated by less than the wrench says (a contact took
    // part of it: 225 m/s^2 over the last 1 us against F / m = 281), the
    // proposal takes the net acceleration.
    wr.torque = Vec3::Zero();
    Body resting = b;
    resting.velocity = q * Vec3(0, 0, -2.25e-4);
    solver::StepAudit c = audit(b);
    c.check(1, 1e-6, 1e-6, start, {resting}, {wr}, 0.0);
    const auto p = c.stableDeltaT({resting}, {wr});
    const double d = kTravel, v = 2.25e-4;
    auto travelStep = [&](double acc) { return 2 * d / (v + std::sqrt(v * v + 4 * acc * d)); };
    CHECK(p.limit == "travel");
    CHECK(p.deltaT == Approx(travelStep(225.0)).epsilon(1e-6));
    CHECK(p.deltaT > 1.1 * travelStep(0.5 / b.mass()));

    // A moving body (1 cm/s) keeps the magnetic acceleration: two clips
    // pressed together while they moved took a longer step and were blown
    // apart (Fig. 8).
    Body moving = b;
    moving.velocity = q * Vec3(0, 0, -0.01);
    std::vector<BodyState> slower(1, b);
    slower[0].velocity = q * Vec3(0, 0, -0.01 + 2.25e-4);
    solver::StepAudit m = audit(b);
    m.check(1, 1e-6, 1e-6, slower, {moving}, {wr}, 0.0);
    const double vm = 0.01, am = 0.5 / b.mass();
    CHECK(m.stableDeltaT({moving}, {wr}).deltaT == Approx(2 * d / (vm + std::sqrt(vm * vm + 4 * am * d))).epsilon(1e-9));

    // It is restart state: written as timeStep.yaml lines, read back, the
    // same proposal to the bit.
    const std::string text = c.netAccelerationState({resting});
    CHECK(text.find("netAcceleration:\n  plate: [") != std::string::npos);
    const Dict d2 = Dict::fromString(text, "timeStep.yaml");
    const auto v2 = d2.sub("netAcceleration").get<std::vector<double>>("plate");
    REQUIRE(v2.size() == 6);
    solver::StepAudit restarted = audit(b);
    restarted.restoreNetAcceleration({resting}, {{"plate", {v2[0], v2[1], v2[2], v2[3], v2[4], v2[5]}}});
    CHECK(restarted.stableDeltaT({resting}, {wr}).deltaT == p.deltaT);
}

TEST_CASE("audit: the total's rise above its lowest before, which the start does not see", "[stepProposal]") {
    // A magnet held still (no kinetic energy, no gravity): the total is the
    // magnetic energy handed to check(). It falls from -1 J to -3 J, rises to
    // -2.5 J (never above the start) and falls again to -4 J: 0.5 J regained
    // (the last 0.1 J above -4 J is less).
    const Body b = plate();
    solver::StepAudit a = audit(b);
    const std::vector<BodyState> still(1, b);
    const double energies[] = {-1.0, -3.0, -2.5, -4.0, -3.9};
    long step = 0;
    for (double u : energies) {
        ++step;
        a.check(step, 1e-4 * static_cast<double>(step), 1e-4, still, {b}, {Wrench{}}, u);
    }
    CHECK(a.energyRecovery() == Approx(0.5).epsilon(1e-12));
    CHECK(a.warnings() == 0); // reported in the summary only
}
