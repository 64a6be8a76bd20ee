// Hybrid field evaluator (paper Sec. 5, Algorithm 1): per pair of bodies, the accurate
// near-field model (MBM) when they are close, the cheap far-field model (EDM) otherwise,
// and one dipole-dipole interaction for pairs much farther apart than their size.
//
//   field:
//     type: hybrid
//     near: {type: MBM, quadrature: {type: gauss, n: 10}}
//     far:  {type: EDM, n: 2}
//     switch: {type: boundingSphere, threshold: 1.0, band: 0.25}
//     dipoleRatio: 8
//     dipoleBand: 0.25
//
// Keys: kDoc at the registration below (magFoam -doc hybrid).
//
// The switch (per pair; R1, R2 bounding radii about the centres of mass c1, c2):
//   boundingSphere  gap = |c1 - c2| - R1 - R2, the distance between the bounding
//                   spheres (negative when they overlap).
//   gjk             gap = distance between the convex hulls of the two bodies' world
//                   vertices (GJK, Gjk.hpp; 0 when they intersect). The hull lies in
//                   the bounding sphere, so GJK runs only when the bounding-sphere gap
//                   is already below the band's end; it catches elongated bodies whose
//                   bounding spheres overlap while the bodies are far apart.
//   near when gap < threshold * max(R1, R2), far when gap >= (threshold + band) * max(R1, R2),
//   both blended between (below).
// Reading of the paper (docs/physics.md#hybrid-switch): Sec. 5 says both "greater than
// the bounding sphere radius -> EDM" and "greater ..., i.e. close -> MBM". We take,
// as docs/physics.md#hybrid-switch does, the gap between the bounding spheres below one bounding radius
// as "close" (MBM); the other literal reading (far apart -> MBM) contradicts the
// section's own rationale and Fig. 5 (EDM is accurate only far apart). threshold is
// that radius factor; the radius is the larger of the two bodies'.
//
// evaluate() at points: the near model for points within (threshold + 1) * R of the
// source's COM (a point is a target of radius 0), the far model elsewhere (fields at
// points carry no energy: no band).
//
// Blended switch (docs/physics.md#hybrid-switch). A sharp switch changes the pair energy
// by U_far - U_near where a pair changes tier, and the bodies keep the kinetic energy
// they had: each crossing adds or removes that difference (a permanent rod slung past
// a cube gained 2.6e-3 of its peak kinetic energy, tests/test_flyBy.cpp: EDM n = 2's
// energy is 1.9 % and 2.9 % off MBM's where it enters and leaves, turned). Over a band
// of the switch measure the pair's energy is U = (1 - s) U_near + s U_far, s =
// smootherstep of the position in the band, and its wrench is the exact gradient of U:
//   F = (1 - s) F_near + s F_far - (U_far - U_near) grad s,
// the torque alike (plus -(U_far - U_near) ds/dtheta with GJK, whose gap depends on the
// orientation; the bounding-sphere gap and the dipole band's centre distance do not).
// Then the total energy is a function of the state, and a symplectic integrator keeps
// it (the drift that remains is the near model's quadrature: 8e-7 for that rod, as
// with MBM alone). Averaging the forces alone would not do: it is not a gradient (2e-3
// for the rod). The same between the far model and the dipole tier, over centre
// distances ((1 - dipoleBand) D, D], D = reach_s + reach_t, inside the tier's reach so
// that the bulk dipole sums and their pair search stay as they are. Pairs outside the
// bands are evaluated exactly as before, bit for bit; a band pair pays for both tiers
// (a near/far band pair ~ a near pair: MBM + EDM). The price of the blend is the
// weight's term: where the far model's energy is off by dU, the force is off by up to
// ~1.9 dU / width more (two 1 cm cubes coaxial: 0.32 % at most in the default band
// against 0.12 % at the sharp switch; band 1: 0.044 %).
//
// Defaults: the paper's (near MBM, far EDM n = 2, bounding spheres, one radius).
// Measured on the paper's Fig. 4 pair (two 1 cm cubes, Br = 1 T, coaxial) against
// Akoun-Yonnet (test_hybrid.cpp checks < 0.5 % at every gap of Figs. 4/5): the switch
// puts face gaps d < 1.598 cm on MBM (gauss n = 10: 3.5e-4 at d = 0.02 cm, 1.5e-5 at
// 0.1 cm, < 1e-9 from 0.5 cm on) and d >= 1.598 cm on EDM n = 2, which overestimates
// the attraction by 0.12 % at d = 1.6 cm, 0.072 % at 2 cm, 0.005 % at 5 cm (n = 3
// would give 0.024 % at 1.6 cm at a much higher cost; timings: cases/benchmarks).
// A lower threshold trades accuracy for speed: 0.31 switches
// these cubes at d = 1 cm (EDM n = 2: 0.30 % off), 0 at d = 0.73 cm.
//
// Dipole tier (the broad phase of large scenes: most pairs are far). Each body has a
// reach, k R with k = max(dipoleRatio, 1 + threshold + band), or with dipoleTolerance the
// reach that bounds the error estimate by it (dipoleReachFor, DipoleFarField.hpp:
// ~5 R for cubes at 1e-3, much more for elongated bodies, whose dipole error decays
// only as d^-2); k >= 1 + threshold + band keeps every dipole pair far by the switch,
// past its band. A pair
// with centre distance d > reach_s + reach_t interacts as two point dipoles m = M V
// at the centres of mass, r = c_t - c_s (corrected Eq. 5, Eq. 6; dipolePairWrench):
//   F = 3 mu0/(4 pi d^5) [(ms.r) mt + (mt.r) ms + (ms.mt) r - 5 (ms.r)(mt.r) r / d^2]
//   torque = mt x B_s(c_t), mechanicalTorque = 0 (the dipole sits at the COM),
//   energy = -mt . B_s(c_t).
// addWrenches() finds the other pairs with a grid and sums the dipole pairs in bulk
// (DipoleFarField.hpp; or by the fast multipole method, DipoleMultipole.hpp, as
// `farField:` says); interaction() gives the same wrench for a pair called directly.
// Momentum and angular momentum are conserved to rounding.
// Error bound. The field of a uniformly magnetized body is -M . grad of the Newtonian
// potential of its volume, so its multipoles beyond the dipole come from the volume's
// moments about its centroid (= COM, uniform density): the first moment vanishes, so
// the first correction is the second moment (quadrupole of the volume), relative
// O((R/d)^2); by the same expansion of B over the target's volume, the target adds
// O((R/d)^2). Bodies whose second moment is isotropic (cubes, regular polyhedra,
// spheres) lose that term too (and the third moment vanishes for centrally symmetric
// ones), so for cubes the error is O((R/d)^4); for a sphere only the icosphere's
// deviation from a ball remains (its EDM is one dipole anyway). A body whose
// magnetization or density were not uniform would have a dipole off the COM and an
// O(R/d) error; that is not the case here. Measured (test_farField.cpp, relative
// force error against MBM, tilted bodies magnetized off-axis):
//   d / (R1 + R2)               2        4        8        16
//   two 1 cm cubes           3.2e-3   2.0e-4   1.3e-5   8.0e-7    (d^-4)
//   3 x 1 x 1 cm bar, cube   1.2e-1   2.9e-2   7.3e-3   1.8e-3    (d^-2)
// (torques alike); over random orientations, against the scale of a dipole pair's
// force, the estimate of DipoleFarField.hpp bounds them. At the default ratio 8 the
// cubes' error is far below that of a scene's near pairs (whose forces are larger by
// (d_far / d_near)^4), an elongated body's is not: dipoleTolerance puts each shape's
// pairs where its own error allows.
//
// Counters: near/far decisions for pairs and for evaluate() points are counted
// (atomics, all threads), dipole pairs and the pairs of each band too (nearPairs,
// farPairs, dipolePairs count pairs of one tier alone), logged at debug level per pair;
// stats() reports them (with the near and far models' own under "near."/"far.").
// Thread-safe: the members are read-only after construction apart from the atomic
// counters.
#include "Gjk.hpp"
#include "DipoleFarField.hpp"
#include "DipoleMultipole.hpp"

