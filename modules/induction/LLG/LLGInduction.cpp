// Induced magnetization of soft bodies by Landau-Lifshitz-Gilbert relaxation
// (paper Sec. 4.3, Eqs. 2, 19, 20; Algorithm 1 lines 3-12; docs/physics.md#induction):
//
//   induction: {type: LLG, tolerance: 1e-6, maxIterations: 500}
//
// Keys: kDoc at the registration below (magFoam -doc LLG).
//
// Per soft material (constant/materials.yaml, Material.hpp):
//   steel: {model: soft, k: 5.0, Js: 2.0, density: 7850, alpha: 0.5}
// k: D = I/k (Eq. 19), Js: saturation polarization, Ms = Js/mu0; alpha: damping
// (Eq. 20, default 0.5). Permanent bodies are sources only; non-soft bodies are never
// changed.
//
// Model. A soft body carries two sub-magnetizations M1, M2 of length Ms; its
// magnetization is M = (M1 + M2)/2, so 0 <= |M| <= Ms. Both feel
//   H_eff = B/mu0 - D M,   D = I/k                                            (Eq. 19)
// where B is the field of every OTHER magnetized body at the body's centre of mass
// (the paper's; `average` below takes it averaged over the body instead),
// and follow LLG in pseudo-time,
//   dM_i/dt = -gamma/(1 + alpha^2) [M_i x H_eff + (alpha/Ms) M_i x (M_i x H_eff)] (Eq. 20)
// (Eq. 20 as printed has alpha without 1/Ms, which is not dimensionless for M_i in A/m;
// the 1/Ms is the standard Gilbert form). Equilibria that are stable: H_eff = 0, i.e.
// M = k B/mu0 (Eq. 2) while k |B|/mu0 < Ms; otherwise M1 = M2 = Ms B/|B| (saturated
// along B). Every other equilibrium has a sub-magnetization antiparallel to H_eff and is
// unstable. The model has one more degree of freedom than M: below saturation the
// pair may turn about M freely (M1, M2 are not unique; only M is reported).
//
// Algorithm (one converge() call = Algorithm 1 lines 3-12 for one time step):
//  - Fields, once per call. B is linear in a source's magnetization (true of every
//    model of a uniformly magnetized body: MBM, EDM, hybrid), so the evaluator is
//    asked once per source: every magnetized non-soft body at all soft bodies' centres,
//    and every soft body with the three unit body-frame magnetizations at the other
//    soft bodies' centres (a 3x3 map per soft pair). A sweep then costs 3x3 products
//    instead of evaluator calls; the result is what re-evaluating every sweep gives.
//    Cost: (N_permanent + 3 N_soft) evaluate() calls of N_soft points each.
//  - Sweep: every soft body in turn takes one step with B from the others' newest
//    magnetizations (Gauss-Seidel; all soft bodies iterate together because they
//    magnetize each other). Converged when, in one sweep, no magnetization M moved
//    by tolerance * Ms or more; after maxIterations sweeps the report says
//    converged = false and names the bodies still moving (the solver warns).
//  - Step (per body, frozen B). In units of m_i = M_i/Ms and h = H_eff/Ms, Eq. 20 reads
//      dm_i/ds = f_i = Q(m_i) h,   Q(m) h = -m x h + alpha (h - m (m.h)),
//    with pseudo-time s = gamma/(1 + alpha^2) Ms t; its fastest linear rate is
//    rate = sqrt(1 + alpha^2) max(1/k, |h|). Two candidate steps, both moving each m_i
//    by a ROTATION (angle |x_i| about m_i x x_i, so |M_i| = Ms exactly):
//    (1) linearly implicit (Rosenbrock) Euler in the 4-dimensional tangent space of
//        the two spheres, x = (I - s J)^-1 s f, J the Jacobian of f including the stiff
//        self term -M/k; s starts at relaxation / rate and is halved until no m_i turns
//        by more than maxRotation and the body's energy e = -M.B/mu0 + |M|^2/(2k) does
//        not increase (Gilbert damping lowers e, precession keeps it). With the default
//        relaxation this is a damped Newton step to the equilibrium: quadratic
//        convergence (linear at the knee, where the equilibrium is degenerate);
//    (2) explicit Euler, x = s f with s = maxRotation / max|f_i|, i.e. the step set by
//        gamma |H_eff| so the fastest m_i turns by maxRotation: Eq. 20's own direction,
//        which leaves unstable regions quickly where Newton steps would creep.
//    The candidate with the lower energy is taken (never above the start). The fixed
//    points are those of Eq. 20 whatever the step; alpha changes only the path.
//  - Unstable equilibria are exactly the configurations where M cannot change to first
//    order: (i) a pair antiparallel along H_eff (M = 0, M1 parallel to H_eff) and (ii) a
//    collinear pair (|M| = Ms) with H_eff against M. There f = 0 and no step moves, and
//    Newton steps are drawn to them. While k |H_eff| > tolerance * Ms (not converged),
//    a pair within 0.01 rad of (i) is turned, keeping M, so that its axis is normal to
//    H_eff, and one within 0.01 rad of (ii) is split by +-0.2 rad about M (lowers e).
//    Neither touches a stable state; the move counts as a change (no false convergence).
//  - Initial state: the pair stored from the previous call (kept in the body frame by
//    body name, so it turns with the body) when the body's magnetizationBody is still
//    Ms (M1 + M2)/2; otherwise derived from magnetizationBody:
//      M1,2 = M +- sqrt(Ms^2 - |M|^2) p,   p unit, normal to M and to B
//    (a soft body starts at M = 0: demagnetized, M1 = -M2 = Ms p normal to B; a given
//    |M| > Ms is clipped to Ms).
//  - Restart: the stored pairs are the model's state (InductionModel::writeState):
//    written at every write time as <time>/induction.yaml,
//      type: LLG
//      bodies:
//        - {name: nut, m1: [x, y, z], m2: [x, y, z]}   # unit, body frame, %.17g
//    and read back at a restart, so that the restarted run starts every soft body
//    from the same pair as the uninterrupted one (bit for bit; without the file
//    the pairs are derived from the written magnetization as above).
//  - average: none | permanent | all (docs/physics.md#induction). The centre
//    field is the body's mean only for a sphere, so the paper's induced force is
//    not the gradient of an energy and a clip beside a magnet gains energy. With
//    `permanent`, B from permanent bodies and the applied field is their field
//    integral as the pair energy sees it (FieldEvaluator::fieldIntegral, the
//    demag model's I / V: one call per such pair, with the target's samples);
//    with `all` the soft-soft maps too (FieldEvaluator::fieldIntegralMap, one
//    geometric pass per soft pair with MBM's regular rules: Fig. 8 1.8x the
//    cost of a step, 4.4x with three wrench calls). M then minimizes -M.I + mu0 V |M|^2/(2k)
//    (Eq. 19's energy) over |M| <= Ms, stationary for the energy the forces
//    derive from, and sceneEnergy counts that energy.
//  - Pseudo-time: only gamma dt enters Eq. 20 and the step is chosen in units of s, so
//    gamma changes neither the result nor the iterations; the debug log line of each
//    call gives the pseudo-time reached in seconds, t = s (1 + alpha^2)/(gamma Ms).
//  - A soft body whose field is not finite (e.g. a centre on a source's edge with some
//    evaluators) keeps its magnetization and is reported unconverged.
//
// Measured (test_llg.cpp; one sphere in a uniform field, k = 5, alpha = 0.5; starts:
// demagnetized, antiparallel to B at |M| = Ms/2 and Ms, saturated along B, normal to
// B, oblique, |M| = 3 Ms): for k|B|/(mu0 Ms) in [0, 0.999] and [1.001, 1000] every
// start converges in 1-15 sweeps with |M - M_Eq.2| <= 2e-13 Ms; at the knee
// k|B|/mu0 = Ms in 39 sweeps (error 8e-11 Ms). Previous step's state in the same field:
// 1 sweep; field changed by 2 %: 3 sweeps; previous states that are unstable in the new
// field (saturated pair, field dropped or reversed): 5-8 sweeps. relaxation: 1 takes
// 40 sweeps where the default takes 5. Five soft balls chained on a 1 cm magnet (MBM):
// 6-27 sweeps, about 6 ms per call (1280-triangle balls; nearly all of it the 65 field
// points of 16 evaluate() calls). alpha = 0.05 .. 5 changes the sweeps (5-14), not M.
#include <magFoam/AppliedField.hpp>
#include <magFoam/Error.hpp>
#include <magFoam/FieldEvaluator.hpp>
#include <magFoam/InductionModel.hpp>
#include <magFoam/ResultsWriter.hpp>
#include <magFoam/SoftFieldIntegrals.hpp>

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <ostream>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace mag {

namespace {

using Mat4 = Eigen::Matrix4d;
using Vec4 = Eigen::Vector4d;
using Mat32 = Eigen::Matrix<double, 3, 2>;

// Saddle detection cone and the split angle (Unstable equilibria above).
constexpr double kSaddleCone = 0.01;  // rad
constexpr double kSplitAngle = 0.2;   // rad
// Step halvings before a step is given up (s shrinks by 2^-60: a zero step).
constexpr int kMaxHalvings = 60;

Mat3 crossMatrix(const Vec3& v) {
    Mat3 m;
    m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
    return m;
}

// Rotate the unit vector m by `angle` about `axis` (Rodrigues), renormalized.
Vec3 rotate(const Vec3& m, const Vec3& axis, double angle) {
    const double n = axis.norm();
    if (n == 0 || angle == 0) return m;
    const Vec3 a = axis / n;
    const double c = std::cos(angle), s = std::sin(angle);
    return (m * c + a.cross(m) * s + a * a.dot(m) * (1 - c)).normalized();
}

// A unit vector normal to u (|u| = 1) and, where possible, to w.
Vec3 normalTo(const Vec3& u, const Vec3& w) {
    const Vec3 p = u.cross(w);
    if (p.norm() > 1e-9 * std::max(1.0, w.norm())) return p.normalized();
    return u.unitOrthogonal();
}

// The pair of unit sub-magnetizations with mean mu (|mu| <= 1), split along p:
// m1,2 = mu +- sqrt(1 - |mu|^2) p, p unit and normal to mu (made so from `hint`).
void decompose(const Vec3& mu, const Vec3& hint, Vec3& m1, Vec3& m2) {
    const double n = mu.norm();
    if (n >= 1) {
        m1 = m2 = mu / n;
        return;
    }
    Vec3 p = n > 0 ? Vec3(hint - hint.dot(mu) / (n * n) * mu) : hint;
    if (!(p.norm() > 1e-12 * std::max(1.0, hint.norm()))) p = n > 0 ? mu.unitOrthogonal() : Vec3(Vec3::UnitX());
    p.normalize();
    const double s = std::sqrt(std::max(0.0, 1 - n * n));
    m1 = (mu + s * p).normalized();
    m2 = (mu - s * p).normalized();
}

// The initial pair for magnetization M (world, A/m) in a field along b: split
// normal to both M and b (for M = 0: demagnetized, M1 = -M2 normal to b).
void initialPair(const Vec3& M, double Ms, const Vec3& b, Vec3& m1, Vec3& m2) {
    Vec3 mu = M / Ms;
    if (mu.norm() > 1) mu.normalize();
    Vec3 hint;
    if (mu.norm() > 1e-12)
        hint = normalTo(mu.normalized(), b);
    else
        hint = b.norm() > 0 ? b.normalized().unitOrthogonal() : Vec3(Vec3::UnitX());
    decompose(mu, hint, m1, m2);
}

// The body's energy per volume in units of mu0 Ms^2: e = -mu.b + |mu|^2/(2k).
double energy(const Vec3& m1, const Vec3& m2, const Vec3& b, double k) {
    const Vec3 mu = 0.5 * (m1 + m2);
    return -mu.dot(b) + mu.squaredNorm() / (2 * k);
}

// Q(m) h = -m x h + alpha (h - m (m.h)): Eq. 20 as dm/ds = Q(m) h.
Mat3 llgOperator(const Vec3& m, double alpha) {
    return -crossMatrix(m) + alpha * (Mat3::Identity() - m * m.transpose());
}

struct StepSettings {
    double tolerance, relaxation, maxRotation;
};

struct StepResult {
    double change = 0;  // |M new - M old| / Ms
    double s = 0;       // pseudo-time step taken (units 1/(gamma' Ms))
};

// One step of one body's pair in the frozen reduced field b = B/Js (= B/(mu0 Ms)):
// repair of unstable equilibria, then the lower-energy of the implicit and the
// explicit Eq. 20 step (see the header). Returns the change of the pair.
StepResult llgStep(Vec3& m1, Vec3& m2, const Vec3& b, double k, double alpha, const StepSettings& set) {
    const Vec3 old1 = m1, old2 = m2;
    Vec3 m[2] = {m1, m2};
    Vec3 h = b - 0.5 * (m[0] + m[1]) / k;

    // Unstable equilibria (i), (ii): only while H_eff is not negligible.
    const double hn = h.norm();
    if (k * hn > set.tolerance) {
        const Vec3 hu = h / hn;
        const double c12 = m[0].dot(m[1]);
        const Vec3 mu = 0.5 * (m[0] + m[1]);
        if (c12 < -std::cos(kSaddleCone)) {
            // (i) antiparallel pair along H_eff: turn its axis normal to H_eff.
            const Vec3 axis = (m[0] - m[1]).normalized();
            if (std::abs(axis.dot(hu)) > std::cos(kSaddleCone)) decompose(mu, normalTo(hu, mu), m[0], m[1]);
        } else if (c12 > std::cos(kSaddleCone) && mu.dot(h) < 0) {
            // (ii) collinear pair against H_eff: split it (|M| shrinks, e drops).
            const Vec3 mh = mu.normalized();
            const Vec3 across = h - h.dot(mh) * mh;
            decompose(mu * std::cos(kSplitAngle), across.norm() > 1e-9 * hn ? across : mh.unitOrthogonal(), m[0],
                      m[1]);
        }
        h = b - 0.5 * (m[0] + m[1]) / k;
    }

    // Tangent bases E_i (3x2) of the two spheres, f = E^T Q h, J = E^T (dF/dm) E.
    Mat32 E[2];
    for (int i = 0; i < 2; ++i) {
        const Vec3 e1 = m[i].unitOrthogonal();
        E[i].col(0) = e1;
        E[i].col(1) = m[i].cross(e1);
    }
    Mat4 J;
    Vec4 f;
    for (int i = 0; i < 2; ++i) {
        const Mat3 Q = llgOperator(m[i], alpha);
        f.segment<2>(2 * i) = E[i].transpose() * (Q * h);
        // d(Q(m) h)/dm at fixed h, and dh/dm_j = -I/(2k) through M = Ms (m1 + m2)/2.
        const Mat3 D = crossMatrix(h) - alpha * (m[i].dot(h) * Mat3::Identity() + m[i] * h.transpose());
        for (int j = 0; j < 2; ++j) {
            Mat3 Jij = -Q / (2 * k);
            if (i == j) Jij += D;
            J.block<2, 2>(2 * i, 2 * j) = E[i].transpose() * Jij * E[j];
        }
    }

    const Vec3 m0[2] = {m[0], m[1]};

    // Implicit candidate: s from relaxation / rate, halved until the rotation is
    // within the trust region and the energy does not increase.
    const double rate = std::sqrt(1 + alpha * alpha) * std::max(1.0 / k, h.norm());
    const double e0 = energy(m[0], m[1], b, k);
    const double eSlack = 1e-14 * (b.norm() + 1.0 / k);
    double s = set.relaxation / rate;
    Vec3 next[2] = {m[0], m[1]};
    bool accepted = false;
    for (int tries = 0; tries < kMaxHalvings && !accepted; ++tries, s *= 0.5) {
        const Vec4 x = (Mat4::Identity() - s * J).partialPivLu().solve(s * f);
        if (!x.allFinite() || std::max(x.segment<2>(0).norm(), x.segment<2>(2).norm()) > set.maxRotation) continue;
        for (int i = 0; i < 2; ++i) {
            const Vec3 d = E[i] * x.segment<2>(2 * i);
            next[i] = rotate(m[i], m[i].cross(d), d.norm());
        }
        accepted = energy(next[0], next[1], b, k) <= e0 + eSlack;
    }
    StepResult r;
    double eBest = e0 + eSlack;
    if (accepted) {
        m[0] = next[0], m[1] = next[1];
        r.s = 2 * s;  // undo the loop's last halving
        eBest = energy(m[0], m[1], b, k);
    }

    // Explicit candidate: Eq. 20's own direction, rotated by maxRotation; taken when
    // it ends lower (it leaves unstable regions much faster than the implicit step).
    const double fMax = std::max(f.segment<2>(0).norm(), f.segment<2>(2).norm());
    if (fMax > 0) {
        const double se = set.maxRotation / fMax;
        Vec3 expl[2];
        for (int i = 0; i < 2; ++i) {
            const Vec3 d = se * (E[i] * f.segment<2>(2 * i));
            expl[i] = rotate(m0[i], m0[i].cross(d), d.norm());
        }
        if (energy(expl[0], expl[1], b, k) < eBest) {
            m[0] = expl[0], m[1] = expl[1];
            r.s = se;
        }
    }
    m1 = m[0], m2 = m[1];
    // Convergence is judged on M = Ms (m1 + m2)/2, the physical magnetization (the
    // pair itself is not unique below saturation). Near the knee the pair is almost
    // collinear and |M| = Ms cos(theta/2): a change of M by eps moves the pair by
    // ~sqrt(8 eps), so a test on the pair would need the square of the tolerance.
    r.change = 0.5 * ((m1 + m2) - (old1 + old2)).norm();
    return r;
}

// Rotations q v q* = v + w U + q_v x U, U = 2 q_v x v (Eigen's form), written out
// with each multiply-add fused as written. Two fusings, the ones these call sites
// have always had: results then do not depend on how the compiler inlines Eigen's
// q * v here (it fuses differently inline and out of line).
Vec3 rotate(const Quat& q, const Vec3& v) {
    const double qx = q.x(), qy = q.y(), qz = q.z(), qw = q.w();
    const double ux = 2 * std::fma(-qz, v.y(), qy * v.z()), uy = 2 * std::fma(-qx, v.z(), qz * v.x()),
                 uz = 2 * std::fma(qx, v.y(), -(qy * v.x()));
    const double cx = std::fma(qy, uz, -(qz * uy)), cy = std::fma(qz, ux, -(qx * uz)), cz = std::fma(qx, uy, -(qy * ux));
    return {std::fma(qw, ux, v.x()) + cx, std::fma(qw, uy, v.y()) + cy, cz + std::fma(qw, uz, v.z())};
}
// The body's magnetization in the world frame.
Vec3 worldMagnetization(const Body& b) {
    const Vec3& v = b.magnetizationBody;
    const double qx = b.orientation.x(), qy = b.orientation.y(), qz = b.orientation.z(), qw = b.orientation.w();
    const double ux = 2 * std::fma(qy, v.z(), -(qz * v.y())), uy = 2 * std::fma(qz, v.x(), -(qx * v.z())),
                 uz = 2 * std::fma(qx, v.y(), -(qy * v.x()));
    const double cx = std::fma(qy, uz, -(qz * uy)), cy = std::fma(qz, ux, -(qx * uz)), cz = std::fma(qx, uy, -(qy * ux));
    return {std::fma(qw, ux, v.x()) + cx, std::fma(qw, uy, v.y()) + cy, std::fma(qw, uz, v.z()) + cz};
}

class LLGInduction final : public InductionModel {
public:
    explicit LLGInduction(const Dict& d) {
        set_.tolerance = d.get<double>("tolerance", 1e-6);
        if (!(set_.tolerance > 0 && set_.tolerance <= 1e-2))
            d.fail("tolerance", "LLG tolerance must be in (0, 0.01] (change of a magnetization per sweep, relative to Ms)");
        maxIterations_ = d.get<int>("maxIterations", 500);
        if (maxIterations_ < 1) d.fail("maxIterations", "LLG maxIterations must be >= 1");
        set_.relaxation = d.get<double>("relaxation", 1e9);
        if (!(set_.relaxation > 0)) d.fail("relaxation", "LLG relaxation must be > 0 (pseudo-time step factor)");
        set_.maxRotation = d.get<double>("maxRotation", 1.0);
        if (!(set_.maxRotation > 0 && set_.maxRotation <= pi / 2))
            d.fail("maxRotation", "LLG maxRotation must be in (0, pi/2] rad");
        gamma_ = d.get<double>("gamma", mu0 * 1.76086e11);
        if (!(gamma_ > 0)) d.fail("gamma", "LLG gamma must be > 0 (gyromagnetic ratio, m/(A s))");
        const std::string average = d.getWord("average", {"none", "permanent", "all"}, "none");
        average_ = average == "all" ? Average::all : average == "permanent" ? Average::permanent : Average::none;
    }

    using InductionModel::converge;
    InductionReport converge(std::vector<Body>& bodies, const FieldEvaluator& field,
                             const AppliedField& applied) override {
        InductionReport report;
        std::vector<std::size_t> soft;
        for (std::size_t i = 0; i < bodies.size(); ++i)
            if (bodies[i].soft()) soft.push_back(i);
        const std::size_t n = soft.size();
        if (n == 0) return report;
        const std::vector<SoftParams> par = softParams(bodies, soft);

        // The permanent part and the soft-to-soft maps: at the soft bodies'
        // centres (the paper's), or averaged as the energy sees them.
        std::vector<Vec3> Bfixed;
        std::vector<Mat3> G; // G[b*n + a]: B at b per M_a (world)
        if (average_ == Average::none) {
            std::vector<Vec3> centres(n);
            for (std::size_t a = 0; a < n; ++a) centres[a] = bodies[soft[a]].position;
            Bfixed = permanentField(bodies, field, applied, centres);
            G = softMaps(bodies, soft, field);
        } else {
            SoftFieldIntegrals averaged = softFieldIntegrals(bodies, soft, field, applied, average_ == Average::all);
            Bfixed = std::move(averaged.fixed);
            G = average_ == Average::all ? std::move(averaged.coupling) : softMaps(bodies, soft, field);
        }

        // Pairs (world frame) and state: stored pair, else from magnetizationBody.
        std::vector<Vec3> m1(n), m2(n), M(n);
        std::vector<double> Js(n);
        for (std::size_t a = 0; a < n; ++a) {
            const Body& body = bodies[soft[a]];
            Js[a] = par[a].Js;
            M[a] = worldMagnetization(body);
        }
        for (std::size_t b = 0; b < n; ++b) {
            const Body& body = bodies[soft[b]];
            const double Ms = Js[b] / mu0;
            const auto it = state_.find(body.name);
            if (it != state_.end() && it->second.m1.allFinite() && it->second.m2.allFinite() &&
                (Ms * 0.5 * (it->second.m1 + it->second.m2) - body.magnetizationBody).norm() <= 1e-9 * Ms) {
                m1[b] = rotate(body.orientation, it->second.m1);
                m2[b] = rotate(body.orientation, it->second.m2);
            } else {
                initialPair(M[b], Ms, fieldAt(b, Bfixed, G, M), m1[b], m2[b]);
                M[b] = Ms * 0.5 * (m1[b] + m2[b]);
            }
        }

        // Sweeps (Gauss-Seidel): each body steps in the field of the others' newest M.
        std::vector<double> change(n, 0.0), pseudoTime(n, 0.0);
        std::vector<bool> finiteField(n, true);
        for (int it = 1; it <= maxIterations_; ++it) {
            report.iterations = it;
            double worst = 0;
            for (std::size_t b = 0; b < n; ++b) {
                const Vec3 B = fieldAt(b, Bfixed, G, M);
                const SoftParams& mat = par[b];
                finiteField[b] = B.allFinite();
                if (!finiteField[b]) {
                    change[b] = std::numeric_limits<double>::infinity();
                    continue;
                }
                const StepResult r = llgStep(m1[b], m2[b], B / Js[b], mat.k, mat.alpha, set_);
                M[b] = Js[b] / mu0 * 0.5 * (m1[b] + m2[b]);
                change[b] = r.change;
                pseudoTime[b] += r.s * (1 + mat.alpha * mat.alpha) / (gamma_ * Js[b] / mu0);
                worst = std::max(worst, r.change);
            }
            report.residual = worst;
            if (worst < set_.tolerance) break;
        }

        // Write back (body frame) and keep the pairs for the next call.
        std::set<std::string> present;
        for (std::size_t b = 0; b < n; ++b) {
            Body& body = bodies[soft[b]];
            present.insert(body.name);
            if (!finiteField[b]) {
                report.unconverged.push_back(body.name);
                continue;
            }
            const Quat toBody = body.orientation.conjugate();
            const Pair pair{rotate(toBody, m1[b]), rotate(toBody, m2[b])};
            body.magnetizationBody = Js[b] / mu0 * 0.5 * (pair.m1 + pair.m2);
            state_[body.name] = pair;
            if (!(change[b] < set_.tolerance)) report.unconverged.push_back(body.name);
        }
        for (auto it = state_.begin(); it != state_.end();)
            it = present.count(it->first) ? std::next(it) : state_.erase(it);
        report.converged = report.unconverged.empty();
        spdlog::debug("LLG: {} soft bodies, {} sweeps, residual {:.3g}, pseudo-time up to {:.3g} s{}", n,
                      report.iterations, report.residual, *std::max_element(pseudoTime.begin(), pseudoTime.end()),
                      report.converged ? "" : " (NOT converged)");
        return report;
    }

    std::string describe() const override {
        static const char* const averages[] = {"none: fields at the centres", "permanent: the permanent sources' "
                                               "and the applied field averaged, the soft bodies' at the centres",
                                               "all: fields averaged as the energy sees them"};
        char text[300];
        std::snprintf(text, sizeof text,
                      "LLG (tolerance %g, maxIterations %d, relaxation %g, maxRotation %g rad, gamma %g m/(A s), "
                      "average %s)",
                      set_.tolerance, maxIterations_, set_.relaxation, set_.maxRotation, gamma_,
                      averages[static_cast<int>(average_)]);
        return text;
    }

    // With averaged fields (average: permanent or all) LLG's equilibrium
    // minimizes e V mu0 Ms^2 = -M . I + mu0 V |M|^2 / (2k) (Eq. 19's energy)
    // for the field integral I the pair energies derive from, so the scene's
    // energy counts every pair once plus each soft body's own mu0 V |M|^2/(2k),
    // as demag does (docs/physics.md#energy). At the centre (the paper's), the
    // default count: the halved energy of a linear induced moment.
    double sceneEnergy(const std::vector<Body>& bodies, const std::vector<Wrench>& wrenches) const override {
        if (average_ == Average::none) return InductionModel::sceneEnergy(bodies, wrenches);
        double e = 0;
        for (const Wrench& w : wrenches) e += 0.5 * w.energy + w.ownEnergy;
        for (const Body& b : bodies)
            if (b.soft())
                e += mu0 * b.shape->volume * b.magnetizationBody.squaredNorm() / (2 * softParams(b).k);
        return e;
    }

    // The stored pairs, in the order of the bodies (Restart above).
    void writeState(std::ostream& os, const std::vector<Body>& bodies) const override {
        bool any = false;
        for (const Body& body : bodies) {
            const auto it = state_.find(body.name);
            if (it == state_.end()) continue;
            if (!any)
                os << "# LLG sub-magnetizations of the soft bodies: unit vectors, body frame\n"
                      "type: LLG\nbodies:\n";
            any = true;
            os << "  - {name: " << body.name << ", m1: " << formatExact(it->second.m1)
               << ", m2: " << formatExact(it->second.m2) << "}\n";
        }
    }

    void readState(const Dict& d, const std::vector<Body>& bodies) override {
        if (d.get<std::string>("type") != "LLG") {
            spdlog::warn("{}: induction state of type '{}', not LLG: ignored (the sub-magnetizations start from "
                         "the magnetizations)",
                         d.file(), d.get<std::string>("type"));
            return;
        }
        state_.clear();
        for (const Dict& b : d.list("bodies")) {
            const std::string name = b.get<std::string>("name");
            const bool known = std::any_of(bodies.begin(), bodies.end(),
                                           [&](const Body& x) { return x.name == name && x.soft(); });
            if (!known) b.fail("name", "no soft body '" + name + "' in constant/bodies.yaml");
            state_[name] = Pair{b.get<Vec3>("m1"), b.get<Vec3>("m2")};
            b.reportUnused();
        }
        d.reportUnused();
    }

private:
    // Sub-magnetization directions in the BODY frame (they turn with the body).
    struct Pair {
        Vec3 m1, m2;
    };

    // A soft material's keys as LLG reads them (Material::properties):
    //   k      required, > 0   induction control, D = I/k (Eq. 19)
    //   Js     required, > 0   saturation polarization mu0 Ms, T
    //   alpha  default 0.5     damping (Eq. 20), > 0
    // Any other key is an error naming it: it belongs to another induction model.
    struct SoftParams {
        double k = 0, Js = 0, alpha = 0.5;
    };
    [[gnu::noinline]] static std::vector<SoftParams> softParams(const std::vector<Body>& bodies,
                                                               const std::vector<std::size_t>& soft) {
        std::vector<SoftParams> out;
        for (std::size_t i : soft) out.push_back(softParams(bodies[i]));
        return out;
    }
    static SoftParams softParams(const Body& body) {
        const Material& m = body.material;
        static const std::vector<std::string> keys = {"k", "Js", "alpha"};
        for (const auto& [key, value] : m.properties)
            if (std::find(keys.begin(), keys.end(), key) == keys.end())
                m.fail(key, "LLG induction does not use soft-material key '" + key + "' (body '" + body.name +
                                "'); LLG reads k, Js and alpha");
        SoftParams p;
        p.k = m.property("k");
        p.Js = m.property("Js");
        p.alpha = m.property("alpha", 0.5);
        if (!(p.k > 0)) m.fail("k", "induction control k must be positive (LLG, body '" + body.name + "')");
        if (!(p.Js > 0)) m.fail("Js", "saturation polarization Js must be positive (tesla; body '" + body.name + "')");
        if (!(p.alpha > 0)) m.fail("alpha", "LLG damping alpha must be positive (body '" + body.name + "')");
        return p;
    }

    // B (world) of every magnetized non-soft body and of the applied field at the soft centres.
    static std::vector<Vec3> permanentField(const std::vector<Body>& bodies, const FieldEvaluator& field,
                                            const AppliedField& applied, const std::vector<Vec3>& centres) {
        std::vector<Vec3> total(centres.size(), Vec3::Zero()), B(centres.size());
        applied.add(centres, total);
        for (const Body& source : bodies) {
            if (source.soft() || source.magnetizationBody.squaredNorm() == 0) continue;
            field.evaluate(source, centres, B);
            for (std::size_t i = 0; i < centres.size(); ++i) total[i] += B[i];
        }
        return total;
    }

    // G[b*n + a] (world): B at soft body b's centre per unit world magnetization of
    // soft body a, from three evaluations with unit body-frame magnetizations.
    static std::vector<Mat3> softMaps(const std::vector<Body>& bodies, const std::vector<std::size_t>& soft,
                                      const FieldEvaluator& field) {
        const std::size_t n = soft.size();
        std::vector<Mat3> G(n * n, Mat3::Zero());
        if (n < 2) return G;
        std::vector<Vec3> points(n - 1), B(n - 1);
        for (std::size_t a = 0; a < n; ++a) {
            Body unit = bodies[soft[a]];
            for (std::size_t b = 0, j = 0; b < n; ++b)
                if (b != a) points[j++] = bodies[soft[b]].position;
            const Mat3 toBody = unit.orientation.conjugate().toRotationMatrix();
            std::vector<Mat3> perTarget(n - 1, Mat3::Zero());
            for (int c = 0; c < 3; ++c) {
                unit.magnetizationBody = Vec3::Unit(c);
                field.evaluate(unit, points, B);
                for (std::size_t j = 0; j < n - 1; ++j) perTarget[j].col(c) = B[j];
            }
            for (std::size_t b = 0, j = 0; b < n; ++b)
                if (b != a) G[b * n + a] = perTarget[j++] * toBody;
        }
        return G;
    }

    static Vec3 fieldAt(std::size_t b, const std::vector<Vec3>& Bfixed, const std::vector<Mat3>& G,
                        const std::vector<Vec3>& M) {
        const std::size_t n = Bfixed.size();
        Vec3 B = Bfixed[b];
        for (std::size_t a = 0; a < n; ++a)
            if (a != b) B += G[b * n + a] * M[a];
        return B;
    }

    enum class Average { none, permanent, all };
    StepSettings set_{};
    Average average_ = Average::none;
    int maxIterations_ = 500;
    double gamma_ = 0;
    std::map<std::string, Pair> state_;
};

const TypeDoc kDoc{
    "The paper's induction (Sec. 4.3): LLG relaxation of soft bodies' magnetization.\n"
    "Each soft body's magnetization relaxes by Landau-Lifshitz-Gilbert (Eqs. 19, 20) in\n"
    "pseudo-time to M = k B/mu0 (Eq. 2, saturating at Ms), with B the other bodies' field at\n"
    "its centre of mass, or averaged over it as the energy sees it (average). Materials:\n"
    "{model: soft, k, Js, density, alpha}.",
    {"type: LLG\ntolerance: 1e-6\nmaxIterations: 500\n"},
    {{"tolerance", "-",
      "converged when no body's magnetization changed by more than tolerance * Ms in the last\n"
      "sweep, (0, 0.01]"},
     {"maxIterations", "-", "sweeps before the step is reported unconverged, >= 1"},
     {"relaxation", "-",
      "largest pseudo-time step per sweep in units of the body's fastest relaxation time, > 0;\n"
      "1e6 and up: Newton-like (fast); about 1: close to the explicit path of Eq. 20 (slow)"},
     {"maxRotation", "rad", "largest rotation of a sub-magnetization in one sweep (trust region), (0, pi/2]"},
     {"gamma", "m/(A s)", "gyromagnetic ratio of Eq. 20 (mu0 * 1.76086e11); sets only the pseudo-time unit"},
     {"average", "-",
      "the field B each soft body relaxes in: none (the paper's: every source's field at the\n"
      "centre of mass), permanent (the permanent sources' and the applied field averaged over\n"
      "the body as the pair energies see them, the soft bodies' at the centre; about as cheap),\n"
      "all (every field averaged: the induced forces conserve energy; a 3x3 map per pair of\n"
      "soft bodies, one more pass of the pair with MBM's regular rules)"}}};

const InductionModel::Add<LLGInduction> addLLG("LLG", kDoc);

} // namespace

} // namespace mag
