#include "magFoam/MagneticSystem.hpp"

#include <algorithm>

namespace mag {

MagneticSystem::MagneticSystem(const Case& c)
    : field_(FieldEvaluator::New(c.fieldDict())), induction_(InductionModel::New(c.inductionDict())),
      applied_(AppliedField::New(c.appliedFieldDict())) {
    c.magSchemes().reportUnused();
}

MagneticSystem::MagneticSystem(std::unique_ptr<FieldEvaluator> field, std::unique_ptr<InductionModel> induction,
                               std::unique_ptr<AppliedField> applied)
    : field_(std::move(field)), induction_(std::move(induction)), applied_(std::move(applied)) {
    if (!applied_) applied_ = AppliedField::New(Dict::fromString("type: none", "no applied field"));
}

InductionReport MagneticSystem::converge(std::vector<Body>& bodies) const {
    bool anySoft = false;
    for (const auto& b : bodies) anySoft = anySoft || b.soft();
    if (!anySoft) return {};
    return induction_->converge(bodies, *field_, *applied_);
}

std::vector<Wrench> MagneticSystem::wrenches(const std::vector<Body>& bodies, bool skipFixedTargets) const {
    // Magnetized bodies only; the evaluator decides how each pair is summed.
    std::vector<std::size_t> active;
    for (std::size_t i = 0; i < bodies.size(); ++i)
        if (bodies[i].magnetizationBody.squaredNorm() != 0) active.push_back(i);
    std::vector<Wrench> out(bodies.size());
    field_->addWrenches(bodies, active, skipFixedTargets, out);
    if (applied_->active())
        for (std::size_t i : active)
            if (!(skipFixedTargets && bodies[i].fixed)) out[i] += applied_->wrench(bodies[i]);
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
    if (applied_->active()) {
        // Outside the bodies H = B / mu0 for the applied part too.
        std::fill(b.begin(), b.end(), Vec3::Zero());
        applied_->add(points, b, A);
        for (std::size_t i = 0; i < n; ++i) {
            B[i] += b[i];
            if (!H.empty()) H[i] += b[i] / mu0;
        }
    }
}

} // namespace mag
