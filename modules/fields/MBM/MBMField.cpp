// Magnetic Boundary Method field evaluator (paper Sec. 4):
//
//   field: {type: MBM, quadrature: {type: adaptive, tolerance: 1e-4}, overlap: charge}
//
// Keys: kDoc at the registration below (magFoam -doc MBM prints them with the
// defaults the constructor reads).
//
// A and B of the source are exact (Fabbri, Eqs. 9-15), evaluated in the
// source's body frame on the target's boundary samples moved there; only the
// boundary integrals of Eqs. 16-18 are sampled. Per-shape tables (edges,
// planar faces, samples) are built once and shared by all bodies of a shape.
// The adaptive rule places its samples per pair (they depend on where the
// source is); at contact it takes the one-sided limit from the target's
// interior, so touching magnets attract in every overlap model
// (docs/physics.md#adaptive-quadrature).
//
// Threads: interaction() and evaluate() may run concurrently (the shape cache
// is behind a mutex, scratch is per thread); interaction() splits the target's
// samples (gauss, regular) or elements (adaptive) into fixed blocks that run on
// the worker threads (Threads.hpp).
#include "AdaptiveQuadrature.hpp"
#include "InteractionWrench.hpp"
#include "PolyhedronField.hpp"
#include "PolyhedronTables.hpp"
#include "SurfaceQuadrature.hpp"

#include <magFoam/Error.hpp>
#include <magFoam/FieldEvaluator.hpp>
#include <magFoam/Threads.hpp>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <map>
#include <mutex>
#include <sstream>

namespace mag {

namespace {

// Samples per parallel block of interaction(): ~15 us of work for a cube
// (~0.5 us per sample), far above the cost of handing out a block.
constexpr std::size_t kSampleBlock = 32;

class MBMField final : public FieldEvaluator {
public:
    explicit MBMField(const Dict& d) {
        const Dict q = d.subOrEmpty("quadrature");
        ruleName_ = q.getWord("type", {"adaptive", "regular", "gauss"}, "adaptive");
        adaptive_ = ruleName_ == "adaptive";
        if (adaptive_) {
            adaptiveSettings_.tolerance = q.get<double>("tolerance", 1e-4);
            if (!(adaptiveSettings_.tolerance >= 1e-12 && adaptiveSettings_.tolerance <= 0.1))
                q.fail("tolerance", "adaptive tolerance must be 1e-12..0.1 (relative error per pair)");
            adaptiveSettings_.order = q.get<int>("order", 3);
            if (adaptiveSettings_.order < 1 || adaptiveSettings_.order > 12)
                q.fail("order", "adaptive order must be 1..12 (Gauss points per element side)");
            const double maxSamples = q.get<double>("maxSamples", 200000);
            if (!(maxSamples >= 100 && maxSamples <= 1e9))
                q.fail("maxSamples", "adaptive maxSamples must be 100..1e9 (samples per pair)");
            adaptiveSettings_.maxSamples = static_cast<std::size_t>(maxSamples);
        } else {
            rule_ = mbm::quadratureRuleFromName(ruleName_);
            n_ = q.get<int>("n", 10);
            if (n_ < 1 || n_ > 100) q.fail("n", "quadrature n must be 1..100 (points per face edge)");
        }
        formName_ = q.getWord("form", {"split", "surfaceCharge"}, "split");
        form_ = mbm::forceFormFromName(formName_);
        adaptiveSettings_.form = form_;
        q.reportUnused();
        overlapName_ = d.getWord("overlap", {"charge", "amperian", "exterior"}, "charge");
        overlap_ = mbm::overlapModelFromName(overlapName_);
        if (form_ == mbm::ForceForm::surfaceCharge && overlap_ == mbm::OverlapModel::amperian)
            q.fail("form", "form surfaceCharge needs overlap: charge or exterior (the amperian field B is not "
                           "the gradient of a potential; docs/physics.md#force-form)");
    }