#include <magFoam/FieldEvaluator.hpp>

#include <spdlog/spdlog.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <sstream>
#include <vector>

namespace mag {

namespace {

// Default band widths (docs/physics.md#hybrid-switch).
constexpr double kDefaultBand = 0.25, kDefaultDipoleBand = 0.25;

class HybridField final : public FieldEvaluator {
public:
    explicit HybridField(const Dict& d) {
        near_ = d.has("near") ? FieldEvaluator::New(d.sub("near"))
                              : FieldEvaluator::New(Dict::fromString("type: MBM\n", "hybrid default near"));
        far_ = d.has("far") ? FieldEvaluator::New(d.sub("far"))
                            : FieldEvaluator::New(Dict::fromString("type: EDM\nn: 2\n", "hybrid default far"));
        const Dict s = d.subOrEmpty("switch");
        switchName_ = s.getWord("type", {"boundingSphere", "gjk"}, "boundingSphere");
        gjk_ = switchName_ == "gjk";
        threshold_ = s.get<double>("threshold", 1.0);
        if (!(threshold_ >= 0)) s.fail("threshold", "hybrid switch threshold must be >= 0 (a factor of the bounding radius)");
        band_ = s.get<double>("band", kDefaultBand);
        if (!(band_ >= 0))
            s.fail("band", "hybrid switch band must be >= 0 (a factor of the bounding radius; 0: a sharp switch)");
        s.reportUnused();
        dipoleBand_ = d.get<double>("dipoleBand", kDefaultDipoleBand);
        if (!(dipoleBand_ >= 0 && dipoleBand_ < 1))
            d.fail("dipoleBand",
                   "hybrid dipoleBand must be in [0, 1) (a fraction of the dipole reach; 0: a sharp switch)");
        if (d.has("dipoleTolerance")) {
            if (d.has("dipoleRatio"))
                d.fail("dipoleRatio", "give either dipoleRatio or dipoleTolerance, not both");
            dipoleTolerance_ = d.get<double>("dipoleTolerance");
            if (!(dipoleTolerance_ > 0 && dipoleTolerance_ < 1))
                d.fail("dipoleTolerance", "hybrid dipoleTolerance must be in (0, 1) (the dipole pairs' error bound)");
            dipoleRatio_ = 0;
        } else {
            dipoleRatio_ = d.get<double>("dipoleRatio", 8.0);
            if (!(dipoleRatio_ >= 0))
                d.fail("dipoleRatio",
                       "hybrid dipoleRatio must be >= 0 (a factor of R1 + R2; 0 turns the dipole tier off)");
        }
        farField_ = FarFieldSettings::read(d.subOrEmpty("farField"));
    }

