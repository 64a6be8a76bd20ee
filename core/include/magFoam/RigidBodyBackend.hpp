// RigidBodyBackend: moves the bodies under the magnetic wrenches, gravity and
// contacts. Selected by constant/rigidBody.yaml `type:` (ODE, free).
#pragma once

#include "magFoam/Body.hpp"
#include "magFoam/Dictionary.hpp"
#include "magFoam/FieldEvaluator.hpp"
#include "magFoam/Registry.hpp"

#include <memory>
#include <span>
#include <string>
#include <vector>

namespace mag {

class RigidBodyBackend {
public:
    virtual ~RigidBodyBackend() = default;

    // Called once with the bodies of the case before the first step.
    virtual void setup(const std::vector<Body>& bodies) = 0;

    // Advance by dt with the given external wrench per body (world frame,
    // torques about each COM) and write the new state back into `bodies`.
    virtual void step(std::vector<Body>& bodies, std::span<const Wrench> wrenches, double dt) = 0;

    virtual std::string describe() const = 0;

    using Registry = mag::Registry<RigidBodyBackend>;
    static Registry& registry();
    static std::unique_ptr<RigidBodyBackend> New(const Dict& dict);

    template <class T> struct Add {
        explicit Add(const std::string& name) {
            registry().add(name, [](const Dict& d) { return std::unique_ptr<RigidBodyBackend>(new T(d)); });
        }
    };
};

} // namespace mag