    void evaluate(const Body& source, std::span<const Vec3> points, std::span<Vec3> B, std::span<Vec3> A,
                  std::span<Vec3> H) const override {
        const ShapeData& s = data(source.shape, source.name);
        const Mat3 R = source.orientation.toRotationMatrix();
        const std::size_t n = points.size();
        std::vector<Vec3> local(n), b(n), a(A.empty() ? 0 : n);
        std::vector<double> inside(H.empty() ? 0 : n);
        for (std::size_t i = 0; i < n; ++i) local[i] = R.transpose() * (points[i] - source.position);
        mbm::evaluate(s.tables, source.magnetizationBody, local, b, a, inside);
        for (std::size_t i = 0; i < n; ++i) {
            B[i] = R * b[i];
            if (!A.empty()) A[i] = R * a[i];
            if (!H.empty()) H[i] = R * mbm::chargeField(b[i], source.magnetizationBody, inside[i]);
        }
    }

    Wrench interaction(const Body& source, const Body& target) const override {
        const ShapeData& src = data(source.shape, source.name);
        const ShapeData& tgt = data(target.shape, target.name);
        const Eigen::Isometry3d T = targetToSource(source, target);
        if (adaptive_) return adaptiveInteraction(source, src, tgt, T, target);
        thread_local std::vector<Vec3> points, normals;
        mbm::transformSamples(tgt.samples, T, points, normals);
        const Vec3 Mt = T.linear() * target.magnetizationBody;
        const Vec3 rc = T.translation();
        // Samples in fixed blocks of kSampleBlock: the partial sums do not depend
        // on the thread count, and are added in block order, so a single pair
        // runs on all threads with bit-identical results. The workers read the
        // calling thread's sample buffers; each has its own field scratch.
        const std::size_t n = points.size();
        const std::size_t blocks = (n + kSampleBlock - 1) / kSampleBlock;
        const std::span<const Vec3> P(points), N(normals);
        const std::span<const double> W(tgt.samples.weights);
        auto block = [&](std::size_t b) {
            const std::size_t begin = b * kSampleBlock, count = std::min(kSampleBlock, n - begin);
            return mbm::interactionWrench(src.tables, source.magnetizationBody, P.subspan(begin, count),
                                          W.subspan(begin, count), N.subspan(begin, count), Mt, rc, overlap_, form_);
        };
        Wrench w;
        if (blocks <= 1) {
            w = block(0);
        } else {
            std::vector<Wrench> partial(blocks);
            parallelFor(blocks, [&](std::size_t b) { partial[b] = block(b); });
            w = partial[0];
            for (std::size_t b = 1; b < blocks; ++b) {
                w.force += partial[b].force;
                w.torque += partial[b].torque;
                w.mechanicalTorque += partial[b].mechanicalTorque;
                w.energy += partial[b].energy;
                w.fieldIntegral += partial[b].fieldIntegral;
            }
        }
        Wrench out;
        out.force = source.orientation * w.force;
        out.torque = source.orientation * w.torque;
        out.mechanicalTorque = source.orientation * w.mechanicalTorque;
        out.energy = w.energy;
        out.fieldIntegral = source.orientation * w.fieldIntegral;
        // Counted last: an atomic in the middle changes how the compiler fuses
        // the multiply-adds of the sample transform, and so the result's last bits.
        samples_.fetch_add(n, std::memory_order_relaxed);
        return out;
    }

    // One interaction(): the kernel integrates the field with the wrench. The
    // adaptive rule refines for the target's force, so a target without
    // magnetization yet (a soft body's first step) is given one along the
    // source's: the integral does not depend on it, only the refinement.
    Vec3 fieldIntegral(const Body& source, const Body& target) const override {
        if (target.magnetizationBody.squaredNorm() > 0) return interaction(source, target).fieldIntegral;
        Body probe = target;
        const Vec3 ms = source.magnetization();
        probe.magnetizationBody =
            target.orientation.conjugate() * (ms.squaredNorm() > 0 ? Vec3(ms.normalized()) : Vec3::UnitZ());
        return interaction(source, probe).fieldIntegral;
    }

