// Tests of the independent oracles in reference/oracles/ against the reference values
// of docs/physics.md#reference-values, against classical closed forms, against brute-force quadrature and against
// each other. The oracles are then used to test the production code.
#include <catch2/catch.hpp>

#include <cmath>
#include <functional>

#include "oracles/akounYonnet.hpp"
#include "oracles/chargeQuadrature.hpp"
#include "oracles/cuboidField.hpp"
#include "oracles/dipole.hpp"

using Eigen::Vector3d;
using oracle::Cuboid;
using oracle::mu0;
using oracle::pi;

namespace {

double relDiff(const Vector3d& a, const Vector3d& b) { return (a - b).norm() / b.norm(); }
double relDiff(double a, double b) { return std::abs(a - b) / std::abs(b); }

// Brute-force H of a cuboid: tensor Gauss-Legendre quadrature of the Coulomb kernel
// sigma/(4 pi) (r - r')/|r - r'|^3 over its six charged faces (axis-aligned only).
Vector3d bruteForceCuboidH(const Cuboid& c, const Vector3d& r, int panels, int order) {
    Eigen::VectorXd gx, gw;
    oracle::detail::gaussLegendre(order, gx, gw);
    Vector3d H = Vector3d::Zero();
    for (int k = 0; k < 3; ++k) {
        const int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
        const double a = c.halfSize[k1], b = c.halfSize[k2];
        const double da = 2 * a / panels, db = 2 * b / panels;
        for (int s = -1; s <= 1; s += 2) {
            const double sigma = s * c.M[k];
            for (int i = 0; i < panels; ++i)
                for (int j = 0; j < panels; ++j)
                    for (int qi = 0; qi < order; ++qi)
                        for (int qj = 0; qj < order; ++qj) {
                            Vector3d rp = c.centre;
                            rp[k] += s * c.halfSize[k];
                            rp[k1] += -a + (i + 0.5 + 0.5 * gx[qi]) * da;
                            rp[k2] += -b + (j + 0.5 + 0.5 * gx[qj]) * db;
                            const Vector3d d = r - rp;
                            const double w = gw[qi] * gw[qj] * 0.25 * da * db;
                            H += w * sigma / (4 * pi) * d / std::pow(d.norm(), 3);
                        }
        }
    }
    return H;
}

// Jacobian of a vector field by central differences, step h.
Eigen::Matrix3d jacobian(const std::function<Vector3d(const Vector3d&)>& f, const Vector3d& r,
                         double h) {
    Eigen::Matrix3d J;
    for (int j = 0; j < 3; ++j) {
        Vector3d e = Vector3d::Zero();
        e[j] = h;
        J.col(j) = (f(r + e) - f(r - e)) / (2 * h);
    }
    return J;
}

// Volume integral of mu0 M2 x H1 over the target (3D Gauss-Legendre): the couple that a
// wrong torque formula would add on top of the surface-charge torque.
Vector3d volumeCouple(const Cuboid& source, const Cuboid& target, int panels, int order) {
    Eigen::VectorXd gx, gw;
    oracle::detail::gaussLegendre(order, gx, gw);
    const Vector3d cell = 2 * target.halfSize / panels;
    Vector3d sum = Vector3d::Zero();
    for (int i = 0; i < panels; ++i)
        for (int j = 0; j < panels; ++j)
            for (int l = 0; l < panels; ++l)
                for (int a = 0; a < order; ++a)
                    for (int b = 0; b < order; ++b)
                        for (int c = 0; c < order; ++c) {
                            const Vector3d local(
                                -target.halfSize.x() + (i + 0.5 + 0.5 * gx[a]) * cell.x(),
                                -target.halfSize.y() + (j + 0.5 + 0.5 * gx[b]) * cell.y(),
                                -target.halfSize.z() + (l + 0.5 + 0.5 * gx[c]) * cell.z());
                            const Vector3d r = target.centre + target.R * local;
                            sum += gw[a] * gw[b] * gw[c] * cell.prod() / 8 *
                                   target.M.cross(oracle::cuboidH(source, r));
                        }
    return mu0 * sum;
}

const double M1T = 1.0 / mu0;  // |M| of a 1 T magnet (A/m)
const Vector3d cm3(0.01, 0.01, 0.01);  // 1 cm cube, full size

}  // namespace

// ---------------------------------------------------------------------------------
// cuboidField.hpp
// ---------------------------------------------------------------------------------

