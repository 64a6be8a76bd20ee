// A field evaluator compiled against the installed headers only.
#include <magFoam/FieldEvaluator.hpp>

namespace {
class OutOfTreeField final : public mag::FieldEvaluator {
public:
    explicit OutOfTreeField(const mag::Dict& d) : scale_(d.get<double>("scale", 1.0)) {}
    void evaluate(const mag::Body&, std::span<const mag::Vec3> points, std::span<mag::Vec3> B, std::span<mag::Vec3>,
                  std::span<mag::Vec3>) const override {
        for (std::size_t i = 0; i < points.size(); ++i) B[i] = scale_ * points[i];
    }
    mag::Wrench interaction(const mag::Body&, const mag::Body&) const override { return {}; }
    std::string describe() const override { return "outOfTreeField"; }

private:
    double scale_;
};
const mag::FieldEvaluator::Add<OutOfTreeField> add("outOfTreeField");
} // namespace
