// The template field evaluator (PointDipoleField.cpp): selected by name from the
// plugin manifest, the field of a dipole on its axis, the force between two
// coaxial dipoles, and Newton's third law.
#include <magFoam/Body.hpp>
#include <magFoam/FieldEvaluator.hpp>
#include <magFoam/MeshPrimitives.hpp>
#include <magFoam/ShapeFactory.hpp>

#include <catch2/catch.hpp>

#include <cmath>

using Catch::Matchers::Contains;

namespace {

// A 1 cm cube of remanence 1 T along +z at `position`.
mag::Body cube(const std::string& name, const mag::Vec3& position) {
    mag::ShapeKind kind;
    kind.kind = mag::ShapeKind::Kind::box;
    kind.size = mag::Vec3::Constant(0.01);
    mag::Body b;
    b.name = name;
    b.shape = mag::makeShape(mag::makeBox(kind.size), kind);
    b.material.Br = 1.0;
    b.material.density = 7500;
    b.magnetizationBody = mag::Vec3(0, 0, 1.0 / mag::mu0);
    b.position = position;
    return b;
}

} // namespace

TEST_CASE("pointDipole is selectable by name", "[pointDipole]") {
    const auto field = mag::FieldEvaluator::New(mag::Dict::fromString("type: pointDipole\n", "magSchemes.yaml"));
    CHECK_THAT(field->describe(), Contains("pointDipole"));
}

TEST_CASE("pointDipole: field on the axis and force between coaxial dipoles", "[pointDipole]") {
    const auto field = mag::FieldEvaluator::New(mag::Dict::fromString("type: pointDipole\n", "magSchemes.yaml"));
    const mag::Body a = cube("a", mag::Vec3::Zero()), b = cube("b", mag::Vec3(0, 0, 0.02));
    const double m = a.magneticMoment().norm(), z = 0.02;

    // On the axis: B = mu0 2 m / (4 pi z^3).
    const mag::Vec3 p(0, 0, z);
    mag::Vec3 B;
    field->evaluate(a, std::span<const mag::Vec3>(&p, 1), std::span<mag::Vec3>(&B, 1));
    CHECK(B.z() == Approx(mag::mu0 * 2 * m / (4 * mag::pi * z * z * z)).epsilon(1e-12));
    CHECK(std::abs(B.x()) + std::abs(B.y()) < 1e-15);

    // Attraction: F = 3 mu0 m^2 / (2 pi z^4), no torque on aligned moments.
    const mag::Wrench onB = field->interaction(a, b), onA = field->interaction(b, a);
    CHECK(onB.force.z() == Approx(-3 * mag::mu0 * m * m / (2 * mag::pi * std::pow(z, 4))).epsilon(1e-12));
    CHECK((onA.force + onB.force).norm() < 1e-12 * onB.force.norm());
    CHECK(onB.torque.norm() < 1e-15);
}