TEST_CASE("cuboid: on-axis Bz equals the classical block formula", "[oracle][cuboid]") {
    // B = Br/pi [atan(LW/(2z sqrt(4z^2+L^2+W^2))) - atan(LW/(2(D+z) sqrt(4(D+z)^2+L^2+W^2)))]
    // z from the pole face, block L x W x D magnetized along D (e.g. K&J Magnetics).
    const double L = 0.02, W = 0.012, D = 0.006, Br = 1.3;
    const Cuboid c{Vector3d::Zero(), Vector3d(L / 2, W / 2, D / 2), Vector3d(0, 0, Br / mu0)};
    for (double z : {1e-4, 1e-3, 5e-3, 0.02, 0.1}) {
        const double ref = Br / pi *
                           (std::atan(L * W / (2 * z * std::sqrt(4 * z * z + L * L + W * W))) -
                            std::atan(L * W / (2 * (D + z) *
                                               std::sqrt(4 * (D + z) * (D + z) + L * L + W * W))));
        const Vector3d B = oracle::cuboidB(c, Vector3d(0, 0, D / 2 + z));
        // two forms of the same closed form: agree to rounding (measured <= 3.5e-15)
        CHECK(relDiff(B.z(), ref) < 1e-12);
        // transverse components vanish by symmetry (rounding of O(Br) terms)
        CHECK(std::abs(B.x()) + std::abs(B.y()) < 1e-14);
    }
}

TEST_CASE("cuboid: cube centre has demagnetizing factor 1/3", "[oracle][cuboid]") {
    // cubic symmetry + trace(N) = 1 inside => H = -M/3, B = (2/3) mu0 M at the centre
    const Vector3d M = Vector3d(0.3, -0.5, 0.8) * M1T;
    const Cuboid c{Vector3d(0.001, 0.002, -0.003), Vector3d(0.004, 0.004, 0.004), M};
    // exact identity, only rounding of the corner sums (measured ~1e-16)
    CHECK(relDiff(oracle::cuboidH(c, c.centre), Vector3d(-M / 3)) < 1e-13);
    CHECK(relDiff(oracle::cuboidB(c, c.centre), Vector3d(2.0 / 3.0 * mu0 * M)) < 1e-13);
}

TEST_CASE("cuboid: closed form equals brute-force charge quadrature", "[oracle][cuboid]") {
    // oblique M, non-cubic box, off-centre; points outside (near and far) and inside
    const Cuboid c{Vector3d(0.001, -0.002, 0.0005), Vector3d(0.005, 0.003, 0.002),
                   Vector3d(0.3, -0.5, 0.8) * M1T};
    const Vector3d pts[] = {Vector3d(0.012, 0.004, 0.003),   Vector3d(-0.003, -0.009, 0.006),
                            Vector3d(0.002, 0.0, -0.004),    Vector3d(0.05, -0.03, 0.02),
                            Vector3d(0.001, -0.002, 0.0005), Vector3d(-0.002, -0.001, 0.001)};
    for (const Vector3d& r : pts) {
        const Vector3d H = oracle::cuboidH(c, r);
        const Vector3d Hq = bruteForceCuboidH(c, r, 16, 10);
        CAPTURE(r.transpose(), H.transpose(), Hq.transpose());
        // points >= 1 mm from the surface, 0.4 mm panels x 10 points: quadrature error
        // far below this (measured <= 1.2e-13)
        CHECK(relDiff(H, Hq) < 1e-9);
    }
}

TEST_CASE("cuboid: far field equals the dipole M V", "[oracle][cuboid][dipole]") {
    const Vector3d M = Vector3d(0.3, -0.5, 0.8) * M1T;
    const Vector3d dir = Vector3d(0.3, 0.7, -0.5).normalized();
    SECTION("cube: next multipole is l = 5, relative error ~ (a/r)^4") {
        const Cuboid c{Vector3d::Zero(), Vector3d(0.005, 0.005, 0.005), M};
        const Vector3d m = M * 8 * c.halfSize.prod();
        // measured 1.2e-5 at 10 edge lengths, 1.2e-9 at 100
        CHECK(relDiff(oracle::cuboidB(c, 0.1 * dir), oracle::dipoleB(m, c.centre, 0.1 * dir)) < 3e-5);
        CHECK(relDiff(oracle::cuboidB(c, 1.0 * dir), oracle::dipoleB(m, c.centre, 1.0 * dir)) < 1e-8);
    }
    SECTION("box: quadrupole-order error ~ (a/r)^2") {
        const Cuboid c{Vector3d::Zero(), Vector3d(0.005, 0.003, 0.002), M};
        const Vector3d m = M * 8 * c.halfSize.prod();
        // measured 1.7e-3 at 10 edge lengths, 1.7e-5 at 100
        CHECK(relDiff(oracle::cuboidB(c, 0.1 * dir), oracle::dipoleB(m, c.centre, 0.1 * dir)) < 4e-3);
        CHECK(relDiff(oracle::cuboidB(c, 1.0 * dir), oracle::dipoleB(m, c.centre, 1.0 * dir)) < 4e-5);
    }
}

