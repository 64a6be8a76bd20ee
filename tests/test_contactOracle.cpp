// Tests of reference/oracles/contactQuadrature.hpp: the one-sided contact limit of the
// Akoun-Yonnet force, and the contact-exact charge-model wrench of two cuboids, against
// Akoun-Yonnet (separated and touching), the limits of separated neighbours, the
// brute-force charge quadrature, Newton's third law and closed-form 1D integrals.
#include <catch2/catch.hpp>

#include <cmath>
#include <iterator>
#include <vector>

#include "oracles/akounYonnet.hpp"
#include "oracles/chargeQuadrature.hpp"
#include "oracles/contactQuadrature.hpp"
#include "oracles/cuboidField.hpp"

using Eigen::Matrix3d;
using Eigen::Vector3d;
using oracle::Cuboid;
using oracle::mu0;
using oracle::pi;
using oracle::Wrench;

namespace {

double relDiff(const Vector3d& a, const Vector3d& b) { return (a - b).norm() / b.norm(); }

const double M1T = 1.0 / mu0;          // |M| of a 1 T magnet (A/m)
const double h = 0.005;                // half edge of a 1 cm cube
const Vector3d cm3(0.01, 0.01, 0.01);  // 1 cm cube, full size
const Cuboid source{Vector3d::Zero(), Vector3d(h, h, h), Vector3d(0, 0, M1T)};

Matrix3d rotation(double angle, const Vector3d& axis) {
    return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

// 1 cm cube, M = 1 T/mu0 along world z, centre c, rotation R (body -> world)
Cuboid cube(const Vector3d& c, const Matrix3d& R = Matrix3d::Identity()) {
    return Cuboid{c, Vector3d(h, h, h), Vector3d(0, 0, M1T), R};
}

// Parallel boxes (full sizes s1 at the origin, s2 at c2), polarizations J1, J2 (T) along z.
struct Pair {
    Vector3d s1, s2, c2;
    double J1, J2;
};
// 1 cm, 1 T cubes touching face to face: the contact placements both parallel tests use.
const Pair kTouchingCubes[] = {
    {cm3, cm3, Vector3d(0, 0, 0.01), 1, 1},          // coaxial
    {cm3, cm3, Vector3d(0.003, 0.002, 0.01), 1, 1},  // offset (3, 2) mm
    {cm3, cm3, Vector3d(0.005, 0.005, 0.01), 1, 1},  // offset (5, 5) mm
    {cm3, cm3, Vector3d(0.01, 0, 0.01), 1, 1},       // edge to edge
};

// the rotations of the reference table
const Matrix3d Rz30 = rotation(pi / 6, Vector3d::UnitZ());
const Matrix3d Rx45 = rotation(pi / 4, Vector3d::UnitX());
const Matrix3d Ry45 = rotation(pi / 4, Vector3d::UnitY());
// takes the body diagonal (1,1,1)/sqrt3 to -z (the minimal rotation, axis (-1,1,0))
const Matrix3d Rvertex = rotation(std::acos(-1 / std::sqrt(3.0)), Vector3d(-1, 1, 0));
const double zEdge = h + h * std::sqrt(2.0);    // Rx45 cube on its lower edge
const double zVertex = h + h * std::sqrt(3.0);  // Rvertex cube on its lowest vertex

// |dT| relative to |F| times the edge (1 cm)
double torqueDiff(const Wrench& a, const Wrench& b) {
    return (a.torque - b.torque).norm() / (b.force.norm() * 0.01);
}

// Touching wrench and the linear trend 2 W(g) - W(2 g) of the target moved by g along dir
// (relative differences of force and torque). Its own error is O(g^2) in these rotated
// cases; a g ln g term (where source and target edges coincide, e.g. the coaxial pair)
// would spoil it, and those cases are checked against Akoun-Yonnet instead.
struct Trend {
    Wrench touching;
    double dF = 0, dT = 0;
};
Trend linearTrend(const Cuboid& src, const Cuboid& tgt, const Vector3d& dir, double g,
                  double relTol = 1e-10) {
    auto at = [&](double gap) {
        Cuboid t = tgt;
        t.centre += gap * dir;
        return oracle::contactChargeWrench(src, t, tgt.centre, relTol);  // about a fixed point
    };
    Trend r;
    r.touching = at(0);
    const Wrench w1 = at(g), w2 = at(2 * g);
    Wrench lin;
    lin.force = 2 * w1.force - w2.force;
    lin.torque = 2 * w1.torque - w2.torque;
    r.dF = relDiff(lin.force, r.touching.force);
    r.dT = torqueDiff(lin, r.touching);
    return r;
}

}  // namespace

// ---------------------------------------------------------------------------------
// akounYonnetForceOneSided
// ---------------------------------------------------------------------------------

TEST_CASE("Akoun-Yonnet one-sided: coaxial contact value and the contact jump", "[oracle][AY][contact]") {
    const Vector3d c2(0, 0, 0.01);
    const Vector3d F1 = oracle::akounYonnetForceOneSided(cm3, Vector3d::Zero(), cm3, c2, 1, 1);
    const Vector3d Fm = oracle::akounYonnetForce(cm3, Vector3d::Zero(), cm3, c2, 1, 1);
    CAPTURE(F1.transpose(), Fm.transpose());
    // docs/physics.md#contact values quoted to 4 digits (measured -32.37863, mean +7.41013)
    CHECK(std::abs(F1.z() - -32.38) < 0.005);
    CHECK(std::abs(Fm.z() - 7.41) < 0.005);
    CHECK(F1.head<2>().norm() < 1e-12);
    // one-sided - mean = the normal force of the half jump J1/(2 mu0) of H on the
    // contact area: -J1 J2 A / (2 mu0) (rounding of the 64-term sums)
    CHECK(std::abs((F1 - Fm).z() - -1e-4 / (2 * mu0)) < 1e-12 * 40);
    // offset (3, 2) mm: contact area 7 mm x 8 mm
    const Vector3d c3(0.003, 0.002, 0.01);
    const Vector3d dF = oracle::akounYonnetForceOneSided(cm3, Vector3d::Zero(), cm3, c3, 1, 1) -
                        oracle::akounYonnetForce(cm3, Vector3d::Zero(), cm3, c3, 1, 1);
    CHECK(dF.head<2>().norm() < 1e-12);
    CHECK(std::abs(dF.z() - -0.007 * 0.008 / (2 * mu0)) < 1e-12 * 40);
    // a separated pair has no w = 0 term: identical to akounYonnetForce
    const Vector3d c4(0.003, 0.002, 0.0101);
    CHECK(oracle::akounYonnetForceOneSided(cm3, Vector3d::Zero(), cm3, c4, 1, 1) ==
          oracle::akounYonnetForce(cm3, Vector3d::Zero(), cm3, c4, 1, 1));
}

TEST_CASE("Akoun-Yonnet one-sided: the limit of small separations along the line of centres",
          "[oracle][AY][contact]") {
    std::vector<Pair> pairs(std::begin(kTouchingCubes), std::end(kTouchingCubes));
    pairs.insert(pairs.end(), {
        {cm3, cm3, Vector3d(0.002, -0.003, -0.01), 1, -0.7},   // below, opposite
        {cm3, cm3, Vector3d(0.01, 0.003, 0), 1, 1},            // side by side (d_z = 0)
        {cm3, Vector3d(0.01, 0.01, 0.02), Vector3d(0.01, 0.003, 0.005), 1, 1},  // shared top plane
        {Vector3d(0.02, 0.012, 0.006), Vector3d(0.012, 0.02, 0.006), Vector3d(0.004, -0.004, 0.006), 0.38, 0.38},
        {cm3, Vector3d(0.01, 0.01, 0.015), Vector3d(0.003, -0.004, 0.0125), 1, 1},  // rounding of 0.0125-0.0075
    });
    for (const Pair& pr : pairs) {
        const Vector3d F0 = oracle::akounYonnetForceOneSided(pr.s1, Vector3d::Zero(), pr.s2, pr.c2, pr.J1, pr.J2);
        // c2 + t c2 with t such that the gap along the line of centres is 1 nm / 10 nm
        auto diff = [&](double gap) {
            const Vector3d c = pr.c2 * (1 + gap / pr.c2.norm());
            return (oracle::akounYonnetForce(pr.s1, Vector3d::Zero(), pr.s2, c, pr.J1, pr.J2) - F0).norm();
        };
        const double d9 = diff(1e-9), d8 = diff(1e-8);
        CAPTURE(pr.c2.transpose(), F0.transpose(), d9, d8);
        // the separated force tends to F0: the difference is O(gap ln gap) or O(gap)
        // (measured d9/|F0| <= 2.6e-6, d8/d9 = 8.55 ... 10.0)
        CHECK(d9 < 1e-5 * F0.norm());
        CHECK(d8 / d9 > 7);
        CHECK(d8 / d9 < 12);
        // Newton's third law holds for the one-sided limits too (the same approach line)
        const Vector3d F21 = oracle::akounYonnetForceOneSided(pr.s2, pr.c2, pr.s1, Vector3d::Zero(), pr.J2, pr.J1);
        CHECK((F21 + F0).norm() < 1e-12 * F0.norm() + 1e-13);
    }
}

// ---------------------------------------------------------------------------------
// the graded adaptive Gauss-Kronrod integrator
// ---------------------------------------------------------------------------------

TEST_CASE("contact quadrature: the graded G7K15 rule on singular 1D integrals", "[oracle][contact]") {
    // the rule itself: weights sum to 2, K15 exact for degree 22 (x^22 -> 2/23)
    double sk = 0, sg = 0, k22 = 0;
    for (int j = 0; j < 8; ++j) {
        const double m = j == 7 ? 1 : 2;
        sk += m * oracle::detail::gkKronrodWeights[j];
        k22 += m * oracle::detail::gkKronrodWeights[j] * std::pow(oracle::detail::gkNodes[j], 22);
        if (j & 1) sg += m * oracle::detail::gkGaussWeights[j / 2];
    }
    CHECK(std::abs(sk - 2) < 1e-15);
    CHECK(std::abs(sg - 2) < 1e-15);
    CHECK(std::abs(k22 - 2.0 / 23) < 1e-15);

    using Int = oracle::detail::GradedIntegrator<1>;
    using V1 = Int::Vec;
    Int q;
    q.relTol = 1e-12;
    q.skip = 1e-14;
    // log and jump at the breakpoint 0: int_{-1}^{1} (ln|x| + [x > 0]) dx = -2 + 1
    const V1 r1 = q.integrate([](double x) { return V1(std::log(std::abs(x)) + (x > 0 ? 1.0 : 0.0)); },
                              {-1.0, 0.0, 1.0});
    CHECK(std::abs(r1[0] - -1.0) < 1e-12);
    // near singularity of width g at a breakpoint: int_{-1}^{2} ln(x^2 + g^2)/2 dx
    for (double g : {1e-3, 1e-6, 1e-9}) {
        auto F = [g](double x) { return 0.5 * x * std::log(x * x + g * g) - x + g * std::atan(x / g); };
        const V1 r = q.integrate([g](double x) { return V1(0.5 * std::log(x * x + g * g)); }, {-1.0, 0.0, 2.0});
        CAPTURE(g, r[0] - (F(2) - F(-1)), q.evaluations);
        CHECK(std::abs(r[0] - (F(2) - F(-1))) < 1e-12);
    }
}

// ---------------------------------------------------------------------------------
// contactChargeWrench: parallel cubes against Akoun-Yonnet
// ---------------------------------------------------------------------------------

TEST_CASE("contact quadrature: separated parallel cubes equal Akoun-Yonnet", "[oracle][contact][AY]") {
    for (const Vector3d& offset : {Vector3d(0, 0, 0), Vector3d(0.003, 0.002, 0)}) {
        for (double gap : {1e-3, 1e-4, 1e-5, 1e-6}) {
            const Vector3d c2 = offset + Vector3d(0, 0, 0.01 + gap);
            const Wrench w = oracle::contactChargeWrench(source, cube(c2), c2);
            const Vector3d F = oracle::akounYonnetForce(cm3, Vector3d::Zero(), cm3, c2, 1, 1);
            CAPTURE(c2.transpose(), F.transpose(), relDiff(w.force, F));
            CHECK(relDiff(w.force, F) < 1e-9);  // measured <= 8e-13 (offset, 1 um)
        }
    }
}

TEST_CASE("contact quadrature: touching parallel boxes equal the one-sided Akoun-Yonnet",
          "[oracle][contact][AY]") {
    std::vector<Pair> pairs(std::begin(kTouchingCubes), std::end(kTouchingCubes));
    pairs.insert(pairs.end(), {
        {cm3, Vector3d(0.02, 0.02, 0.01), Vector3d(0.001, 0.002, 0.01), 1, 1},  // source edges inside the target face
        {Vector3d(0.02, 0.012, 0.006), Vector3d(0.012, 0.02, 0.006), Vector3d(0.004, -0.004, -0.006), 0.38, -0.38},
    });
    for (const Pair& pr : pairs) {
        const Cuboid a{Vector3d::Zero(), pr.s1 / 2, Vector3d(0, 0, pr.J1 / mu0)};
        const Cuboid b{pr.c2, pr.s2 / 2, Vector3d(0, 0, pr.J2 / mu0)};
        const Wrench w = oracle::contactChargeWrench(a, b, b.centre);
        const Vector3d F1 = oracle::akounYonnetForceOneSided(pr.s1, Vector3d::Zero(), pr.s2, pr.c2, pr.J1, pr.J2);
        const Vector3d Fm = oracle::akounYonnetForce(pr.s1, Vector3d::Zero(), pr.s2, pr.c2, pr.J1, pr.J2);
        CAPTURE(pr.c2.transpose(), w.force.transpose(), F1.transpose(), Fm.transpose());
        CHECK(relDiff(w.force, F1) < 1e-8);  // measured <= 3e-12
    }
}

// ---------------------------------------------------------------------------------
// contactChargeWrench: rotated contacts
// ---------------------------------------------------------------------------------

// The exactly touching value continues the trend of small gaps (g = 0.1 um, 0.2 um):
// 2 W(g) - W(2g) = W(0) + O(g^2) here (measured 6.6e-10 ... 1.7e-9 of |F|, 100x more at
// g = 1 um). The mean of the two one-sided fields at a face contact would be off by
// O(1) (the contact jump: 39.8 N on 1 cm^2 at 1 T).
TEST_CASE("contact quadrature: rotated face contact is the limit of its separated neighbours",
          "[oracle][contact]") {
    // target rotated 30 deg about z, coaxial, on the source's top face
    const Trend t = linearTrend(source, cube(Vector3d(0, 0, 0.01), Rz30), Vector3d::UnitZ(), 1e-7);
    CAPTURE(t.touching.force.transpose(), t.touching.torque.transpose(), t.dF, t.dT);
    CHECK(t.dF < 1e-8);  // measured 1.3e-9
    CHECK(t.dT < 1e-8);
}

TEST_CASE("contact quadrature: edge-on-face contact is the limit of its separated neighbours",
          "[oracle][contact]") {
    // target rotated 45 deg about x on its lower edge, laterally offset
    const Trend t = linearTrend(source, cube(Vector3d(0.002, 0.001, zEdge), Rx45), Vector3d::UnitZ(), 1e-7);
    CAPTURE(t.touching.force.transpose(), t.touching.torque.transpose(), t.dF, t.dT);
    CHECK(t.dF < 1e-8);  // measured 6.6e-10
    CHECK(t.dT < 1e-8);
}

TEST_CASE("contact quadrature: vertex-on-face contact is the limit of its separated neighbours",
          "[oracle][contact]") {
    const Trend t = linearTrend(source, cube(Vector3d(0.001, -0.002, zVertex), Rvertex), Vector3d::UnitZ(), 1e-7);
    CAPTURE(t.touching.force.transpose(), t.touching.torque.transpose(), t.dF, t.dT);
    CHECK(t.dF < 1e-8);  // measured 7.0e-10
    CHECK(t.dT < 1e-8);
}

TEST_CASE("contact quadrature: crossing edges in contact are the limit of separated neighbours",
          "[oracle][contact]") {
    // source rotated 45 deg about x (top edge along x), target rotated 45 deg about y
    // resting on it with its lower edge along y: point contact of two crossing edges
    const Cuboid src = cube(Vector3d::Zero(), Rx45);
    const Trend t = linearTrend(src, cube(Vector3d(0.002, 0.003, 2 * h * std::sqrt(2.0)), Ry45),
                                Vector3d::UnitZ(), 1e-7);
    CAPTURE(t.touching.force.transpose(), t.touching.torque.transpose(), t.dF, t.dT);
    CHECK(t.dF < 1e-8);  // measured 7.7e-10
    CHECK(t.dT < 1e-8);
}

TEST_CASE("contact quadrature: general poses (oblique M, different boxes) in face contact",
          "[oracle][contact]") {
    // source with a general pose; target on its +x face, turned 0.35 rad about that normal
    const Matrix3d Rs = rotation(0.4, Vector3d(1, 2, 3));
    const Cuboid src{Vector3d(0.001, 0.002, -0.001), Vector3d(0.006, 0.004, 0.005),
                     Vector3d(0.3, -0.5, 0.8) * M1T, Rs};
    const Cuboid tgt{src.centre + Rs * Vector3d(0.009, 0.0015, -0.001), Vector3d(0.003, 0.005, 0.004),
                     Vector3d(-0.2, 0.9, 0.1) * M1T, Rs * rotation(0.35, Vector3d::UnitX())};
    // relTol 1e-9 keeps this case (6 charged faces on each body) near 2 s; the errors
    // are still ~1e-13 (the estimates are conservative, file comment of the oracle)
    const Trend t = linearTrend(src, tgt, Rs.col(0), 1e-7, 1e-9);
    CAPTURE(t.touching.force.transpose(), t.touching.torque.transpose(), t.dF, t.dT);
    CHECK(t.dF < 1e-8);  // measured 1.7e-9
    CHECK(t.dT < 1e-8);
}

TEST_CASE("contact quadrature: torque of separated rotated pairs equals the brute-force quadrature",
          "[oracle][contact][quadrature]") {
    const Cuboid general{Vector3d::Zero(), Vector3d(0.006, 0.004, 0.003), Vector3d(0.2, 0.3, 0.9) * M1T,
                         rotation(0.3, Vector3d(0, 1, 1))};
    const Cuboid generalTarget{Vector3d(0.004, -0.002, 0.013), Vector3d(0.004, 0.003, 0.002),
                               Vector3d(-0.4, 0.5, 0.7) * M1T, rotation(0.5, Vector3d(1, -1, 2))};
    struct Pair { Cuboid s, t; };
    const Pair pairs[] = {
        {source, cube(Vector3d(0, 0, 0.011), Rz30)},                // 1 mm gap, rotated 30 deg
        {source, cube(Vector3d(0.002, 0.001, zEdge + 0.001), Rx45)},  // edge 1 mm above the face
        {general, generalTarget},
    };
    for (const Pair& pr : pairs) {
        const Wrench w = oracle::contactChargeWrench(pr.s, pr.t, pr.t.centre);
        // 0.5 mm panels x 8 points: spectrally converged at a 1 mm gap
        const Wrench q = oracle::chargeQuadratureWrench(pr.s, pr.t, pr.t.centre, 20, 8);
        CAPTURE(w.force.transpose(), w.torque.transpose(), q.torque.transpose());
        CHECK(relDiff(w.force, q.force) < 1e-10);  // measured <= 1e-14
        const double L = 2 * pr.t.halfSize.maxCoeff();
        CHECK((w.torque - q.torque).norm() < 1e-10 * w.force.norm() * L);
    }
}

namespace {
// on b from a, and on a from b (the roles swapped: b's edge / vertex on a's face is then
// a SOURCE edge / vertex on the target's face, a different integrand on other faces)
void checkNewton(const Cuboid& a, const Cuboid& b, double relTol = 1e-10) {
    const Vector3d p(0.003, -0.001, 0.004);
    const Wrench wb = oracle::contactChargeWrench(a, b, p, relTol);
    const Wrench wa = oracle::contactChargeWrench(b, a, p, relTol);
    CAPTURE(wb.force.transpose(), wa.force.transpose(), wb.torque.transpose(), wa.torque.transpose(),
            (wa.force + wb.force).norm() / wb.force.norm());
    CHECK((wa.force + wb.force).norm() < 1e-8 * wb.force.norm());  // measured <= 3e-13
    // central Coulomb forces between charge elements: no net torque about any point
    CHECK((wa.torque + wb.torque).norm() < 1e-8 * wb.force.norm() * 0.01);
}
}  // namespace

TEST_CASE("contact quadrature: Newton's third law and zero total torque for touching cubes",
          "[oracle][contact]") {
    checkNewton(source, cube(Vector3d(0, 0, 0.01), Rz30));                // rotated footprint
    checkNewton(source, cube(Vector3d(0.002, 0.001, zEdge), Rx45));       // edge on face
    checkNewton(source, cube(Vector3d(0.001, -0.002, zVertex), Rvertex)); // vertex on face
    checkNewton(cube(Vector3d::Zero(), Rx45), cube(Vector3d(0.002, 0.003, 2 * h * std::sqrt(2.0)), Ry45));
}

TEST_CASE("contact quadrature: Newton's third law for a general touching pair", "[oracle][contact]") {
    const Matrix3d Rs = rotation(0.4, Vector3d(1, 2, 3));
    const Cuboid a{Vector3d(0.001, 0.002, -0.001), Vector3d(0.006, 0.004, 0.005),
                   Vector3d(0.3, -0.5, 0.8) * M1T, Rs};
    const Cuboid b{a.centre + Rs * Vector3d(0.009, 0.0015, -0.001), Vector3d(0.003, 0.005, 0.004),
                   Vector3d(-0.2, 0.9, 0.1) * M1T, Rs * rotation(0.35, Vector3d::UnitX())};
    checkNewton(a, b);
}

TEST_CASE("contact quadrature: torque about another point", "[oracle][contact]") {
    const Cuboid t = cube(Vector3d(0.001, -0.002, zVertex), Rvertex);
    const Vector3d p1 = t.centre, p2(0.02, -0.01, 0.03);
    const Wrench w1 = oracle::contactChargeWrench(source, t, p1);
    const Wrench w2 = oracle::contactChargeWrench(source, t, p2);
    CHECK(relDiff(w2.force, w1.force) < 1e-14);  // the same integrals
    const Vector3d moved = w1.torque + (p1 - p2).cross(w1.force);
    CHECK((w2.torque - moved).norm() < 1e-13 * w1.force.norm() * 0.03);  // rounding
}

// The reference table of contactQuadrature.hpp (quoted to 10 digits; components that
// vanish by symmetry are below 1e-12 relative; allowed: half a unit of the 10th digit
// plus 1e-11 of |F| (|F| x 1 cm) for the quadrature).
TEST_CASE("contact quadrature: the reference values", "[oracle][contact]") {
    struct Row { const char* name; Vector3d c; Matrix3d R; Vector3d F, T; };
    const Matrix3d I = Matrix3d::Identity();
    const Row rows[] = {
        {"coaxial", Vector3d(0, 0, 0.01), I, Vector3d(0, 0, -32.37863296), Vector3d(0, 0, 0)},
        {"offset (3,2) mm", Vector3d(0.003, 0.002, 0.01), I, Vector3d(-9.150942274, -6.881274379, -15.61100447),
         Vector3d(-0.01879536742, 0.02233820467, 0.001170969294)},
        {"offset (5,5) mm", Vector3d(0.005, 0.005, 0.01), I, Vector3d(-7.111730414, -7.111730414, -4.943744363),
         Vector3d(-0.02319929116, 0.02319929116, 0)},
        {"edge to edge (10,0) mm", Vector3d(0.01, 0, 0.01), I, Vector3d(-6.779247875, 0, 3.462332414),
         Vector3d(0, 0.05120790144, 0)},
        {"rotated 30 deg about z", Vector3d(0, 0, 0.01), Rz30, Vector3d(0, 0, -26.22521328),
         Vector3d(0, 0, -0.005766853108)},
        {"rotated 45 deg about x, on its edge", Vector3d(0, 0, zEdge), Rx45, Vector3d(0, 0, -15.02530617),
         Vector3d(0, 0, 0)},
        {"on its vertex", Vector3d(0, 0, zVertex), Rvertex, Vector3d(-0.03696809755, -0.03696809755, -9.829194262),
         Vector3d(-0.0001081800937, 0.0001081800937, 0)},
        {"gap 1 um", Vector3d(0, 0, 0.010001), I, Vector3d(0, 0, -32.33198254), Vector3d(0, 0, 0)},
        {"gap 10 um", Vector3d(0, 0, 0.01001), I, Vector3d(0, 0, -32.02874544), Vector3d(0, 0, 0)},
    };
    for (const Row& row : rows) {
        const Wrench w = oracle::contactChargeWrench(source, cube(row.c, row.R), row.c);
        CAPTURE(row.name, w.force.transpose(), w.torque.transpose());
        const double Fn = row.F.norm();
        // 10 significant digits: half a unit of the 10th digit of each component
        for (int j = 0; j < 3; ++j) {
            CHECK(std::abs(w.force[j] - row.F[j]) < 5e-10 * std::abs(row.F[j]) + 1e-11 * Fn);
            CHECK(std::abs(w.torque[j] - row.T[j]) < 5e-10 * std::abs(row.T[j]) + 1e-11 * Fn * 0.01);
        }
    }
}
