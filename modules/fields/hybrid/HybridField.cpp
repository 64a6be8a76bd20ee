// Hybrid field evaluator (paper Sec. 5, Algorithm 1): per pair of bodies, the accurate
// near-field model (MBM) when they are close, the cheap far-field model (EDM) otherwise,
// and one dipole-dipole interaction for pairs much farther apart than their size.
//
//   field:
//     type: hybrid
//     near: {type: MBM, quadrature: {type: gauss, n: 10}}
//     far:  {type: EDM, n: 2}
//     switch: {type: boundingSphere, threshold: 1.0}
//     dipoleRatio: 8
//
// Keys: kDoc at the registration below (magFoam -doc hybrid).
//
// The switch (per pair; R1, R2 bounding radii about the centres of mass c1, c2):
//   boundingSphere  gap = |c1 - c2| - R1 - R2, the distance between the bounding
//                   spheres (negative when they overlap).
//   gjk             gap = distance between the convex hulls of the two bodies' world
//                   vertices (GJK, Gjk.hpp; 0 when they intersect). The hull lies in
//                   the bounding sphere, so GJK runs only when the bounding-sphere gap
//                   is already below the threshold; it catches elongated bodies whose
//                   bounding spheres overlap while the bodies are far apart.
//   near when gap < threshold * max(R1, R2), else far.
// Reading of the paper (docs/physics.md#hybrid-switch): Sec. 5 says both "greater than
// the bounding sphere radius -> EDM" and "greater ..., i.e. close -> MBM". We take,
// as docs/physics.md#hybrid-switch does, the gap between the bounding spheres below one bounding radius
// as "close" (MBM); the other literal reading (far apart -> MBM) contradicts the
// section's own rationale and Fig. 5 (EDM is accurate only far apart). threshold is
// that radius factor; the radius is the larger of the two bodies'.
//
// evaluate() at points: the near model for points within (threshold + 1) * R of the
// source's COM (a point is a target of radius 0), the far model elsewhere.
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
// reach, k R with k = max(dipoleRatio, 1 + threshold), or with dipoleTolerance the
// reach that bounds the error estimate by it (dipoleReachFor, DipoleFarField.hpp:
// ~5 R for cubes at 1e-3, much more for elongated bodies, whose dipole error decays
// only as d^-2); k >= 1 + threshold keeps every dipole pair far by the switch. A pair
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
// (atomics, all threads), dipole pairs too, and logged at debug level per pair;
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
        s.reportUnused();
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
        if (isDipolePair(farFieldBody(source, dipoleReach(source)), farFieldBody(target, dipoleReach(target)))) {
            dipolePairs_.fetch_add(1, std::memory_order_relaxed);
            spdlog::debug("hybrid: '{}' -> '{}': dipole pair", source.name, target.name);
            Wrench w =
                dipolePairWrench(source.magneticMoment(), target.magneticMoment(), target.position - source.position);
            w.fieldIntegral = dipoleFieldIntegral(source, target);
            return w;
        }
        const double distance = (target.position - source.position).norm();
        const double gap = this->gap(source, target, distance);
        const double Rs = source.shape->boundingRadius, Rt = target.shape->boundingRadius;
        const bool isNear = gap < threshold_ * std::max(Rs, Rt);
        (isNear ? nearPairs_ : farPairs_).fetch_add(1, std::memory_order_relaxed);
        spdlog::debug("hybrid: '{}' -> '{}': {} gap {:g} m -> {}", source.name, target.name, switchName_, gap,
                      isNear ? "near" : "far");
        return (isNear ? *near_ : *far_).interaction(source, target);
    }

    // The tier interaction() takes: a dipole pair's energy -m_t . B_s(c_t)
    // gives V_t B_s(c_t); near and far pairs ask their evaluator.
    Vec3 fieldIntegral(const Body& source, const Body& target) const override {
        if (isDipolePair(farFieldBody(source, dipoleReach(source)), farFieldBody(target, dipoleReach(target))))
            return dipoleFieldIntegral(source, target);
        const double distance = (target.position - source.position).norm();
        const double Rs = source.shape->boundingRadius, Rt = target.shape->boundingRadius;
        const bool isNear = gap(source, target, distance) < threshold_ * std::max(Rs, Rt);
        return (isNear ? *near_ : *far_).fieldIntegral(source, target);
    }

    // The near tier's promise; the far tiers' errors fall with distance (dipoleTolerance).
    double forceTolerance() const override { return std::max(near_->forceTolerance(), dipoleTolerance_); }

    std::string describe() const override {
        std::ostringstream os;
        os << "hybrid (switch " << switchName_ << ", threshold " << threshold_;
        if (dipoleTolerance_ > 0)
            os << ", dipoleTolerance " << dipoleTolerance_;
        else
            os << ", dipoleRatio " << dipoleRatio_;
        os << ", dipole sum " << farField_.describe() << "; near: " << near_->describe() << "; far: " << far_->describe()
           << ")";
        return os.str();
    }

    FieldStats stats() const override {
        FieldStats s;
        s.add("dipolePairs", dipolePairs_);
        s.add("nearPairs", nearPairs_);
        s.add("farPairs", farPairs_);
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
        for (const auto& [a, b] : nearPairs(tier, skipFixedPairs)) pairs.add(active[a], active[b]);
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
    // k = max(dipoleRatio, 1 + threshold): such a pair is also far by the switch
    // (gap >= k (Rs + Rt) - Rs - Rt >= threshold max(Rs, Rt), and the GJK gap is
    // never below the bounding-sphere gap).
    double dipoleReach(const Body& b) const {
        const double R = b.shape->boundingRadius;
        if (dipoleTolerance_ > 0) return std::max(dipoleReachFor(*b.shape, dipoleTolerance_), (1.0 + threshold_) * R);
        if (dipoleRatio_ <= 0) return std::numeric_limits<double>::infinity();
        return std::max(dipoleRatio_, 1.0 + threshold_) * R;
    }

    // Decisions so far (pairs).
    std::uint64_t nearCount() const { return nearPairs_; }
    std::uint64_t farCount() const { return farPairs_; }

private:
    // V_t B_s(c_t) of the source's point dipole (docs/physics.md#dipoles-and-edm).
    static Vec3 dipoleFieldIntegral(const Body& source, const Body& target) {
        const Vec3 m = source.magneticMoment(), r = target.position - source.position;
        const double d = r.norm();
        const Vec3 u = r / d;
        return target.shape->volume * (mu0 / (4 * std::numbers::pi)) * (3 * u.dot(m) * u - m) / (d * d * d);
    }

    // Gap between the two bodies as the switch measures it (m); `distance`
    // between their centres of mass.
    double gap(const Body& a, const Body& b, double distance) const {
        const double Ra = a.shape->boundingRadius, Rb = b.shape->boundingRadius;
        const double sphereGap = distance - Ra - Rb;
        if (!gjk_) return sphereGap;
        // The hull distance is >= the bounding-sphere gap: GJK only when it matters.
        if (sphereGap >= threshold_ * std::max(Ra, Rb)) return sphereGap;
        const gjk::PlacedPoints pa{a.shape->mesh.vertices, a.orientation.toRotationMatrix(), a.position};
        const gjk::PlacedPoints pb{b.shape->mesh.vertices, b.orientation.toRotationMatrix(), b.position};
        return gjk::distance(pa, pb);
    }

    std::unique_ptr<FieldEvaluator> near_, far_;
    std::string switchName_ = "boundingSphere";
    bool gjk_ = false;
    double threshold_ = 1.0;
    double dipoleRatio_ = 8.0;
    double dipoleTolerance_ = 0;  // > 0: reach from the shapes (dipoleReachFor)
    FarFieldSettings farField_;   // how the dipole pairs are summed
    mutable std::atomic<std::uint64_t> nearPairs_{0}, farPairs_{0}, dipolePairs_{0}, nearPoints_{0}, farPoints_{0},
        multipoleSums_{0}, dipoleSumNanoseconds_{0};
};