TEST_CASE("cuboid: div B = 0 and curl H = 0 by finite differences", "[oracle][cuboid]") {
    // rotated box, oblique M; points outside and inside (away from the faces)
    Cuboid c{Vector3d(0.001, 0.002, -0.001), Vector3d(0.005, 0.003, 0.002),
             Vector3d(0.3, -0.5, 0.8) * M1T};
    c.R = Eigen::AngleAxisd(0.4, Vector3d(1, 2, 3).normalized()).toRotationMatrix();
    // (not the centre itself: grad H vanishes there by symmetry)
    const Vector3d pts[] = {Vector3d(0.012, 0.004, 0.003), Vector3d(-0.006, -0.009, 0.006),
                            Vector3d(0.0, 0.0, 0.009),
                            Vector3d(c.centre + c.R * Vector3d(0.003, -0.002, 0.001)),
                            Vector3d(c.centre + c.R * Vector3d(-0.001, 0.0015, -0.0008))};
    const double h = 1e-7;  // 0.1 um step: O(h^2) truncation ~1e-9, rounding ~1e-12
    for (const Vector3d& r : pts) {
        const Eigen::Matrix3d JB = jacobian([&](const Vector3d& x) { return oracle::cuboidB(c, x); }, r, h);
        const Eigen::Matrix3d JH = jacobian([&](const Vector3d& x) { return oracle::cuboidH(c, x); }, r, h);
        const double scale = JH.norm();  // typical derivative size
        const Vector3d curl(JH(2, 1) - JH(1, 2), JH(0, 2) - JH(2, 0), JH(1, 0) - JH(0, 1));
        CAPTURE(r.transpose(), JB.trace() / mu0 / scale, curl.norm() / scale);
        // finite-difference noise relative to |grad H| (measured <= 1.1e-9)
        CHECK(std::abs(JB.trace()) / mu0 < 1e-7 * scale);
        CHECK(curl.norm() < 1e-7 * scale);
    }
}

TEST_CASE("cuboid: boundary values, continuity, finiteness", "[oracle][cuboid]") {
    const Vector3d M = Vector3d(0.3, -0.5, 0.8) * M1T;
    const Cuboid c{Vector3d::Zero(), Vector3d(0.005, 0.003, 0.002), M};
    // one-sided offsets of 1 pm: the one-sided values differ from the limits by
    // O(d / distance-to-edge) ~ 1e-9 relative (points >= 1 mm from the edges;
    // measured <= 6e-10)
    const double d = 1e-12;
    SECTION("top face: B normal continuous, H tangential continuous, value = mean") {
        const Vector3d r(0.001, 0.0012, 0.002);
        const Vector3d up(0, 0, d);
        const Vector3d Bo = oracle::cuboidB(c, r + up), Bi = oracle::cuboidB(c, r - up);
        const Vector3d Ho = oracle::cuboidH(c, r + up), Hi = oracle::cuboidH(c, r - up);
        // normal B continuous (1e-8: see d above)
        CHECK(std::abs(Bo.z() - Bi.z()) < 1e-8 * Bo.norm());
        // tangential H continuous
        CHECK(std::abs(Ho.x() - Hi.x()) + std::abs(Ho.y() - Hi.y()) < 1e-8 * Ho.norm());
        // normal H jumps outwards by sigma = M . n = Mz
        CHECK(relDiff(Ho.z() - Hi.z(), M.z()) < 1e-8);
        // on the face: mean of the one-sided limits, for H and B
        CHECK(relDiff(oracle::cuboidH(c, r), Vector3d(0.5 * (Ho + Hi))) < 1e-8);
        CHECK(relDiff(oracle::cuboidB(c, r), Vector3d(0.5 * (Bo + Bi))) < 1e-8);
    }
    SECTION("side face x = +a: same checks along x") {
        const Vector3d r(0.005, -0.001, 0.0005);
        const Vector3d out(d, 0, 0);
        const Vector3d Bo = oracle::cuboidB(c, r + out), Bi = oracle::cuboidB(c, r - out);
        const Vector3d Ho = oracle::cuboidH(c, r + out), Hi = oracle::cuboidH(c, r - out);
        // normal B continuous / normal H jumps by Mx / on-face mean (as above)
        CHECK(std::abs(Bo.x() - Bi.x()) < 1e-8 * Bo.norm());
        CHECK(relDiff(Ho.x() - Hi.x(), M.x()) < 1e-8);
        CHECK(relDiff(oracle::cuboidB(c, r), Vector3d(0.5 * (Bo + Bi))) < 1e-8);
    }
    SECTION("finite on face planes and edge-line extensions outside, not on edges") {
        // face plane z = h outside the face, and the extension of the vertical edge x=a,y=b
        CHECK(std::isfinite(oracle::cuboidB(c, Vector3d(0.009, 0.001, 0.002)).norm()));
        CHECK(std::isfinite(oracle::cuboidB(c, Vector3d(0.005, 0.003, 0.007)).norm()));
        CHECK(std::isfinite(oracle::cuboidB(c, Vector3d(0.011, 0.003, 0.002)).norm()));
        // documented: exactly on an edge the tangential H is log-singular
        CHECK_FALSE(std::isfinite(oracle::cuboidH(c, Vector3d(0.005, 0.0, 0.002)).norm()));
    }
}

