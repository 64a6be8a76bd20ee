// A test plugin: a field evaluator of a uniform field B0 (no wrench), to prove
// that a model in a separate shared library is selectable by name from a case.
#include <magFoam/FieldEvaluator.hpp>

#include <limits>

namespace {

class UniformTestField final : public mag::FieldEvaluator {
public:
    explicit UniformTestField(const mag::Dict& d)
        : B0_(d.get<mag::Vec3>("B0")), nanForce_(d.get<bool>("nanForce", false)),
          nanAboveSpeed_(d.get<double>("nanAboveSpeed", std::numeric_limits<double>::infinity())) {}
    void evaluate(const mag::Body&, std::span<const mag::Vec3> points, std::span<mag::Vec3> B,
                  std::span<mag::Vec3> A, std::span<mag::Vec3> H) const override {
        for (std::size_t i = 0; i < points.size(); ++i) {
            B[i] = B0_;
            if (!A.empty()) A[i] = 0.5 * B0_.cross(points[i]);
            if (!H.empty()) H[i] = B0_ / mag::mu0;
        }
    }
    // nanForce: a broken model, to test that solvers stop on non-finite
    // wrenches; nanAboveSpeed: broken only once the target is faster (m/s),
    // so that a run has good states before the bad one.
    mag::Wrench interaction(const mag::Body&, const mag::Body& target) const override {
        mag::Wrench w;
        if (nanForce_ || target.velocity.norm() > nanAboveSpeed_)
            w.force.x() = std::numeric_limits<double>::quiet_NaN();
        return w;
    }
    std::string describe() const override { return "testUniformField"; }

private:
    mag::Vec3 B0_;
    bool nanForce_;
    double nanAboveSpeed_;
};

const mag::FieldEvaluator::Add<UniformTestField> addTest("testUniformField");

} // namespace
