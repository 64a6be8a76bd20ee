// Magnetic Boundary Method field evaluator (paper Sec. 4):
//
//   field: {type: MBM, quadrature: {type: gauss, n: 10}, overlap: charge}
//
// | key             | default | meaning                                            |
// |-----------------|---------|----------------------------------------------------|
// | quadrature.type | gauss   | regular (paper: n x n midpoints per planar face)   |
// |                 |         | or gauss (n x n Gauss-Legendre per face)           |
// | quadrature.n    | 10      | points per face edge, 1..100                        |
// | overlap         | charge  | charge (Akoun-Yonnet: pushes overlapping magnets   |
// |                 |         | apart) or amperian (energy force),                 |
// |                 |         | docs/physics.md#overlap-models                     |
//
// A and B of the source are exact (Fabbri, Eqs. 9-15), evaluated in the
// source's body frame on the target's boundary samples moved there; only the
// boundary integrals of Eqs. 16-18 are sampled. Per-shape tables (edges,
// planar faces, samples) are built once and shared by all bodies of a shape.
//
// Threads: interaction() and evaluate() may run concurrently (the shape cache
// is behind a mutex, scratch is per thread); interaction() splits the target's
// samples into fixed blocks that run on the worker threads (Threads.hpp).
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

namespace mag {

namespace {

// Samples per parallel block of interaction(): ~15 us of work for a cube
// (~0.5 us per sample), far above the cost of handing out a block.
constexpr std::size_t kSampleBlock = 32;

class MBMField final : public FieldEvaluator {
public:
    explicit MBMField(const Dict& d) {
        const Dict q = d.subOrEmpty("quadrature");
        ruleName_ = q.getWord("type", {"regular", "gauss"}, "gauss");
        rule_ = mbm::quadratureRuleFromName(ruleName_);
        n_ = q.get<int>("n", 10);
        if (n_ < 1 || n_ > 100) q.fail("n", "quadrature n must be 1..100 (points per face edge)");
        q.reportUnused();
        overlapName_ = d.getWord("overlap", {"charge", "amperian"}, "charge");
        overlap_ = mbm::overlapModelFromName(overlapName_);
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
        // Target body frame -> source body frame.
        const Quat qs = source.orientation.conjugate();
        Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
        T.linear() = (qs * target.orientation).toRotationMatrix();
        T.translation() = qs * (target.position - source.position);
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
                                          W.subspan(begin, count), N.subspan(begin, count), Mt, rc, overlap_);
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
            }
        }
        Wrench out;
        out.force = source.orientation * w.force;
        out.torque = source.orientation * w.torque;
        out.mechanicalTorque = source.orientation * w.mechanicalTorque;
        out.energy = w.energy;
        // Counted last: an atomic in the middle changes how the compiler fuses
        // the multiply-adds of the sample transform, and so the result's last bits.
        samples_.fetch_add(n, std::memory_order_relaxed);
        return out;
    }

    std::string describe() const override {
        return "MBM (quadrature " + ruleName_ + " n=" + std::to_string(n_) + ", overlap " + overlapName_ + ")";
    }

    // boundarySamples: the target samples taken by interaction() so far (cost
    // reports, e.g. magBench's table1 and table2).
    FieldStats stats() const override {
        FieldStats s;
        s.add("boundarySamples", samples_.load(std::memory_order_relaxed));
        return s;
    }

private:
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
            auto samples = mbm::buildSurfaceQuadrature(tables, rule_, n_);
            auto d = std::make_unique<ShapeData>(ShapeData{std::move(tables), std::move(samples)});
            auto& entry = cache_[shape.get()];
            entry = CacheEntry{shape, std::move(d)};
            return *entry.data;
        } catch (const std::invalid_argument& e) {
            throw InputError("body '" + bodyName + "' (" + shape->mesh.source + "): " + e.what());
        }
    }

    std::string ruleName_, overlapName_;
    mbm::QuadratureRule rule_ = mbm::QuadratureRule::gauss;
    int n_ = 10;
    mbm::OverlapModel overlap_ = mbm::OverlapModel::charge;
    mutable std::mutex mutex_;
    mutable std::atomic<std::uint64_t> samples_{0};
    struct CacheEntry {
        std::weak_ptr<const Shape> shape;
        std::unique_ptr<const ShapeData> data;
    };
    mutable std::map<const Shape*, CacheEntry> cache_;
};

const FieldEvaluator::Add<MBMField> addMBM("MBM");

} // namespace

} // namespace mag
