#include "magFoam/MagneticSystem.hpp"

#include "magFoam/Parts.hpp"

#include <algorithm>
#include <optional>

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

// Compound bodies (Parts.hpp): the models get the parts; a soft part is
// magnetized by every other part, its own body's too, but pairs within a body
// are left out of the wrenches (rigid: they exert no net force or torque).

InductionReport MagneticSystem::converge(std::vector<Body>& bodies) const {
    bool anySoft = false;
    for (const auto& b : bodies) anySoft = anySoft || b.soft();
    if (!anySoft) return {};
    if (!hasCompounds(bodies)) return induction_->converge(bodies, *field_, *applied_);
    PartBodies view(bodies);
    const InductionReport report = induction_->converge(view.parts, *field_, *applied_);
    view.storeMagnetizations(bodies);
    return report;
}

std::vector<Wrench> MagneticSystem::wrenches(const std::vector<Body>& bodies, bool skipFixedTargets) const {
    if (!hasCompounds(bodies)) return partWrenches(bodies, skipFixedTargets);
    const PartBodies view(bodies);
    return view.sum(bodies, partWrenches(view.parts, skipFixedTargets));
}

double MagneticSystem::magneticEnergy(const std::vector<Body>& bodies, const std::vector<Wrench>& wrenches) const {
    // The pairs within a compound are constant while its parts are permanent;
    // with a soft part they change, and the energy takes them in.
    if (std::none_of(bodies.begin(), bodies.end(), [](const Body& b) { return b.compound && b.compound->anySoft; }))
        return induction_->sceneEnergy(bodies, wrenches);
    PartBodies view(bodies);
    for (Body& p : view.parts) p.group = 0;
    return induction_->sceneEnergy(view.parts, partWrenches(view.parts, false));
}

void MagneticSystem::writeInductionState(std::ostream& yaml, const std::vector<Body>& bodies) const {
    if (!hasCompounds(bodies)) return induction_->writeState(yaml, bodies);
    induction_->writeState(yaml, PartBodies(bodies).parts);
}

void MagneticSystem::readInductionState(const Dict& state, const std::vector<Body>& bodies) {
    if (!hasCompounds(bodies)) return induction_->readState(state, bodies);
    induction_->readState(state, PartBodies(bodies).parts);
}

std::vector<Wrench> MagneticSystem::partWrenches(const std::vector<Body>& bodies, bool skipFixedTargets) const {
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
    s.wrenches = wrenches(bodies, fixedPairsConstant(bodies));
    return s;
}

bool MagneticSystem::fixedPairsConstant(const std::vector<Body>& bodies) {
    return std::none_of(bodies.begin(), bodies.end(), [](const Body& b) { return b.fixed && b.soft(); });
}

void MagneticSystem::field(const std::vector<Body>& bodies, std::span<const Vec3> points, std::span<Vec3> B,
                           std::span<Vec3> A, std::span<Vec3> H, const Body* exclude) const {
    const std::size_t n = points.size();
    std::fill(B.begin(), B.end(), Vec3::Zero());
    std::fill(A.begin(), A.end(), Vec3::Zero());
    std::fill(H.begin(), H.end(), Vec3::Zero());
    std::vector<Vec3> b(n), a(A.empty() ? 0 : n), h(H.empty() ? 0 : n);
    const bool compounds = hasCompounds(bodies);
    const std::optional<PartBodies> view = compounds ? std::optional<PartBodies>(std::in_place, bodies) : std::nullopt;
    const std::vector<Body>& sources = compounds ? view->parts : bodies;
    for (std::size_t k = 0; k < sources.size(); ++k) {
        const Body& source = sources[k];
        const Body& owner = compounds ? bodies[view->owner[k]] : source;
        if (&owner == exclude || source.magnetizationBody.squaredNorm() == 0) continue;
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