TEST_CASE("cuboid: a rotated box equals the equivalent axis-aligned box", "[oracle][cuboid]") {
    // 90 deg about x maps body (a, b, h) to world extents (a, h, b) and M_body to R M_body
    const Eigen::Matrix3d R = Eigen::AngleAxisd(pi / 2, Vector3d::UnitX()).toRotationMatrix();
    const Vector3d Mw = Vector3d(0.2, 0.9, -0.4) * M1T;
    Cuboid rotated{Vector3d(0.001, 0, 0.002), Vector3d(0.005, 0.003, 0.002), Mw};
    rotated.R = R;
    const Cuboid aligned{rotated.centre, Vector3d(0.005, 0.002, 0.003), Mw};
    for (const Vector3d& r : {Vector3d(0.01, 0.004, -0.003), Vector3d(0.0, 0.001, 0.002)}) {
        // same geometry, different code path; cos(pi/2) rounding ~6e-17 (measured ~1e-15)
        CHECK(relDiff(oracle::cuboidB(rotated, r), oracle::cuboidB(aligned, r)) < 1e-12);
    }
}

// ---------------------------------------------------------------------------------
// dipole.hpp
// ---------------------------------------------------------------------------------

TEST_CASE("dipole: force is grad(m.B), Newton 3, angular momentum", "[oracle][dipole]") {
    const Vector3d m1(0.3, -0.2, 0.9), p1(0.001, -0.002, 0.0);
    const Vector3d m2(-0.5, 0.4, 0.2), p2(0.02, 0.013, -0.017);
    const Vector3d F = oracle::dipoleForce(m2, p2, m1, p1);
    // central differences of the energy -m2.B1 (h = 1 um at 30 mm: error ~1e-9)
    Vector3d grad;
    const double h = 1e-6;
    for (int j = 0; j < 3; ++j) {
        Vector3d e = Vector3d::Zero();
        e[j] = h;
        grad[j] = (m2.dot(oracle::dipoleB(m1, p1, p2 + e)) - m2.dot(oracle::dipoleB(m1, p1, p2 - e))) / (2 * h);
    }
    CHECK(relDiff(F, grad) < 1e-7);  // finite-difference truncation (measured 2.6e-9)
    // Newton's third law (exact formula symmetry: rounding only)
    CHECK(relDiff(oracle::dipoleForce(m1, p1, m2, p2), Vector3d(-F)) < 1e-13);
    // total angular momentum balance about the origin (rounding only)
    const Vector3d T1 = oracle::dipoleTorque(m1, p1, m2, p2);
    const Vector3d T2 = oracle::dipoleTorque(m2, p2, m1, p1);
    const Vector3d total = T1 + T2 + p1.cross(-F) + p2.cross(F);
    CHECK(total.norm() < 1e-12 * (T1.norm() + T2.norm()));
    // torque is m x B (paper Eq. 6)
    CHECK(relDiff(T2, Vector3d(m2.cross(oracle::dipoleB(m1, p1, p2)))) < 1e-15);  // same expression
    // coaxial attraction: F = -3 mu0 m^2/(2 pi r^4) ez for m along z at distance r
    const Vector3d mz(0, 0, 1.0);
    const Vector3d Fz = oracle::dipoleForce(mz, Vector3d(0, 0, 0.1), mz, Vector3d::Zero());
    CHECK(relDiff(Fz.z(), -3 * mu0 / (2 * pi * 1e-4)) < 1e-14);  // rounding only
}

TEST_CASE("sphere: surface-charge quadrature gives -M/3 inside and the dipole outside",
          "[oracle][dipole]") {
    const double a = 0.004;
    const Vector3d c(0.001, 0.0, -0.002), M = Vector3d(0.3, -0.5, 0.8) * M1T;
    // H = 1/(4 pi) int sigma (r - r')/|r - r'|^3 dA, sigma = M . n; Gauss in theta,
    // trapezoid (spectral for periodic integrands) in phi
    auto quadH = [&](const Vector3d& r) {
        Eigen::VectorXd x, w;
        oracle::detail::gaussLegendre(96, x, w);
        const int nphi = 192;
        Vector3d H = Vector3d::Zero();
        for (int i = 0; i < x.size(); ++i) {
            const double ct = x[i], st = std::sqrt(1 - ct * ct);
            for (int j = 0; j < nphi; ++j) {
                const double ph = 2 * pi * j / nphi;
                const Vector3d n(st * std::cos(ph), st * std::sin(ph), ct);
                const Vector3d d = r - (c + a * n);
                H += w[i] * (2 * pi / nphi) * a * a * M.dot(n) / (4 * pi) * d / std::pow(d.norm(), 3);
            }
        }
        return H;
    };
    for (const Vector3d& r : {Vector3d(c + Vector3d(0.001, 0.0005, -0.0008)),
                              Vector3d(c + Vector3d(0.005, -0.003, 0.002))}) {
        // points >= 1.8 mm from the surface of a 4 mm sphere: quadrature converged
        // far beyond this (measured <= 4e-15)
        CHECK(relDiff(oracle::sphereH(c, a, M, r), quadH(r)) < 1e-9);
    }
    // inside B = (2/3) mu0 M; surface value is the mean of both sides
    CHECK(relDiff(oracle::sphereB(c, a, M, c), Vector3d(2.0 / 3.0 * mu0 * M)) < 1e-15);
    const Vector3d rs = c + a * Vector3d(0, 0, 1);
    const Vector3d Bmean = 0.5 * (oracle::sphereB(c, a, M, c + Vector3d(0, 0, a * (1 - 1e-12))) +
                                  oracle::sphereB(c, a, M, c + Vector3d(0, 0, a * (1 + 1e-12))));
    // one-sided values at 1e-12 relative offsets (measured 1.6e-12)
    CHECK(relDiff(oracle::sphereB(c, a, M, rs), Bmean) < 1e-10);
}