    // Regular rules: one pass of the geometric field S and the inside fraction
    // at the target's samples (mbm::fieldIntegralMap), against three wrenches
    // with unit source magnetizations; the same samples, equal to rounding.
    // The adaptive rule refines for the magnetizations: three calls (the default).
    Mat3 fieldIntegralMap(const Body& source, const Body& target) const override {
        if (adaptive_) return FieldEvaluator::fieldIntegralMap(source, target);
        const ShapeData& src = data(source.shape, source.name);
        const ShapeData& tgt = data(target.shape, target.name);
        const Eigen::Isometry3d T = targetToSource(source, target);
        thread_local std::vector<Vec3> points, normals;
        mbm::transformSamples(tgt.samples, T, points, normals);
        const std::size_t n = points.size();
        const std::size_t blocks = (n + kSampleBlock - 1) / kSampleBlock;
        const std::span<const Vec3> P(points), N(normals);
        const std::span<const double> W(tgt.samples.weights);
        std::vector<Mat3> partial(blocks, Mat3::Zero());
        auto block = [&](std::size_t b) {
            const std::size_t begin = b * kSampleBlock, count = std::min(kSampleBlock, n - begin);
            partial[b] = mbm::fieldIntegralMap(src.tables, P.subspan(begin, count), W.subspan(begin, count),
                                               N.subspan(begin, count), overlap_, form_);
        };
        if (blocks <= 1) {
            if (blocks == 1) block(0);
        } else {
            parallelFor(blocks, block);
        }
        Mat3 K = Mat3::Zero();
        for (const Mat3& k : partial) K += k;
        const Mat3 R = source.orientation.toRotationMatrix();
        samples_.fetch_add(n, std::memory_order_relaxed);
        return R * K * R.transpose();
    }

    std::string describe() const override {
        std::ostringstream s;
        s << "MBM (quadrature " << ruleName_;
        if (adaptive_) s << " tolerance=" << adaptiveSettings_.tolerance << " order=" << adaptiveSettings_.order;
        else s << " n=" << n_;
        if (form_ != mbm::ForceForm::split) s << " form=" << formName_;
        s << ", overlap " << overlapName_ << ")";
        return s.str();
    }

    double forceTolerance() const override { return adaptive_ ? adaptiveSettings_.tolerance : 0.0; }

    // boundarySamples: the target samples taken by interaction() so far (cost
    // reports, e.g. magBench's table1 and table2). Adaptive only: pairs (pair
    // evaluations), pairSamplesMin/Max (samples of the cheapest and dearest
    // one; mean = boundarySamples / pairs) and cappedPairs (stopped at
    // maxSamples before the tolerance).
    FieldStats stats() const override {
        FieldStats s;
        s.add("boundarySamples", samples_.load(std::memory_order_relaxed));
        if (adaptive_) {
            const std::uint64_t pairs = pairs_.load(std::memory_order_relaxed);
            s.add("pairs", pairs);
            s.add("pairSamplesMin", pairs ? minSamples_.load(std::memory_order_relaxed) : 0);
            s.add("pairSamplesMax", maxSamples_.load(std::memory_order_relaxed));
            s.add("cappedPairs", capped_.load(std::memory_order_relaxed));
        }
        return s;
    }

private:
    struct ShapeData;

    // Target body frame -> source body frame.
    static Eigen::Isometry3d targetToSource(const Body& source, const Body& target) {
        const Quat qs = source.orientation.conjugate();
        Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
        T.linear() = (qs * target.orientation).toRotationMatrix();
        T.translation() = qs * (target.position - source.position);
        return T;
    }

    Wrench adaptiveInteraction(const Body& source, const ShapeData& src, const ShapeData& tgt,
                               const Eigen::Isometry3d& T, const Body& target) const {
        const Vec3 Mt = T.linear() * target.magnetizationBody;
        const mbm::AdaptiveResult r =
            mbm::adaptiveInteraction(src.tables, source.magnetizationBody, tgt.tables, T, Mt, T.translation(),
                                     overlap_, adaptiveSettings_);
        Wrench out;
        out.force = source.orientation * r.wrench.force;
        out.torque = source.orientation * r.wrench.torque;
        out.mechanicalTorque = source.orientation * r.wrench.mechanicalTorque;
        out.energy = r.wrench.energy;
        out.fieldIntegral = source.orientation * r.wrench.fieldIntegral;
        const std::uint64_t n = r.samples;
        samples_.fetch_add(n, std::memory_order_relaxed);
        pairs_.fetch_add(1, std::memory_order_relaxed);
        if (r.capped) capped_.fetch_add(1, std::memory_order_relaxed);
        for (std::uint64_t m = minSamples_.load(); n < m && !minSamples_.compare_exchange_weak(m, n);) {}
        for (std::uint64_t m = maxSamples_.load(); n > m && !maxSamples_.compare_exchange_weak(m, n);) {}
        return out;
    }

