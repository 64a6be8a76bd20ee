#include "magFoam/FieldEvaluator.hpp"

#include "magFoam/Threads.hpp"

#include <algorithm>
#include <cmath>

namespace mag {

namespace {

// d x F with each multiply-add fused as written (this file is compiled without
// the compiler's own contraction, core/CMakeLists.txt): the reaction torque's
// rounding is fixed here, whatever the surrounding code, and is the one the
// solver has always had.
Vec3 reactionArm(const Vec3& d, const Vec3& F) {
    return {std::fma(-d.z(), F.y(), d.y() * F.z()), std::fma(-d.x(), F.z(), d.z() * F.x()),
            std::fma(d.x(), F.y(), -(d.y() * F.x()))};
}

} // namespace

void FieldEvaluator::addWrenches(std::span<const Body> bodies, std::span<const std::size_t> active,
                                 bool skipFixedPairs, std::span<Wrench> out) const {
    // Every pair (i < j) of the active bodies but those within a compound.
    PairChunks pairs(*this, bodies, out);
    for (std::size_t a = 0; a < active.size(); ++a)
        for (std::size_t b = a + 1; b < active.size(); ++b) {
            const std::size_t i = active[a], j = active[b];
            if (sameRigidBody(bodies[i], bodies[j])) continue;
            if (!(skipFixedPairs && bodies[i].fixed && bodies[j].fixed)) pairs.add(i, j);
        }
    pairs.finish();
}

void FieldEvaluator::PairChunks::add(std::size_t i, std::size_t j) {
    pairs_.push_back(orientedPair(bodies_, i, j));
    if (pairs_.size() == kChunk) finish();
}

Vec3 FieldEvaluator::fieldIntegral(const Body& source, const Body& target) const {
    Body unit = target;
    Vec3 integral;
    for (int k = 0; k < 3; ++k) {
        unit.magnetizationBody = target.orientation.conjugate() * Vec3::Unit(k);
        integral[k] = -interaction(source, unit).energy;
    }
    return integral;
}

Mat3 FieldEvaluator::fieldIntegralMap(const Body& source, const Body& target) const {
    Body unit = source;
    Mat3 K;
    for (int c = 0; c < 3; ++c) {
        unit.magnetizationBody = source.orientation.conjugate() * Vec3::Unit(c);
        K.col(c) = fieldIntegral(unit, target);
    }
    return K;
}

void FieldEvaluator::PairChunks::finish() {
    f_.addPairWrenches(bodies_, pairs_, out_);
    pairs_.clear();
}

void FieldEvaluator::addPairWrenches(std::span<const Body> bodies, std::span<const BodyPair> pairs,
                                     std::span<Wrench> out) const {
    std::vector<Wrench> perPair(pairs.size());
    auto evaluate = [&](std::size_t k) { perPair[k] = interaction(bodies[pairs[k].source], bodies[pairs[k].target]); };
    // Many pairs: in parallel, handed out in runs (cheap pairs at well under a
    // microsecond must not each take the shared loop counter). Few: one after
    // another, so that an evaluator's own parallel loop (over a pair's samples)
    // gets the threads. Either way each pair's result is the same, bit for bit.
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
        r.torque = -w.totalTorque() - reactionArm(bodies[t].position - bodies[s].position, w.force);
        r.energy = w.energy;
        out[s] += r;
    }
}

} // namespace mag