// ---------------------------------------------------------------------------------
// akounYonnet.hpp
// ---------------------------------------------------------------------------------

TEST_CASE("Akoun-Yonnet: the reference gap table for two 1 cm, 1 T cubes", "[oracle][AY]") {
    struct Row { double gap, F; };
    const Row table[] = {{0.2e-3, 28.4021}, {0.5e-3, 24.703}, {1e-3, 20.360}, {2e-3, 14.673},
                         {5e-3, 6.568},     {10e-3, 2.251},   {20e-3, 0.4635}, {50e-3, 0.02929}};
    for (const Row& row : table) {
        const Vector3d F =
            oracle::akounYonnetForce(cm3, Vector3d::Zero(), cm3, Vector3d(0, 0, 0.01 + row.gap), 1, 1);
        CAPTURE(row.gap, F.z());
        // reference quoted to 4-6 digits: half a unit of its last digit (<= 2e-4 rel)
        CHECK(relDiff(-F.z(), row.F) < 2.5e-4);
        // attraction, no lateral force (cancellation noise of the 64-term sum)
        CHECK(F.z() < 0);
        CHECK(F.head<2>().norm() < 1e-10 * std::abs(F.z()));
    }
}

TEST_CASE("Akoun-Yonnet: the 1984 paper's geometry", "[oracle][AY]") {
    const Vector3d s1(0.020, 0.012, 0.006), s2(0.012, 0.020, 0.006);
    struct Row { double d; Vector3d F; };
    const Row rows[] = {{0, Vector3d(0.5884, 0.5884, -1.7736)},
                        {4, Vector3d(0, 0.6376, -1.8534)},
                        {10, Vector3d(-0.9086, 0.5177, -1.4668)},
                        {20, Vector3d(-0.5671, 0.0573, 0.4102)}};
    for (const Row& row : rows) {
        const Vector3d c2((-4 + row.d) * 1e-3, -4e-3, 8e-3);
        const Vector3d F = oracle::akounYonnetForce(s1, Vector3d::Zero(), s2, c2, 0.38, 0.38);
        CAPTURE(row.d, F.transpose());
        // reference quoted to 4 decimals (N): half a unit of the last digit
        CHECK((F - row.F).cwiseAbs().maxCoeff() < 0.5e-4 + 1e-12);
    }
}

TEST_CASE("Akoun-Yonnet: symmetry and Newton's third law", "[oracle][AY]") {
    const Vector3d s1(0.02, 0.012, 0.006), s2(0.012, 0.02, 0.008);
    const Vector3d c1(0.001, -0.002, 0.003), c2(0.004, 0.006, 0.012);
    const Vector3d F21 = oracle::akounYonnetForce(s1, c1, s2, c2, 0.9, 1.2);
    const Vector3d F12 = oracle::akounYonnetForce(s2, c2, s1, c1, 1.2, 0.9);
    CHECK(relDiff(F12, Vector3d(-F21)) < 1e-12);  // rounding of the 64-term sums
    // translation invariance (rounding; measured ~1e-15)
    const Vector3d shift(0.1, -0.2, 0.05);
    CHECK(relDiff(oracle::akounYonnetForce(s1, c1 + shift, s2, c2 + shift, 0.9, 1.2), F21) < 1e-10);
    // reversing one magnetization reverses the force (exact: J1 J2 prefactor)
    CHECK(relDiff(oracle::akounYonnetForce(s1, c1, s2, c2, -0.9, 1.2), Vector3d(-F21)) < 1e-15);
}

