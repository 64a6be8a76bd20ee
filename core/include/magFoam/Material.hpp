// Materials (constant/materials.yaml): every top-level key names one.
//
//   N42:   {model: permanent, Br: 1.3, density: 7500}     # Br: remanence, T
//   steel: {model: soft, k: 5.0, Js: 2.0, density: 7850}  # keys of the induction model
//
// | key     | model     | required | unit  | meaning                                  |
// |---------|-----------|----------|-------|------------------------------------------|
// | model   | both      | yes      |       | permanent or soft                        |
// | density | both      | yes      | kg/m3 | > 0                                      |
// | Br      | permanent | yes      | T     | remanence, |M| = Br/mu0, >= 0            |
// | (other) | soft      |          |       | numbers read and checked by the induction|
// |         |           |          |       | model (e.g. LLG: k, Js, alpha)           |
//
// A soft material's magnetization is the induction model's business, so core
// keeps its keys as they are and the model validates them: a key the selected
// model does not use is an error naming it (docs/case-reference.md#materials).
#pragma once

#include "magFoam/Dictionary.hpp"

#include <map>
#include <optional>
#include <string>

namespace mag {

struct Material {
    enum class Model { permanent, soft };
    std::string name;
    Model model = Model::permanent;
    double density = 0;  // kg/m^3
    double Br = 0;       // T (permanent)
    // Soft: every key but `model` and `density`, for the induction model.
    std::map<std::string, double> properties;
    std::optional<Dict> dict;  // where the material was read (none when built in code)

    bool soft() const { return model == Model::soft; }
    // The soft property `key`; `fallback` when absent, or an error naming the
    // key when there is no fallback.
    double property(const std::string& key) const;
    double property(const std::string& key, double fallback) const;
    // An InputError about `key` of this material: "file:line:col: steel.k: message"
    // when it was read from a file.
    [[noreturn]] void fail(const std::string& key, const std::string& message) const;

    static Material read(const std::string& name, const Dict& dict);
};

// constant/materials.yaml: every top-level key is a material.
std::map<std::string, Material> readMaterials(const Dict& dict);

} // namespace mag
