// magfoam.Case: a case folder read as the apps read it (Case::read: the same
// files, checks and messages), evaluated by the apps' own code: forces() is
// magForces (ForceSweep.hpp), run() is magFoam (Solver.hpp), with the results
// returned as numpy arrays.
#pragma once

#include <pybind11/pybind11.h>

namespace mag::python {

void bindCase(pybind11::module_& m);

} // namespace mag::python