TEST_CASE("Akoun-Yonnet: overlap and contact, charge and Amperian", "[oracle][AY]") {
    // docs/physics.md#overlap-models
    SECTION("1 cm cubes at face gap -0.5 cm") {
        const Vector3d c2(0, 0, 0.005);
        const Vector3d Fc = oracle::akounYonnetForce(cm3, Vector3d::Zero(), cm3, c2, 1, 1);
        const Vector3d Fa = oracle::amperianForceCuboids(cm3, Vector3d::Zero(), cm3, c2, 1, 1);
        // references quoted to 4 digits (measured 28.5504 and -51.0271)
        CHECK(relDiff(Fc.z(), 28.55) < 2e-4);
        CHECK(relDiff(Fa.z(), -51.03) < 2e-4);
        CHECK(Fc.head<2>().norm() < 1e-12);  // symmetry: rounding only
    }
    SECTION("contact jump of the charge force; the Amperian force is continuous") {
        const double eps = 1e-12;  // 1 pm: one-sided limits within O(eps/gap-scale)
        auto Fc = [&](double z) { return oracle::akounYonnetForce(cm3, Vector3d::Zero(), cm3, Vector3d(0, 0, z), 1, 1).z(); };
        auto Fa = [&](double z) { return oracle::amperianForceCuboids(cm3, Vector3d::Zero(), cm3, Vector3d(0, 0, z), 1, 1).z(); };
        // docs/physics.md#contact, values quoted to 4 digits
        CHECK(relDiff(Fc(0.01 + eps), -32.38) < 2e-4);
        CHECK(relDiff(Fc(0.01 - eps), 47.20) < 2e-4);
        // exactly touching: the mean of the two limits (documented convention;
        // measured 2e-15, the 1e-6 allows for the O(eps) offset of the limits)
        CHECK(relDiff(Fc(0.01), 0.5 * (Fc(0.01 + eps) + Fc(0.01 - eps))) < 1e-6);
        // Amperian: continuous through contact (the jump is removed exactly; what is
        // left is the O(eps) change of a smooth function, measured 7e-9)
        CHECK(relDiff(Fa(0.01 - eps), Fa(0.01 + eps)) < 1e-6);
        CHECK(relDiff(Fa(0.01), Fa(0.01 + eps)) < 1e-6);
    }
    SECTION("overlap volume gradient equals its finite difference") {
        const Vector3d s1(0.02, 0.012, 0.006), s2(0.012, 0.02, 0.008);
        const Vector3d c1(0.001, -0.002, 0.003), c2(0.004, 0.006, 0.005);
        const Vector3d g = oracle::overlapVolumeGradient(s1, c1, s2, c2);
        const double h = 1e-7;  // V is piecewise polynomial: exact away from kinks
        for (int j = 0; j < 3; ++j) {
            Vector3d e = Vector3d::Zero();
            e[j] = h;
            const double fd = (oracle::overlapVolume(s1, c1, s2, c2 + e) -
                               oracle::overlapVolume(s1, c1, s2, c2 - e)) / (2 * h);
            CHECK(std::abs(fd - g[j]) < 1e-9 * g.norm());  // rounding / h
        }
    }
    SECTION("finite for degenerate configurations (coincident faces, edges, boxes)") {
        const Vector3d cases[] = {Vector3d(0, 0, 0), Vector3d(0.01, 0, 0), Vector3d(0.01, 0.01, 0.01),
                                  Vector3d(0.005, 0, 0), Vector3d(0, 0.01, 0.005)};
        for (const Vector3d& c2 : cases) {
            const Vector3d F = oracle::akounYonnetForce(cm3, Vector3d::Zero(), cm3, c2, 1, 1);
            CAPTURE(c2.transpose(), F.transpose());
            CHECK(std::isfinite(F.norm()));
        }
        // identical boxes: zero force by symmetry (rounding of O(10 N) terms)
        CHECK(oracle::akounYonnetForce(cm3, Vector3d::Zero(), cm3, Vector3d::Zero(), 1, 1).norm() < 1e-12);
    }
}

TEST_CASE("Akoun-Yonnet: far field equals the dipole-dipole force", "[oracle][AY][dipole]") {
    const Vector3d m(0, 0, M1T * 1e-6);  // 1 cm^3 at 1 T
    for (double f : {10.0, 20.0}) {
        const Vector3d c2 = Vector3d(0.2, 0.1, 1).normalized() * f * 0.01;
        const Vector3d F = oracle::akounYonnetForce(cm3, Vector3d::Zero(), cm3, c2, 1, 1);
        const Vector3d Fd = oracle::dipoleForce(m, c2, m, Vector3d::Zero());
        CAPTURE(f, relDiff(F, Fd));
        // cubes: next term ~ (a/r)^4 (measured 8.0e-5 at 10 edges, 5.0e-6 at 20)
        CHECK(relDiff(F, Fd) < (f == 10.0 ? 2e-4 : 1.5e-5));
    }
}

// ---------------------------------------------------------------------------------
// chargeQuadrature.hpp
// ---------------------------------------------------------------------------------