    void evaluate(const Body& source, std::span<const Vec3> points, std::span<Vec3> B, std::span<Vec3> A,
                  std::span<Vec3> H) const override {
        const double reach = (threshold_ + 1.0) * source.shape->boundingRadius;
        // Split the points, evaluate each group with its model, scatter back.
        std::vector<std::size_t> index[2];
        for (std::size_t p = 0; p < points.size(); ++p)
            index[(points[p] - source.position).norm() < reach ? 0 : 1].push_back(p);
        nearPoints_ += index[0].size();
        farPoints_ += index[1].size();
        for (int g = 0; g < 2; ++g) {
            const auto& ix = index[g];
            if (ix.empty()) continue;
            if (ix.size() == points.size()) {
                (g == 0 ? *near_ : *far_).evaluate(source, points, B, A, H);
                return;
            }
            std::vector<Vec3> p(ix.size()), b(ix.size()), a(A.empty() ? 0 : ix.size()), h(H.empty() ? 0 : ix.size());
            for (std::size_t i = 0; i < ix.size(); ++i) p[i] = points[ix[i]];
            (g == 0 ? *near_ : *far_).evaluate(source, p, b, a, h);
            for (std::size_t i = 0; i < ix.size(); ++i) {
                B[ix[i]] = b[i];
                if (!A.empty()) A[ix[i]] = a[i];
                if (!H.empty()) H[ix[i]] = h[i];
            }
        }
    }

    Wrench interaction(const Body& source, const Body& target) const override {
        const FarFieldBody fs = farFieldBody(source, dipoleReach(source));
        const FarFieldBody ft = farFieldBody(target, dipoleReach(target));
        if (isDipolePair(fs, ft)) {
            dipolePairs_.fetch_add(1, std::memory_order_relaxed);
            spdlog::debug("hybrid: '{}' -> '{}': dipole pair", source.name, target.name);
            return dipoleWrench(source, target);
        }
        const Vec3 r = target.position - source.position;
        const double distance = r.norm();
        const Switch sw = nearWeight(source, target, distance, true);
        spdlog::debug("hybrid: '{}' -> '{}': {} gap {:g} m -> {}", source.name, target.name, switchName_, sw.gap,
                      sw.isNear ? "near" : sw.inBand ? "near/far band" : "far");
        if (sw.isNear) {
            nearPairs_.fetch_add(1, std::memory_order_relaxed);
            return near_->interaction(source, target);
        }
        if (!sw.inBand) return farTier(source, target, fs, ft, r, distance, true);
        // Both tiers, U = (1 - s) U_near + s U_far (docs/physics.md#hybrid-switch).
        nearBandPairs_.fetch_add(1, std::memory_order_relaxed);
        return blend(near_->interaction(source, target), farTier(source, target, fs, ft, r, distance, false), sw);
    }