const TypeDoc kDoc{
    "Hybrid (paper Sec. 5): MBM for near pairs, EDM for far ones, dipoles for distant ones.\n"
    "Per pair, the near model when the bodies are close, the far model otherwise, and one\n"
    "dipole pair for pairs much farther apart than their size (summed directly or by a fast\n"
    "multipole method).",
    {"type: hybrid\nnear: {type: MBM, quadrature: {type: gauss, n: 10}}\nfar: {type: EDM, n: 2}\n"
     "switch: {type: boundingSphere, threshold: 1.0}\ndipoleRatio: 8\n"
     "farField: {method: auto, multipoleAbove: 3000, order: 12, theta: 0.5, leafSize: 64, directPairs: 300}\n",
     "type: hybrid\ndipoleTolerance: 1e-3\n"},
    {{"near", "-", "the near-field model, any field evaluator (default {type: MBM})"},
     {"far", "-", "the far-field model, any field evaluator (default {type: EDM, n: 2})"},
     {"switch", "-", "which pairs are near"},
     {"switch.type", "-",
      "boundingSphere: gap between the bounding spheres; gjk: distance between the convex hulls"},
     {"switch.threshold", "-", "near when gap < threshold * max(R1, R2), >= 0"},
     {"dipoleRatio", "-",
      "pairs with centre distance > dipoleRatio (R1 + R2) are one dipole pair; 0: no dipole tier"},
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
