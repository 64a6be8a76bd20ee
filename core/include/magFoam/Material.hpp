// Materials (constant/materials.yaml):
//
//   N42:   {model: permanent, Br: 1.3, density: 7500}     # Br: remanence, T
//   steel: {model: soft, k: 5.0, Js: 2.0, density: 7850}  # k: induction control
//                                                         # (D = I/k, Eq. 19);
//                                                         # Js = mu0 Ms, T
//
// | key     | model     | required | unit  | meaning                          |
// |---------|-----------|----------|-------|----------------------------------|
// | model   | both      | yes      |       | permanent or soft                |
// | density | both      | yes      | kg/m3 | > 0                              |
// | Br      | permanent | yes      | T     | remanence, |M| = Br/mu0, >= 0    |
// | k       | soft      | yes      |       | > 0, M = k B/mu0 below saturation|
// | Js      | soft      | yes      | T     | saturation polarization, > 0     |
// | alpha   | soft      | no (0.5) |       | LLG damping (Eq. 20)             |
#pragma once

#include "magFoam/Dictionary.hpp"

#include <map>
#include <string>

namespace mag {

struct Material {
    enum class Model { permanent, soft };
    std::string name;
    Model model = Model::permanent;
    double density = 0;  // kg/m^3
    double Br = 0;       // T (permanent)
    double k = 0;        // induction control parameter (soft)
    double Js = 0;       // saturation polarization mu0*Ms, T (soft)
    double alpha = 0.5;  // LLG damping (soft)

    bool soft() const { return model == Model::soft; }
    static Material read(const std::string& name, const Dict& dict);
};

// constant/materials.yaml: every top-level key is a material.
std::map<std::string, Material> readMaterials(const Dict& dict);

} // namespace mag
