// The Python module `magfoam` (docs/python.md): systems built from Python,
// case folders, the registered model types. It is a thin layer over
// libmagCore and the apps' evaluation code; the models arrive as the plugins
// the apps load (build/lib, or MAG_PLUGIN_PATH).
#include "CaseBinding.hpp"
#include "System.hpp"

#include <magFoam/AppliedField.hpp>
#include <magFoam/Error.hpp>
#include <magFoam/FieldEvaluator.hpp>
#include <magFoam/InductionModel.hpp>
#include <magFoam/Log.hpp>
#include <magFoam/Plugins.hpp>
#include <magFoam/RigidBodyBackend.hpp>
#include <magFoam/Threads.hpp>

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

namespace py = pybind11;

namespace {

template <class Base> std::vector<std::string> typeNames() { return Base::registry().names(); }

} // namespace

PYBIND11_MODULE(magfoam, m) {
    m.doc() = "magFoam from Python: fields, forces and runs of rigid magnets (docs/python.md)";
    m.attr("__version__") = MAG_VERSION;

    // Bad input names file:line:col (or the argument), the key and what was expected.
    py::register_exception<mag::InputError>(m, "InputError", PyExc_ValueError);
    py::register_exception<mag::StateError>(m, "StateError", PyExc_RuntimeError);
    // A result file that cannot be written (full disk, permissions): names the file.
    py::register_exception<mag::OutputError>(m, "OutputError", PyExc_OSError);

    // Warnings and errors only: a notebook should not fill with the apps' progress lines.
    mag::log::init("warn");
    mag::plugins::loadStandardModules();

    m.def(
        "modules",
        [] {
            py::dict out;
            out["field"] = typeNames<mag::FieldEvaluator>();
            out["induction"] = typeNames<mag::InductionModel>();
            out["rigidBody"] = typeNames<mag::RigidBodyBackend>();
            out["appliedField"] = typeNames<mag::AppliedField>();
            return out;
        },
        "The registered model types per registry (field, induction, rigidBody, appliedField).");
    m.def(
        "load", [](const std::string& lib) { return mag::plugins::load(lib); }, py::arg("library"),
        "Load a plugin library (bare name like magFoo, or a path), as controlDict libs:; True when newly loaded.");
    m.def(
        "set_log_level", [](const std::string& level) { mag::log::init(level); }, py::arg("level"),
        "The log's level: trace, debug, info (the apps' progress lines), warn (the default), error.");
    m.def(
        "available_cores", [] { return mag::availableCores(); }, "Cores this process may use.");

    mag::python::bindSystem(m);
    mag::python::bindCase(m);
}