    struct ShapeData {
        mbm::PolyhedronTables tables;
        mbm::SurfaceQuadrature samples;
    };

    // Tables of a shape, built on first use (shapes are immutable and shared).
    // The weak reference catches a new shape allocated at a freed one's address.
    const ShapeData& data(const std::shared_ptr<const Shape>& shape, const std::string& bodyName) const {
        std::lock_guard lock(mutex_);
        auto it = cache_.find(shape.get());
        if (it != cache_.end() && !it->second.shape.owner_before(shape) && !shape.owner_before(it->second.shape))
            return *it->second.data;
        try {
            mbm::PolyhedronTables tables(shape->mesh.vertices, shape->mesh.triangles);
            // The adaptive rule places its samples per pair.
            auto samples = adaptive_ ? mbm::SurfaceQuadrature{} : mbm::buildSurfaceQuadrature(tables, rule_, n_);
            auto d = std::make_unique<ShapeData>(ShapeData{std::move(tables), std::move(samples)});
            auto& entry = cache_[shape.get()];
            entry = CacheEntry{shape, std::move(d)};
            return *entry.data;
        } catch (const std::invalid_argument& e) {
            throw InputError("body '" + bodyName + "' (" + shape->mesh.source + "): " + e.what());
        }
    }

    std::string ruleName_, overlapName_, formName_;
    mbm::QuadratureRule rule_ = mbm::QuadratureRule::gauss;
    int n_ = 10;
    bool adaptive_ = true;
    mbm::AdaptiveSettings adaptiveSettings_;
    mbm::OverlapModel overlap_ = mbm::OverlapModel::charge;
    mbm::ForceForm form_ = mbm::ForceForm::split;
    mutable std::mutex mutex_;
    mutable std::atomic<std::uint64_t> samples_{0}, pairs_{0}, capped_{0}, maxSamples_{0};
    mutable std::atomic<std::uint64_t> minSamples_{UINT64_MAX};
    struct CacheEntry {
        std::weak_ptr<const Shape> shape;
        std::unique_ptr<const ShapeData> data;
    };
    mutable std::map<const Shape*, CacheEntry> cache_;
};

const TypeDoc kDoc{
    "Magnetic Boundary Method (paper Sec. 4): exact fields, bounded at contact and overlap.\n"
    "Fields of uniformly magnetized polyhedra in closed form (Fabbri), forces and torques\n"
    "integrated over the target's boundary (Eqs. 16-18).\n"
    "The default quadrature is adaptive and contact-exact.",
    {"type: MBM\nquadrature: {type: adaptive, tolerance: 1e-4}\noverlap: charge\n",
     "type: MBM\nquadrature: {type: gauss, n: 10}\n"},
    {{"quadrature", "-", "how the boundary integrals are sampled"},
     {"quadrature.type", "-",
      "adaptive: tolerance-driven and contact-exact (docs/physics.md#adaptive-quadrature);\n"
      "regular: the paper's n x n midpoints per planar face; gauss: n x n Gauss-Legendre per face"},
     {"quadrature.tolerance", "-", "adaptive: relative error of force and torque/size per pair, 1e-12..0.1"},
     {"quadrature.order", "-", "adaptive: Gauss points per side of a contact element, 1..12"},
     {"quadrature.maxSamples", "-",
      "adaptive: samples per pair; beyond it the pair keeps its estimate (counted as capped)"},
     {"quadrature.n", "-", "regular, gauss: points per face edge, 1..100"},
     {"quadrature.form", "-",
      "split: the paper's Eqs. 16-18, (M . B) n; surfaceCharge: the target's surface charge (M . n)\n"
      "in the field, the exact gradient of the sampled energy for any rule (charge, exterior;\n"
      "docs/physics.md#force-form)"},
     {"overlap", "-",
      "charge: Akoun-Yonnet, pushes overlapping magnets apart; amperian: the energy force;\n"
      "exterior: the field just outside the nearest source face continued into the overlap, so\n"
      "the force stays continuous through a contact solver's penetration (docs/physics.md#overlap-models)"}}};

const FieldEvaluator::Add<MBMField> addMBM("MBM", kDoc);

} // namespace

} // namespace mag
