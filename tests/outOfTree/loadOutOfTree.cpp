// Loads libmagOutOfTree.so by name (MAG_PLUGIN_PATH) and selects its type.
#include <magFoam/FieldEvaluator.hpp>
#include <magFoam/Plugins.hpp>

#include <iostream>

int main() {
    mag::plugins::load("magOutOfTree");
    auto field = mag::FieldEvaluator::New(mag::Dict::fromString("type: outOfTreeField\nscale: 2\n", "inline"));
    mag::Vec3 p(1, 2, 3), B;
    field->evaluate(mag::Body{}, std::span<const mag::Vec3>(&p, 1), std::span<mag::Vec3>(&B, 1));
    std::cout << field->describe() << " B = " << B.transpose() << "\n";
    return (B - 2 * p).norm() < 1e-15 ? 0 : 1;
}
