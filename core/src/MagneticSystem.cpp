#include "magFoam/MagneticSystem.hpp"

#include "magFoam/DipoleMultipole.hpp"
#include "magFoam/Threads.hpp"

#include <algorithm>

namespace mag {

MagneticSystem::MagneticSystem(const Case& c)
    : field_(FieldEvaluator::New(c.fieldDict())), induction_(InductionModel::New(c.inductionDict())),
      farField_(FarFieldSettings::read(c.magSchemes().subOrEmpty("farField"))) {
    c.magSchemes().reportUnused();
}

MagneticSystem::MagneticSystem(std::unique_ptr<FieldEvaluator> field, std::unique_ptr<InductionModel> induction)
    : field_(std::move(field)), induction_(std::move(induction)) {}

InductionReport MagneticSystem::converge(std::vector<Body>& bodies) const {
    bool anySoft = false;
    for (const auto& b : bodies) anySoft = anySoft || b.soft();
    if (!anySoft) return {};
    return induction_->converge(bodies, *field_);
}

std::vector<Wrench> MagneticSystem::wrenches(const std::vector<Body>& bodies, bool skipFixedTargets) const {
    // One evaluation per pair (the paper negates F for the other magnet):
    // the sampled boundary is the target's, and the source gets the exact
    // opposite force and the torque that conserves angular momentum about
    // any point. A quadrature error then cannot make a cluster of touching
    // magnets push itself along or spin itself up.
    struct Pair {
        std::size_t source, target;
    };
    // Pairs go in chunks: a chunk's wrenches are evaluated into per-pair slots
    // (in parallel), then added to the bodies in pair order. Chunks bound the
    // memory of large scenes (5 MB, not 80 bytes per pair) without changing
    // any sum's order; each is still one parallel loop of many pairs.
    constexpr std::size_t kChunk = 65536;
    std::vector<Pair> pairs;
    std::vector<Wrench> perPair;
    std::vector<Wrench> out(bodies.size());
    auto flush = [&] {
        perPair.resize(pairs.size());
        auto evaluate = [&](std::size_t k) {
            perPair[k] = field_->interaction(bodies[pairs[k].source], bodies[pairs[k].target]);
        };
        // Many pairs: in parallel, handed out in runs (cheap pairs, dipole or
        // EDM at ~0.1-1 us, must not each take the shared loop counter). Few:
        // one after another, so that an evaluator's own parallel loop (MBM's
        // sample blocks) gets the threads. Either way each pair's result is the
        // same, bit for bit.
        const auto nThreads = static_cast<std::size_t>(threads());
        if (pairs.size() >= 2 * nThreads)
            parallelFor(pairs.size(), evaluate, std::max<std::size_t>(1, pairs.size() / (64 * nThreads)));
        else
            for (std::size_t k = 0; k < pairs.size(); ++k) evaluate(k);
        for (std::size_t k = 0; k < pairs.size(); ++k) {
            const std::size_t s = pairs[k].source, t = pairs[k].target;
            const Wrench& w = perPair[k];
            out[t] += w;
            Wrench r;
            r.force = -w.force;
            r.torque = -w.totalTorque() - (bodies[t].position - bodies[s].position).cross(w.force);
            r.energy = w.energy;
            out[s] += r;
        }
        pairs.clear();
    };
    // Magnetized bodies only; the field evaluator says which pairs are dipole
    // pairs (far apart against their size): those go to the bulk far field, the
    // others (found by a grid, not by visiting every pair) one by one.
    std::vector<std::size_t> index;
    std::vector<FarFieldBody> active;
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        const Body& b = bodies[i];
        if (b.magnetizationBody.squaredNorm() == 0) continue;
        index.push_back(i);
        active.push_back(farFieldBody(b, *field_));
    }
    for (const auto& [ai, aj] : nearPairs(active, skipFixedTargets)) {
        const std::size_t i = index[ai], j = index[aj];
        // Sample the body that moves (a fixed body needs no wrench);
        // otherwise the one listed later.
        const bool targetIsA = bodies[j].fixed && !bodies[i].fixed;
        pairs.push_back(targetIsA ? Pair{j, i} : Pair{i, j});
        if (pairs.size() == kChunk) flush();
    }
    flush();
    std::vector<Wrench> far(active.size());
    if (const std::uint64_t n = addDipoleFarField(active, skipFixedTargets, far, farField_)) {
        field_->countDipolePairs(n);
        for (std::size_t a = 0; a < active.size(); ++a) out[index[a]] += far[a];
    }
    return out;
}

MagneticSystem::Step MagneticSystem::step(std::vector<Body>& bodies) const {
    Step s;
    s.induction = converge(bodies);
    s.wrenches = wrenches(bodies, true);
    return s;
}

void MagneticSystem::field(const std::vector<Body>& bodies, std::span<const Vec3> points, std::span<Vec3> B,
                           std::span<Vec3> A, std::span<Vec3> H, const Body* exclude) const {
    const std::size_t n = points.size();
    std::fill(B.begin(), B.end(), Vec3::Zero());
    std::fill(A.begin(), A.end(), Vec3::Zero());
    std::fill(H.begin(), H.end(), Vec3::Zero());
    std::vector<Vec3> b(n), a(A.empty() ? 0 : n), h(H.empty() ? 0 : n);
    for (const auto& source : bodies) {
        if (&source == exclude || source.magnetizationBody.squaredNorm() == 0) continue;
        field_->evaluate(source, points, b, a, h);
        for (std::size_t i = 0; i < n; ++i) {
            B[i] += b[i];
            if (!A.empty()) A[i] += a[i];
            if (!H.empty()) H[i] += h[i];
        }
    }
}

} // namespace mag