TEST_CASE("charge quadrature equals Akoun-Yonnet (gaps, offsets, overlap)", "[oracle][quadrature][AY]") {
    const Cuboid c1{Vector3d::Zero(), Vector3d(0.005, 0.005, 0.005), Vector3d(0, 0, M1T)};
    SECTION("coaxial gap table") {
        for (double gap : {0.2e-3, 0.5e-3, 2e-3, 10e-3, 50e-3}) {
            const Vector3d c2(0, 0, 0.01 + gap);
            const Cuboid t{c2, c1.halfSize, c1.M};
            // panels of 0.5 mm x 8 points resolve the edge layer of width ~gap
            const oracle::Wrench w = oracle::chargeQuadratureWrench(c1, t, c2, 20, 8);
            const Vector3d F = oracle::akounYonnetForce(cm3, Vector3d::Zero(), cm3, c2, 1, 1);
            CAPTURE(gap, relDiff(w.force, F));
            // independent methods; measured 1.2e-9 at 0.2 mm (panels 2.5x the gap),
            // <= 3e-11 at the other gaps
            CHECK(relDiff(w.force, F) < 1e-8);
        }
    }
    SECTION("lateral offsets, near contact and overlapping") {
        const Vector3d centres[] = {Vector3d(0.003, 0.001, 0.0105), Vector3d(0.004, 0.002, 0.0102),
                                    Vector3d(0, 0, 0.005),          Vector3d(0.002, 0.003, 0.004),
                                    Vector3d(0.002, -0.001, -0.006)};
        for (const Vector3d& c2 : centres) {
            const Cuboid t{c2, c1.halfSize, c1.M};
            const oracle::Wrench w = oracle::chargeQuadratureWrench(c1, t, c2, 40, 8);
            const Vector3d F = oracle::akounYonnetForce(cm3, Vector3d::Zero(), cm3, c2, 1, 1);
            CAPTURE(c2.transpose(), F.transpose(), relDiff(w.force, F));
            // measured <= 3e-13 with 40 panels (0.25 mm) per face
            CHECK(relDiff(w.force, F) < 1e-9);
        }
    }
    SECTION("exact contact with a lateral offset: both give the mean of the limits") {
        const Vector3d c2(0.003, 0.001, 0.01);  // touching faces, offset (3, 1) mm
        const Cuboid t{c2, c1.halfSize, c1.M};
        // 0.25 mm panels: the source edges in the contact plane fall on panel boundaries
        const oracle::Wrench w = oracle::chargeQuadratureWrench(c1, t, c2, 40, 8);
        const Vector3d F = oracle::akounYonnetForce(cm3, Vector3d::Zero(), cm3, c2, 1, 1);
        CAPTURE(F.transpose(), w.force.transpose());
        // first-order convergence here (log-singular tangential H along the in-plane
        // source edges; measured 4.9e-4 with 40 panels); a one-sided convention on either
        // side would differ by O(1) (the contact jump)
        CHECK(relDiff(w.force, F) < 1e-3);
    }
    SECTION("the 1984 geometry (different box shapes, J = 0.38 T)") {
        const Vector3d s1(0.020, 0.012, 0.006), s2(0.012, 0.020, 0.006);
        const Cuboid a{Vector3d::Zero(), s1 / 2, Vector3d(0, 0, 0.38 / mu0)};
        for (double d : {0.0, 4.0, 10.0, 20.0}) {
            const Vector3d c2((-4 + d) * 1e-3, -4e-3, 8e-3);
            const Cuboid b{c2, s2 / 2, a.M};
            const oracle::Wrench w = oracle::chargeQuadratureWrench(a, b, c2, 10, 8);
            const Vector3d F = oracle::akounYonnetForce(s1, Vector3d::Zero(), s2, c2, 0.38, 0.38);
            CAPTURE(d, relDiff(w.force, F));
            CHECK(relDiff(w.force, F) < 1e-9);  // measured <= 6e-13
        }
    }
}

