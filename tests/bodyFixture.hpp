// Bodies built in code for the field-evaluator tests (no case folder): an
// evaluator from a YAML string, box and sphere shapes, a uniformly magnetized
// body (|M| = 1 T / mu0 along dir), a rotation in degrees.
#pragma once

#include <magFoam/Body.hpp>
#include <magFoam/Dictionary.hpp>
#include <magFoam/FieldEvaluator.hpp>
#include <magFoam/MeshPrimitives.hpp>
#include <magFoam/ShapeFactory.hpp>

#include <memory>
#include <string>

namespace magtest {

inline std::unique_ptr<mag::FieldEvaluator> field(const std::string& yaml) {
    return mag::FieldEvaluator::New(mag::Dict::fromString(yaml, "test"));
}

inline std::shared_ptr<const mag::Shape> boxShape(const mag::Vec3& size) {
    mag::ShapeKind kind;
    kind.kind = mag::ShapeKind::Kind::box;
    kind.size = size;
    return mag::makeShape(mag::makeBox(size), kind);
}

inline std::shared_ptr<const mag::Shape> sphereShape(double radius, int subdivisions) {
    mag::ShapeKind kind;
    kind.kind = mag::ShapeKind::Kind::sphere;
    kind.radius = radius;
    return mag::makeShape(mag::makeIcosphere(radius, subdivisions), kind);
}

inline mag::Body magnet(const std::string& name, std::shared_ptr<const mag::Shape> shape, const mag::Vec3& position,
                        const mag::Vec3& dir, const mag::Quat& orientation = mag::Quat::Identity()) {
    mag::Body b;
    b.name = name;
    b.shape = std::move(shape);
    b.material.Br = 1.0;
    b.material.density = 7500;
    b.magnetizationBody = dir.normalized() / mag::mu0;
    b.position = position;
    b.orientation = orientation.normalized();
    return b;
}

inline mag::Quat axisAngle(double degrees, const mag::Vec3& axis) {
    return mag::Quat(Eigen::AngleAxisd(degrees * mag::pi / 180.0, axis.normalized()));
}

} // namespace magtest