    // The tier interaction() takes, weighted alike (the weights depend on the pose
    // alone, not on M_t): a dipole pair's energy -m_t . B_s(c_t) gives V_t B_s(c_t);
    // near and far pairs ask their evaluator.
    Vec3 fieldIntegral(const Body& source, const Body& target) const override {
        return byTier(source, target, &FieldEvaluator::fieldIntegral, &dipoleFieldIntegral);
    }

    // fieldIntegral() per unit source magnetization, tier by tier as there.
    Mat3 fieldIntegralMap(const Body& source, const Body& target) const override {
        return byTier(source, target, &FieldEvaluator::fieldIntegralMap, &dipoleFieldIntegralMap);
    }

    // The near tier's promise; the far tiers' errors fall with distance (dipoleTolerance).
    double forceTolerance() const override { return std::max(near_->forceTolerance(), dipoleTolerance_); }

    std::string describe() const override {
        std::ostringstream os;
        os << "hybrid (switch " << switchName_ << ", threshold " << threshold_ << ", band " << band_;
        if (dipoleTolerance_ > 0)
            os << ", dipoleTolerance " << dipoleTolerance_;
        else
            os << ", dipoleRatio " << dipoleRatio_;
        os << ", dipoleBand " << dipoleBand_;
        os << ", dipole sum " << farField_.describe() << "; near: " << near_->describe() << "; far: " << far_->describe()
           << ")";
        return os.str();
    }

    FieldStats stats() const override {
        FieldStats s;
        s.add("dipolePairs", dipolePairs_);
        s.add("nearPairs", nearPairs_);
        s.add("farPairs", farPairs_);
        s.add("nearBandPairs", nearBandPairs_);      // near/far blends (the counts above are one tier alone)
        s.add("dipoleBandPairs", dipoleBandPairs_);  // far/dipole blends
        s.add("nearPoints", nearPoints_);
        s.add("farPoints", farPoints_);
        s.add("multipoleSums", multipoleSums_);             // addWrenches calls that used the multipole sum
        s.add("dipoleSumNanoseconds", dipoleSumNanoseconds_);  // wall time in the dipole sums
        s.add("near.", near_->stats());
        s.add("far.", far_->stats());
        return s;
    }

    // The dipole pairs in bulk, the others (found by a grid, not by visiting
    // every pair) one by one through interaction().
    void addWrenches(std::span<const Body> bodies, std::span<const std::size_t> active, bool skipFixedPairs,
                     std::span<Wrench> out) const override {
        std::vector<FarFieldBody> tier;
        tier.reserve(active.size());
        for (std::size_t i : active) tier.push_back(farFieldBody(bodies[i], dipoleReach(bodies[i])));
        PairChunks pairs(*this, bodies, out);
        for (const auto& [a, b] : nearPairs(tier, skipFixedPairs))
            if (!sameRigidBody(bodies[active[a]], bodies[active[b]])) pairs.add(active[a], active[b]);
        pairs.finish();
        std::vector<Wrench> far(tier.size());
        const auto start = std::chrono::steady_clock::now();
        const std::uint64_t n = addDipoleFarField(tier, skipFixedPairs, far, farField_);
        dipoleSumNanoseconds_.fetch_add(
            std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - start).count(),
            std::memory_order_relaxed);
        if (farField_.usesMultipole(tier.size())) multipoleSums_.fetch_add(1, std::memory_order_relaxed);
        if (n) {
            dipolePairs_.fetch_add(n, std::memory_order_relaxed);
            for (std::size_t a = 0; a < tier.size(); ++a) out[active[a]] += far[a];
        }
    }

