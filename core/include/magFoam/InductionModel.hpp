// InductionModel: converges the magnetizations of soft bodies in the field of
// all other bodies (paper Sec. 4.3, Algorithm 1 lines 3-12). Selected by
// system/magSchemes.yaml `induction: {type: ...}`; `none` (built in) leaves
// magnetizations as they are.
#pragma once

#include "magFoam/Body.hpp"
#include "magFoam/Wrench.hpp"
#include "magFoam/Dictionary.hpp"
#include "magFoam/Registry.hpp"

#include <iosfwd>
#include <memory>
#include <string>
#include <vector>

namespace mag {

class AppliedField;
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

    // Update the magnetization of every soft body in `bodies` (others fixed)
    // in the field of the other bodies and the applied field (AppliedField.hpp).
    virtual InductionReport converge(std::vector<Body>& bodies, const FieldEvaluator& field,
                                     const AppliedField& applied) = 0;
    // Without an applied field.
    InductionReport converge(std::vector<Body>& bodies, const FieldEvaluator& field);
    virtual std::string describe() const = 0;

    // The scene's magnetic energy (J) from the wrenches at the converged
    // magnetizations (docs/physics.md#energy). The default counts every pair
    // once and each soft body's interaction and applied-field energy at half,
    // the energy -1/2 m . B of a linear induced moment; a model with a
    // material law adds each soft body's own energy instead.
    virtual double sceneEnergy(const std::vector<Body>& bodies, const std::vector<Wrench>& wrenches) const;

    // Restart state (docs/architecture.md): what the model carries from one
    // converge() call to the next beyond the bodies' magnetizations. The
    // solver writes it at every write time as <time>/induction.yaml and hands
    // that file back at a restart (startFrom: latestTime), so that the
    // restarted run continues bit for bit. writeState emits the file's YAML,
    // every number exact (formatExact, ResultsWriter.hpp), and should begin
    // with `type: <model>`; writing nothing (the default) means no state, and
    // no file. readState gets the file back with the bodies as restarted.
    virtual void writeState(std::ostream& /*yaml*/, const std::vector<Body>& /*bodies*/) const {}
    virtual void readState(const Dict& /*state*/, const std::vector<Body>& /*bodies*/) {}

    using Registry = mag::Registry<InductionModel>;
    static Registry& registry();
    static std::unique_ptr<InductionModel> New(const Dict& dict);

    template <class T> struct Add {
        explicit Add(const std::string& name, TypeDoc doc = {}) {
            noteModelLayout(sizeof(Body), alignof(Quat));
            registry().add(
                name, [](const Dict& d) { return std::unique_ptr<InductionModel>(new T(d)); }, std::move(doc));
        }
    };
};

} // namespace mag
