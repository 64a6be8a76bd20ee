// InductionModel: converges the magnetizations of soft bodies in the field of
// all other bodies (paper Sec. 4.3, Algorithm 1 lines 3-12). Selected by
// system/magSchemes.yaml `induction: {type: ...}`; `none` (built in) leaves
// magnetizations as they are.
#pragma once

#include "magFoam/Body.hpp"
#include "magFoam/Dictionary.hpp"
#include "magFoam/Registry.hpp"

#include <memory>
#include <string>
#include <vector>

namespace mag {

class FieldEvaluator;

struct InductionReport {
    int iterations = 0;
    double residual = 0;    // largest relative change of a magnetization
    bool converged = true;
    std::vector<std::string> unconverged;  // names of bodies still changing
};

class InductionModel {
public:
    virtual ~InductionModel() = default;

    // Update the magnetization of every soft body in `bodies` (others fixed).
    virtual InductionReport converge(std::vector<Body>& bodies, const FieldEvaluator& field) = 0;
    virtual std::string describe() const = 0;

    using Registry = mag::Registry<InductionModel>;
    static Registry& registry();
    static std::unique_ptr<InductionModel> New(const Dict& dict);

    template <class T> struct Add {
        explicit Add(const std::string& name) {
            registry().add(name, [](const Dict& d) { return std::unique_ptr<InductionModel>(new T(d)); });
        }
    };
};

} // namespace mag
