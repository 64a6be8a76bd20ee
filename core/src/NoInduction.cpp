// `induction: {type: none}`: magnetizations stay as they are (the default;
// the solver also skips induction entirely when no body is soft).
#include "magFoam/InductionModel.hpp"

namespace mag {

namespace {
class NoInduction final : public InductionModel {
public:
    explicit NoInduction(const Dict&) {}
    InductionReport converge(std::vector<Body>&, const FieldEvaluator&) override { return {}; }
    std::string describe() const override { return "none"; }
};
const InductionModel::Add<NoInduction> addNone(
    "none", TypeDoc{"Magnetizations stay as given (the default).\nInduction is skipped when no body is soft.",
                    {"type: none\n"},
                    {}});
} // namespace

} // namespace mag
