// FieldEvaluator: the field of one magnetized body and the wrench it exerts on
// another (paper Sec. 3 for EDM, Sec. 4 for MBM). Selected at run time from
// system/magSchemes.yaml `field: {type: ...}`.
//
// Contract: all inputs and outputs are in the WORLD frame; torques are about
// the target's centre of mass. Implementations cache per-shape tables (they
// may key them by the Shape pointer: shapes are immutable and shared).
#pragma once

#include "magFoam/Body.hpp"
#include "magFoam/Dictionary.hpp"
#include "magFoam/Registry.hpp"

#include <cstdint>
#include <limits>
#include <memory>
#include <span>
#include <string>

namespace mag {

// Wrench on a target body from one source body.
struct Wrench {
    Vec3 force = Vec3::Zero();            // N (Eq. 16)
    Vec3 torque = Vec3::Zero();           // magnetic torque, N m (Eq. 17)
    Vec3 mechanicalTorque = Vec3::Zero(); // about the target's COM, N m (Eq. 18)
    double energy = 0;                    // interaction energy, J (see the model)

    Vec3 totalTorque() const { return torque + mechanicalTorque; }
    Wrench& operator+=(const Wrench& o) {
        force += o.force, torque += o.torque, mechanicalTorque += o.mechanicalTorque, energy += o.energy;
        return *this;
    }
};

class FieldEvaluator {
public:
    virtual ~FieldEvaluator() = default;

    // Fields of `source` at world points: flux density B (T, always), and when
    // the spans are non-empty the vector potential A (T m) and H (A/m).
    virtual void evaluate(const Body& source, std::span<const Vec3> points, std::span<Vec3> B,
                          std::span<Vec3> A = {}, std::span<Vec3> H = {}) const = 0;

    // Wrench on `target` exerted by `source`.
    virtual Wrench interaction(const Body& source, const Body& target) const = 0;

    // One line for logs: type and main settings.
    virtual std::string describe() const = 0;

    // Far-field tier (DipoleFarField.hpp): a pair of bodies farther apart than
    // dipoleReach(a) + dipoleReach(b) (centres of mass) interacts as two point
    // dipoles, and MagneticSystem evaluates all such pairs in bulk instead of
    // calling interaction(). +inf (the default): never. An evaluator that
    // returns a finite reach must treat such a pair the same way in its own
    // interaction() (dipolePairWrench), so that both paths agree.
    virtual double dipoleReach(const Body&) const { return std::numeric_limits<double>::infinity(); }
    // The system reports how many pairs it took in bulk (for describe()).
    virtual void countDipolePairs(std::uint64_t) const {}

    // Boundary quadrature samples that interaction() takes on a target of this
    // shape (cost reports: magBench's table1, table2); 0, the default, where the
    // model samples no boundary.
    virtual std::size_t boundarySamples(const Shape&) const { return 0; }

    // Registry and selection by `type`.
    using Registry = mag::Registry<FieldEvaluator>;
    static Registry& registry();
    static std::unique_ptr<FieldEvaluator> New(const Dict& dict);

    template <class T> struct Add {
        explicit Add(const std::string& name) {
            registry().add(name, [](const Dict& d) { return std::unique_ptr<FieldEvaluator>(new T(d)); });
        }
    };
};

} // namespace mag
