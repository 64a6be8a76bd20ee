// A test plugin compiled without AVX (tests/CMakeLists.txt: -mno-avx), so its
// Body has another layout than libmagCore's: the loader must refuse it.
#include <magFoam/FieldEvaluator.hpp>

namespace {
class LayoutMismatchField final : public mag::FieldEvaluator {
public:
    explicit LayoutMismatchField(const mag::Dict&) {}
    void evaluate(const mag::Body&, std::span<const mag::Vec3>, std::span<mag::Vec3>, std::span<mag::Vec3>,
                  std::span<mag::Vec3>) const override {}
    mag::Wrench interaction(const mag::Body&, const mag::Body&) const override { return {}; }
    std::string describe() const override { return "layoutMismatchField"; }
};
const mag::FieldEvaluator::Add<LayoutMismatchField> add("layoutMismatchField");
} // namespace