    // Dipole pairs have centre distance > reach_s + reach_t, reach = k R with
    // k = max(dipoleRatio, 1 + threshold + band): such a pair is also far by the
    // switch, past its band (gap >= k (Rs + Rt) - Rs - Rt >= (threshold + band)
    // max(Rs, Rt), and the GJK gap is never below the bounding-sphere gap), so the
    // bulk dipole sum never meets a pair the near tier should weigh in.
    double dipoleReach(const Body& b) const {
        const double R = b.shape->boundingRadius;
        const double least = 1.0 + threshold_ + band_;
        if (dipoleTolerance_ > 0) return std::max(dipoleReachFor(*b.shape, dipoleTolerance_), least * R);
        if (dipoleRatio_ <= 0) return std::numeric_limits<double>::infinity();
        return std::max(dipoleRatio_, least) * R;
    }

    // Decisions so far (pairs).
    std::uint64_t nearCount() const { return nearPairs_; }
    std::uint64_t farCount() const { return farPairs_; }

private:
    // V_t B_s(c_t) of the source's point dipole (docs/physics.md#dipoles-and-edm).
    // A quantity that is linear in the target's magnetization from the tiers
    // interaction() would take (fieldIntegral, fieldIntegralMap): `of` of the
    // near or far evaluator, `dipole` for dipole pairs, blended in the bands.
    template <class T>
    T byTier(const Body& source, const Body& target, T (FieldEvaluator::*of)(const Body&, const Body&) const,
             T (*dipole)(const Body&, const Body&)) const {
        const FarFieldBody fs = farFieldBody(source, dipoleReach(source));
        const FarFieldBody ft = farFieldBody(target, dipoleReach(target));
        if (isDipolePair(fs, ft)) return dipole(source, target);
        const double distance = (target.position - source.position).norm();
        const Switch sw = nearWeight(source, target, distance, false);
        if (sw.isNear) return ((*near_).*of)(source, target);
        auto farPart = [&] {
            const Switch dw = dipoleWeight(fs, ft, Vec3::Zero(), distance);
            if (!dw.inBand) return ((*far_).*of)(source, target);
            return T((1 - dw.s) * ((*far_).*of)(source, target) + dw.s * dipole(source, target));
        };
        if (!sw.inBand) return farPart();
        return T((1 - sw.s) * ((*near_).*of)(source, target) + sw.s * farPart());
    }

    // dipoleFieldIntegral per unit world magnetization of the source (m = V_s M).
    static Mat3 dipoleFieldIntegralMap(const Body& source, const Body& target) {
        const Vec3 r = target.position - source.position;
        const double d = r.norm();
        const Vec3 u = r / d;
        return target.shape->volume * source.shape->volume * (mu0 / (4 * std::numbers::pi)) *
               (3 * u * u.transpose() - Mat3::Identity()) / (d * d * d);
    }

    static Vec3 dipoleFieldIntegral(const Body& source, const Body& target) {
        const Vec3 m = source.magneticMoment(), r = target.position - source.position;
        const double d = r.norm();
        const Vec3 u = r / d;
        return target.shape->volume * (mu0 / (4 * std::numbers::pi)) * (3 * u.dot(m) * u - m) / (d * d * d);
    }

    // Where a pair stands against one boundary: s, the weight of the farther tier
    // (0: the nearer tier alone, 1: the farther alone, between: in the band), and
    // the gradient of s with respect to the target's position and rotation (the
    // source's follow from translation and rotation invariance: addPairWrenches).
    struct Switch {
        double s = 0, gap = 0;
        bool isNear = false, inBand = false;
        Vec3 dPosition = Vec3::Zero(), dRotation = Vec3::Zero();
    };

    // The blend weight over a band, x in [0, 1]: smootherstep 6x^5 - 15x^4 + 10x^3,
    // C2 at both ends, so that the blended force stays C1 where a pair enters or
    // leaves the band (the integrator's error stays that of a smooth potential).
    static double smoothStep(double x) { return x <= 0 ? 0 : x >= 1 ? 1 : x * x * x * (10 + x * (6 * x - 15)); }
    static double smoothStepSlope(double x) { return x <= 0 || x >= 1 ? 0 : 30 * x * x * (1 - x) * (1 - x); }