TEST_CASE("charge quadrature: the reference forces and torques", "[oracle][quadrature]") {
    SECTION("Janssen: 40x40x20 mm, 1.3 T, offset (20, 0, 30) mm") {
        const double M = 1.3 / mu0;
        const Cuboid a{Vector3d::Zero(), Vector3d(0.02, 0.02, 0.01), Vector3d(0, 0, M)};
        const Cuboid b{Vector3d(0.02, 0, 0.03), a.halfSize, a.M};
        const oracle::Wrench w = oracle::chargeQuadratureWrench(a, b, b.centre, 8, 8);
        CAPTURE(w.force.transpose(), w.torque.transpose());
        // references quoted to 6-7 significant digits (measured 0.4228294, -98.32961, -105.21147)
        CHECK(relDiff(w.torque.y(), 0.422829) < 2e-6);
        CHECK(relDiff(w.force.x(), -98.3296) < 1e-6);
        CHECK(relDiff(w.force.z(), -105.2115) < 1e-6);
        // y components vanish by mirror symmetry (quadrature rounding)
        CHECK(std::abs(w.force.y()) < 1e-10);
        CHECK(std::abs(w.torque.x()) + std::abs(w.torque.z()) < 1e-12);
    }
    SECTION("1 cm cubes, upper cube at (5, 0, 12) mm") {
        const Cuboid a{Vector3d::Zero(), Vector3d(0.005, 0.005, 0.005), Vector3d(0, 0, M1T)};
        const Cuboid b{Vector3d(0.005, 0, 0.012), a.halfSize, a.M};
        const oracle::Wrench w = oracle::chargeQuadratureWrench(a, b, b.centre, 10, 8);
        CAPTURE(w.force.transpose(), w.torque.transpose());
        // references quoted to 4-5 digits: half a unit of the last one
        CHECK(std::abs(w.force.x() - -6.586) < 0.5e-3);
        CHECK(std::abs(w.force.z() - -7.904) < 0.5e-3);
        CHECK(std::abs(w.torque.y() - 0.019754) < 0.5e-6);
        // and the force agrees with Akoun-Yonnet (independent closed form)
        CHECK(relDiff(w.force, oracle::akounYonnetForce(cm3, Vector3d::Zero(), cm3, b.centre, 1, 1)) < 1e-9);
    }
}

TEST_CASE("charge quadrature: force = -grad U, torque = -dU/dtheta (rotated target)",
          "[oracle][quadrature]") {
    // source: rotated box with oblique M; target: rotated box, oblique M, a few mm away
    Cuboid src{Vector3d::Zero(), Vector3d(0.006, 0.004, 0.003), Vector3d(0.2, 0.3, 0.9) * M1T};
    src.R = Eigen::AngleAxisd(0.3, Vector3d(0, 1, 1).normalized()).toRotationMatrix();
    Cuboid tgt{Vector3d(0.004, -0.002, 0.013), Vector3d(0.004, 0.003, 0.002),
               Vector3d(-0.4, 0.5, 0.7) * M1T};
    tgt.R = Eigen::AngleAxisd(0.5, Vector3d(1, -1, 2).normalized()).toRotationMatrix();
    // smooth integrand (separated boxes): 4 panels x 8 points is converged far below
    // the finite-difference tolerances used here
    const oracle::Wrench w = oracle::chargeQuadratureWrench(src, tgt, tgt.centre, 4, 8);
    auto energy = [&](const Cuboid& t) { return oracle::chargeInteractionEnergy(src, t, 3, 8); };
    const double h = 1e-6, th = 1e-4;  // central differences: O(h^2) ~ 1e-8 relative
    for (int j = 0; j < 3; ++j) {
        Vector3d e = Vector3d::Zero();
        e[j] = 1;
        Cuboid p = tgt, m = tgt;
        p.centre += h * e;
        m.centre -= h * e;
        const double fd = -(energy(p) - energy(m)) / (2 * h);
        CAPTURE(j, w.force[j], fd);
        // FD truncation + quadrature (measured <= 8e-9)
        CHECK(std::abs(w.force[j] - fd) < 1e-7 * w.force.norm());
        // rigid rotation about the target centre: R and M (body-fixed) both turn
        const Eigen::Matrix3d Rp = Eigen::AngleAxisd(th, e).toRotationMatrix();
        const Eigen::Matrix3d Rm = Eigen::AngleAxisd(-th, e).toRotationMatrix();
        p = tgt;
        m = tgt;
        p.R = Rp * tgt.R;
        p.M = Rp * tgt.M;
        m.R = Rm * tgt.R;
        m.M = Rm * tgt.M;
        const double fdT = -(energy(p) - energy(m)) / (2 * th);
        CAPTURE(w.torque[j], fdT);
        // FD truncation + quadrature (measured <= 5e-10)
        CHECK(std::abs(w.torque[j] - fdT) < 1e-7 * w.torque.norm());
    }
    // the volume couple int mu0 M2 x H1 dV is as large as the torque itself here
    // (measured 1.05x), so the energy check above really rules out adding it
    CHECK(volumeCouple(src, tgt, 3, 8).norm() > 0.1 * w.torque.norm());
    // in a nearly uniform far field the torque tends to m x B (dipole limit)
    Cuboid far = tgt;
    far.centre = Vector3d(0.3, -0.2, 0.5);
    const oracle::Wrench wf = oracle::chargeQuadratureWrench(src, far, far.centre, 2, 6);
    const Vector3d m2 = far.M * 8 * far.halfSize.prod();
    // finite-size corrections ~ (size/r)^2 at 0.6 m for 1 cm boxes (measured 1.2e-5)
    CHECK(relDiff(wf.torque, Vector3d(m2.cross(oracle::cuboidB(src, far.centre)))) < 1e-4);
}
