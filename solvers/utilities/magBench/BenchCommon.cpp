#include "BenchCommon.hpp"

#include "oracles/akounYonnet.hpp"

#include <magFoam/Error.hpp>
#include <magFoam/MeshPrimitives.hpp>
#include <magFoam/ShapeFactory.hpp>

#include <map>

namespace mag::bench {

Body cube(const std::string& name, double edge, double Br, const Vec3& position, const Quat& q) {
    // One shape per edge length: evaluators cache their tables per shape.
    static std::map<double, std::shared_ptr<const Shape>> shapes;
    auto& shape = shapes[edge];
    if (!shape) {
        ShapeKind kind;
        kind.kind = ShapeKind::Kind::box;
        kind.size = Vec3::Constant(edge);
        shape = makeShape(makeBox(kind.size), kind);
    }
    Body b;
    b.name = name;
    b.shape = shape;
    b.material.Br = Br;
    b.material.density = 7500;
    b.magnetizationBody = Vec3(0, 0, Br / mu0);
    b.position = position;
    b.orientation = q;
    return b;
}

std::vector<Body> cubePair(double gap) {
    return {cube("bottom", 0.01, 1.0, Vec3::Zero()), cube("top", 0.01, 1.0, Vec3(0, 0, 0.01 + gap))};
}

std::unique_ptr<FieldEvaluator> evaluator(const std::string& yaml) {
    return FieldEvaluator::New(Dict::fromString(yaml, "magBench"));
}

Vec3 exactCubeForce(const Body& lower, const Body& upper) {
    const Vec3 s1 = Vec3::Constant(std::cbrt(lower.shape->volume));
    const Vec3 s2 = Vec3::Constant(std::cbrt(upper.shape->volume));
    return oracle::akounYonnetForce(s1, lower.position, s2, upper.position, lower.material.Br, upper.material.Br);
}

} // namespace mag::bench