    // Near/far: near when gap < threshold max(Rs, Rt) (unchanged), far when gap >=
    // (threshold + band) max(Rs, Rt), blended between. `distance` between the centres;
    // withGradient: the gradient of s too (GJK's closest points).
    Switch nearWeight(const Body& a, const Body& b, double distance, bool withGradient) const {
        const double Ra = a.shape->boundingRadius, Rb = b.shape->boundingRadius, R = std::max(Ra, Rb);
        const double sphereGap = distance - Ra - Rb, g0 = threshold_ * R, width = band_ * R;
        Switch w;
        w.gap = sphereGap;
        // The hull distance is >= the bounding-sphere gap: GJK only when it matters.
        gjk::Closest hull;
        if (gjk_ && sphereGap < g0 + width) {
            const gjk::PlacedPoints pa{a.shape->mesh.vertices, a.orientation.toRotationMatrix(), a.position};
            const gjk::PlacedPoints pb{b.shape->mesh.vertices, b.orientation.toRotationMatrix(), b.position};
            hull = gjk::closest(pa, pb);
            w.gap = hull.distance;
        }
        if (w.gap < g0) {
            w.isNear = true;
            return w;
        }
        if (!(w.gap < g0 + width)) {
            w.s = 1;
            return w;
        }
        w.inBand = true;
        const double x = (w.gap - g0) / width;
        w.s = smoothStep(x);
        if (!withGradient) return w;
        const double slope = smoothStepSlope(x) / width;  // ds / dgap
        if (!gjk_) {
            // d gap / d c_b = the unit vector from a's centre to b's; no rotation.
            if (distance > 0) w.dPosition = slope / distance * (b.position - a.position);
        } else if (w.gap > 0) {
            // d gap / d c_b = n, the unit vector from a's closest point to b's; turning
            // b about its centre moves its closest point: d gap / d theta = (p_b - c_b) x n.
            // Where the closest features are not unique (parallel faces) the distance
            // has a kink in the rotation and this is one of its one-sided slopes.
            const Vec3 n = (hull.onB - hull.onA) / w.gap;
            w.dPosition = slope * n;
            w.dRotation = slope * (hull.onB - b.position).cross(n);
        }
        return w;
    }

    // Far/dipole: the dipole alone beyond reach_s + reach_t (isDipolePair), the far
    // model alone within (1 - dipoleBand) of it, blended between (centre distance only).
    Switch dipoleWeight(const FarFieldBody& a, const FarFieldBody& b, const Vec3& r, double distance) const {
        Switch w;
        const double reach = a.reach + b.reach, inner = (1 - dipoleBand_) * reach;
        if (!(dipoleBand_ > 0 && distance > inner)) return w;  // an infinite reach: never
        w.inBand = true;
        const double width = reach - inner, x = (distance - inner) / width;
        w.s = smoothStep(x);
        if (distance > 0) w.dPosition = smoothStepSlope(x) / (width * distance) * r;
        return w;
    }

    // The far tier of a pair that is not a dipole pair: the far model, blended with
    // the dipole pair in the dipole band. `pure`: the pair is far alone (counted as
    // such), not the far side of a near/far blend.
    Wrench farTier(const Body& source, const Body& target, const FarFieldBody& fs, const FarFieldBody& ft,
                   const Vec3& r, double distance, bool pure) const {
        const Switch dw = dipoleWeight(fs, ft, r, distance);
        if (!dw.inBand) {
            if (pure) farPairs_.fetch_add(1, std::memory_order_relaxed);
            return far_->interaction(source, target);
        }
        dipoleBandPairs_.fetch_add(1, std::memory_order_relaxed);
        return blend(far_->interaction(source, target), dipoleWrench(source, target), dw);
    }

    // The wrench of U = (1 - s) U_a + s U_b with s = s(pose): the exact gradient of
    // the blended energy, F = (1 - s) F_a + s F_b - (U_b - U_a) grad s, and the same
    // for the rotation. The extra force acts at the target's centre; for the
    // bounding-sphere and dipole bands it is central, so the source's reaction
    // (addPairWrenches) keeps angular momentum with no extra torque.
    static Wrench blend(const Wrench& a, const Wrench& b, const Switch& w) {
        const double t = 1 - w.s, s = w.s, dU = b.energy - a.energy;
        Wrench out;
        out.force = t * a.force + s * b.force - dU * w.dPosition;
        out.torque = t * a.torque + s * b.torque;
        out.mechanicalTorque = t * a.mechanicalTorque + s * b.mechanicalTorque - dU * w.dRotation;
        out.energy = t * a.energy + s * b.energy;
        out.ownEnergy = t * a.ownEnergy + s * b.ownEnergy;
        out.fieldIntegral = t * a.fieldIntegral + s * b.fieldIntegral;
        return out;
    }

