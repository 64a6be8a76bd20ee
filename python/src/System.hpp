// magfoam.System: bodies built in Python, evaluated by the same MagneticSystem
// as the apps (models from the registries, plugins loaded as the apps load
// them). Every evaluation releases the GIL and runs on the worker threads
// (Threads.hpp); a mutex keeps two Python threads from evaluating one system
// at once.
#pragma once

#include <magFoam/Body.hpp>
#include <magFoam/Case.hpp>
#include <magFoam/MagneticSystem.hpp>
#include <magFoam/ShapeFactory.hpp>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace mag::python {

namespace py = pybind11;

class System {
public:
    // field / induction: magSchemes.yaml's `field:` and `induction:` mappings;
    // applied: constant/appliedField.yaml; materials: constant/materials.yaml.
    System(const py::object& field, const py::object& induction, const py::object& applied,
           const py::object& materials, int threads);
    // The models and bodies of a case (magfoam.Case.system()).
    System(const Case& c, int threads);

    // One body, as an entry of constant/bodies.yaml (docs/python.md#bodies).
    void addBody(const std::string& name, const py::kwargs& kwargs);

    // Move a body; quaternion [w, x, y, z] (normalized, as bodies.yaml reads it).
    void setPose(const std::string& name, const py::object& position, const py::object& quaternion);
    py::tuple pose(const std::string& name) const;
    std::vector<std::string> names() const;

    // (F, T) of one body, every body, and many poses of one body: N, and N m
    // about the centre of mass (magnetic Eq. 17 + mechanical Eq. 18).
    py::tuple wrench(const std::string& name);
    py::dict wrenches();
    py::tuple sweep(const std::string& name, const py::object& positions, const py::object& quaternions);
    // The scene's magnetic energy, J (MagneticSystem::magneticEnergy: soft bodies as the induction model counts them).
    double energy();

    // B (T) at points of shape (..., 3), and A (T m), H (A/m) when asked.
    py::object field(const py::object& points, bool withA, bool withH);

    std::string describe() const;

private:
    std::size_t index(const std::string& name, const std::string& context) const;
    // Converge soft bodies, then every body's wrench (the magForces step).
    std::vector<Wrench> evaluate();

    std::unique_ptr<MagneticSystem> system_;
    std::vector<Body> bodies_;
    std::map<std::string, Material> materials_;
    ShapeCache shapes_;
    int threads_ = 1;
    mutable std::mutex mutex_;  // held while evaluating (GIL released) or changing bodies_
};

void bindSystem(py::module_& m);

} // namespace mag::python
