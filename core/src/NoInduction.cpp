// `induction: {type: none}`: magnetizations stay as they are (the default;
// the solver also skips induction entirely when no body is soft).
#include "magFoam/InductionModel.hpp"

#include "magFoam/AppliedField.hpp"

namespace mag {

namespace {
class NoInduction final : public InductionModel {
public:
    explicit NoInduction(const Dict&) {}
    InductionReport converge(std::vector<Body>&, const FieldEvaluator&, const AppliedField&) override { return {}; }
    std::string describe() const override { return "none"; }
};
const InductionModel::Add<NoInduction> addNone(
    "none", TypeDoc{"Magnetizations stay as given (the default).\nInduction is skipped when no body is soft.",
                    {"type: none\n"},
                    {}});
} // namespace

double InductionModel::sceneEnergy(const std::vector<Body>& bodies, const std::vector<Wrench>& wrenches) const {
    return sceneMagneticEnergy(wrenches, [&](std::size_t i) { return bodies[i].soft(); });
}

InductionReport InductionModel::converge(std::vector<Body>& bodies, const FieldEvaluator& field) {
    static const std::unique_ptr<AppliedField> none = AppliedField::New(Dict::fromString("type: none", "none"));
    return converge(bodies, field, *none);
}

} // namespace mag