    // The dipole pair (corrected Eq. 5, Eq. 6) with its field integral.
    static Wrench dipoleWrench(const Body& source, const Body& target) {
        Wrench w =
            dipolePairWrench(source.magneticMoment(), target.magneticMoment(), target.position - source.position);
        w.fieldIntegral = dipoleFieldIntegral(source, target);
        return w;
    }

    std::unique_ptr<FieldEvaluator> near_, far_;
    std::string switchName_ = "boundingSphere";
    bool gjk_ = false;
    double threshold_ = 1.0;
    double band_ = kDefaultBand;              // near/far band, a factor of max(Rs, Rt)
    double dipoleBand_ = kDefaultDipoleBand;  // far/dipole band, a fraction of reach_s + reach_t
    double dipoleRatio_ = 8.0;
    double dipoleTolerance_ = 0;  // > 0: reach from the shapes (dipoleReachFor)
    FarFieldSettings farField_;   // how the dipole pairs are summed
    mutable std::atomic<std::uint64_t> nearPairs_{0}, farPairs_{0}, dipolePairs_{0}, nearPoints_{0}, farPoints_{0},
        multipoleSums_{0}, dipoleSumNanoseconds_{0}, nearBandPairs_{0}, dipoleBandPairs_{0};
};

const TypeDoc kDoc{
    "Hybrid (paper Sec. 5): MBM for near pairs, EDM for far ones, dipoles for distant ones.\n"
    "Per pair, the near model when the bodies are close, the far model otherwise, and one\n"
    "dipole pair for pairs much farther apart than their size (summed directly or by a fast\n"
    "multipole method).",
    {"type: hybrid\nnear: {type: MBM, quadrature: {type: gauss, n: 10}}\nfar: {type: EDM, n: 2}\n"
     "switch: {type: boundingSphere, threshold: 1.0, band: 0.25}\ndipoleRatio: 8\ndipoleBand: 0.25\n"
     "farField: {method: auto, multipoleAbove: 3000, order: 12, theta: 0.5, leafSize: 64, directPairs: 300}\n",
     "type: hybrid\ndipoleTolerance: 1e-3\n"},
    {{"near", "-", "the near-field model, any field evaluator (default {type: MBM})"},
     {"far", "-", "the far-field model, any field evaluator (default {type: EDM, n: 2})"},
     {"switch", "-", "which pairs are near"},
     {"switch.type", "-",
      "boundingSphere: gap between the bounding spheres; gjk: distance between the convex hulls"},
     {"switch.threshold", "-", "near when gap < threshold * max(R1, R2), >= 0"},
     {"switch.band", "-",
      "far from gap (threshold + band) * max(R1, R2) on; between, the energies of both are\n"
      "blended and the wrench is their blend's exact gradient (energy is conserved through the\n"
      "switch), >= 0; 0: a sharp switch"},
     {"dipoleRatio", "-",
      "pairs with centre distance > dipoleRatio (R1 + R2) are one dipole pair; 0: no dipole tier"},
     {"dipoleBand", "-",
      "pairs with centre distance in ((1 - dipoleBand) D, D], D the dipole reach of the pair,\n"
      "blend the far model's energy with the dipole pair's, [0, 1); 0: a sharp switch"},
     {"dipoleTolerance", "-",
      "instead of dipoleRatio: each shape's reach from its moments, so that a dipole pair's\n"
      "relative error stays below this, (0, 1)"},
     {"farField", "-", "how the dipole pairs are summed"},
     {"farField.method", "-", "direct (O(N^2)), multipole (O(N)) or auto (multipole above multipoleAbove bodies)"},
     {"farField.multipoleAbove", "-", "auto: bodies taking part above which the multipole sum is used"},
     {"farField.order", "-", "multipole expansion degree, 2..30"},
     {"farField.theta", "-", "multipole opening angle, (0, 1)"},
     {"farField.leafSize", "-", "bodies per leaf cell of the multipole tree"},
     {"farField.directPairs", "-", "cell pairs with at most this many body pairs are summed directly"}}};

const FieldEvaluator::Add<HybridField> addHybrid("hybrid", kDoc);

} // namespace

} // namespace mag
