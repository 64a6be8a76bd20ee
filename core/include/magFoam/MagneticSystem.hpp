// MagneticSystem: one step of the paper's Algorithm 1, in one place, for every
// app (magFoam, magForces, magBench): converge the induced magnetizations,
// then the wrench on every body summed over all other bodies. It reaches the
// models only through the registries (FieldEvaluator, InductionModel).
#pragma once

#include "magFoam/AppliedField.hpp"
#include "magFoam/Case.hpp"
#include "magFoam/FieldEvaluator.hpp"
#include "magFoam/InductionModel.hpp"

#include <iosfwd>
#include <memory>
#include <span>
#include <vector>

namespace mag {

class MagneticSystem {
public:
    // Models from the case's system/magSchemes.yaml (field:, induction:) and
    // constant/appliedField.yaml.
    explicit MagneticSystem(const Case& c);
    MagneticSystem(std::unique_ptr<FieldEvaluator> field, std::unique_ptr<InductionModel> induction,
                   std::unique_ptr<AppliedField> applied = nullptr);

    // The time the applied field is taken at (magFoam: the start of each step).
    void setTime(double t) { applied_->setTime(t); }

    // Converge soft-body magnetizations (Algorithm 1, lines 3-12). Does
    // nothing, and costs nothing, when no body is soft.
    InductionReport converge(std::vector<Body>& bodies) const;

    // Wrench on each body from all others (lines 13-24), through the field
    // evaluator's addWrenches(), plus the applied field's: unmagnetized bodies are skipped; with
    // skipFixedTargets, pairs of two fixed bodies are skipped. Bit-identical
    // for any thread count.
    std::vector<Wrench> wrenches(const std::vector<Body>& bodies, bool skipFixedTargets = false) const;

    // The magnetic part of one solver step, as magFoam runs it: converge, then
    // wrenches with pairs of two fixed bodies skipped where fixedPairsConstant.
    struct Step {
        InductionReport induction;
        std::vector<Wrench> wrenches;
    };
    Step step(std::vector<Body>& bodies) const;

    // Whether the pairs of two fixed bodies are constant, so that a step may
    // skip them: no fixed body is soft. A fixed soft body's magnetization
    // changes with what moves past it, and with it its energy with a fixed
    // magnet, which the audit sums from the step's wrenches.
    static bool fixedPairsConstant(const std::vector<Body>& bodies);

    // The scene's magnetic energy (J) from wrenches() at converged
    // magnetizations, as the induction model counts soft bodies. A compound
    // with a soft part takes one more evaluation of the parts, with the pairs
    // within each compound (they change with the soft part's magnetization).
    double magneticEnergy(const std::vector<Body>& bodies, const std::vector<Wrench>& wrenches) const;

    // The induction model's restart state (InductionModel::writeState,
    // readState), given the bodies' parts.
    void writeInductionState(std::ostream& yaml, const std::vector<Body>& bodies) const;
    void readInductionState(const Dict& state, const std::vector<Body>& bodies);

    // Total field of all bodies (except `exclude`, if set, and its parts) and the applied field at world points.
    void field(const std::vector<Body>& bodies, std::span<const Vec3> points, std::span<Vec3> B,
               std::span<Vec3> A = {}, std::span<Vec3> H = {}, const Body* exclude = nullptr) const;

    const FieldEvaluator& fieldEvaluator() const { return *field_; }
    const InductionModel& inductionModel() const { return *induction_; }
    const AppliedField& appliedField() const { return *applied_; }
    InductionModel& inductionModel() { return *induction_; }  // restart state (InductionModel::readState)

private:
    // wrenches() of bodies that are not compound (parts).
    std::vector<Wrench> partWrenches(const std::vector<Body>& bodies, bool skipFixedTargets) const;

    std::unique_ptr<FieldEvaluator> field_;
    std::unique_ptr<InductionModel> induction_;
    std::unique_ptr<AppliedField> applied_;
};

} // namespace mag
