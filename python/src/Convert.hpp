// Python values to magFoam's inputs and numpy arrays from its results.
//
// Dictionaries from Python (System(field=...), add_body(...)) are turned into
// YAML nodes and read by the same Dict reader as the case files, so that
// unknown keys and bad values give the same messages (Dict::fromNode: the
// message names the argument where a file's line:column would be).
#pragma once

#include <magFoam/Dictionary.hpp>
#include <magFoam/Types.hpp>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <optional>
#include <span>
#include <utility>
#include <string>
#include <vector>

namespace mag::python {

namespace py = pybind11;

// numpy rows of 3 doubles are read and written as Vec3 in place: Eigen's
// 3-vector of doubles is exactly 3 packed doubles, aligned as a double.
static_assert(sizeof(Vec3) == 3 * sizeof(double) && alignof(Vec3) <= alignof(double));

// A Python value as a YAML node: dict -> mapping (str keys), list, tuple and
// numpy arrays -> sequence, bool -> true/false, int, float (shortest text that
// reads back to the same double), str and os.PathLike -> scalar, None -> null.
// TypeError naming `path` (e.g. "field.quadrature") for anything else.
YAML::Node toNode(const py::handle& value, const std::string& path);

// A Python dict (None: an empty one) as a Dict named `name` in messages.
Dict toDict(const py::handle& value, const std::string& name);

// An array of shape (..., 3) (any float-convertible dtype) seen as world
// vectors without a copy when it is already C-contiguous float64 (else
// converted once); InputError naming `what` for another shape or a
// non-finite entry. `leading` is the shape without its last axis.
struct Vec3View {
    py::array_t<double, py::array::c_style | py::array::forcecast> array;  // keeps the data alive
    std::span<const Vec3> vectors;
    std::vector<py::ssize_t> leading;
};
Vec3View viewVec3s(const py::handle& value, const std::string& what);
std::vector<Vec3> toVec3s(const py::handle& value, const std::string& what);

// A new float64 array of shape leading + (3,), and its data as vectors.
std::pair<py::array_t<double>, std::span<Vec3>> newVec3s(const std::vector<py::ssize_t>& leading);

// Vectors as a float64 array of shape (n, 3), or shape + (3,) when given (the
// product of `shape` must be n; an empty shape: one vector, shape (3,)).
py::array_t<double> toArray(const std::vector<Vec3>& v, std::optional<std::vector<py::ssize_t>> shape = {});
py::array_t<double> toArray(const Vec3& v);
py::array_t<double> toArray(const Quat& q);  // [w, x, y, z]

} // namespace mag::python
