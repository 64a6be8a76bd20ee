// A test plugin: a rigid-body backend that fails, as an engine can (ODE's
// internal assertions), in a given step, after it has moved the bodies part
// of the way; to test that magFoam names the step and writes the last good
// state. Until then it moves dynamic bodies in free flight under their forces.
#include <magFoam/Error.hpp>
#include <magFoam/RigidBodyBackend.hpp>

#include <string>

namespace {

class FailingBackend final : public mag::RigidBodyBackend {
public:
    explicit FailingBackend(const mag::Dict& d) : failAtStep_(d.get<int>("failAtStep")) { d.reportUnused(); }
    void setup(const std::vector<mag::Body>&) override {}
    void step(std::vector<mag::Body>& bodies, std::span<const mag::Wrench> wrenches, double dt) override {
        ++steps_;
        for (std::size_t i = 0; i < bodies.size(); ++i) {
            mag::Body& b = bodies[i];
            if (b.fixed) continue;
            b.velocity += dt * wrenches[i].force / b.mass();
            b.position += dt * b.velocity;
        }
        if (steps_ == failAtStep_) {
            for (mag::Body& b : bodies)
                if (!b.fixed) b.velocity.x() = 1e3; // what a step half done leaves
            throw mag::StateError("test backend failure in its step " + std::to_string(steps_));
        }
    }
    void setState(const std::vector<mag::Body>&) override {}
    std::string describe() const override { return "testFailingBackend"; }

private:
    int failAtStep_;
    int steps_ = 0;
};

const mag::RigidBodyBackend::Add<FailingBackend> addFailing("testFailingBackend");

} // namespace
