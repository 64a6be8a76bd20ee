#include "Convert.hpp"

#include <magFoam/Error.hpp>

#include <charconv>
#include <cmath>
#include <cstring>

namespace mag::python {

YAML::Node toNode(const py::handle& value, const std::string& path) {
    // numpy scalars and arrays: as the Python numbers and lists they hold.
    if (py::hasattr(value, "tolist") && !py::isinstance<py::str>(value)) return toNode(value.attr("tolist")(), path);
    if (value.is_none()) return YAML::Node(YAML::NodeType::Null);
    if (py::isinstance<py::bool_>(value)) return YAML::Node(value.cast<bool>() ? "true" : "false");
    if (py::isinstance<py::int_>(value)) return YAML::Node(py::str(value).cast<std::string>());
    if (py::isinstance<py::float_>(value)) {
        // Shortest round-trip text: the Dict reader's strtod gets the same double back.
        char buf[64];
        const auto r = std::to_chars(buf, buf + sizeof buf, value.cast<double>());
        return YAML::Node(std::string(buf, r.ptr));
    }
    if (py::isinstance<py::str>(value)) return YAML::Node(value.cast<std::string>());
    if (py::hasattr(value, "__fspath__")) return YAML::Node(py::str(value.attr("__fspath__")()).cast<std::string>());
    if (py::isinstance<py::dict>(value)) {
        YAML::Node map(YAML::NodeType::Map);
        map.SetStyle(YAML::EmitterStyle::Flow);  // messages quote values as [0, 1], {n: 4}
        for (const auto& [k, v] : value.cast<py::dict>()) {
            if (!py::isinstance<py::str>(k))
                throw py::type_error(path + ": keys must be strings, got " + py::repr(k).cast<std::string>());
            const std::string key = k.cast<std::string>();
            map[key] = toNode(v, path.empty() ? key : path + "." + key);
        }
        return map;
    }
    if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
        YAML::Node seq(YAML::NodeType::Sequence);
        seq.SetStyle(YAML::EmitterStyle::Flow);
        std::size_t i = 0;
        for (const auto& item : value) seq.push_back(toNode(item, path + "[" + std::to_string(i++) + "]"));
        return seq;
    }
    throw py::type_error(path + ": expected a number, string, list or dict, got " +
                         py::str(py::type::of(value).attr("__name__")).cast<std::string>());
}

Dict toDict(const py::handle& value, const std::string& name) {
    if (value.is_none()) return Dict::fromNode(YAML::Node(YAML::NodeType::Map), name);
    if (!py::isinstance<py::dict>(value))
        throw py::type_error(name + ": expected a dict, got " +
                             py::str(py::type::of(value).attr("__name__")).cast<std::string>());
    return Dict::fromNode(toNode(value, ""), name);
}

Vec3View viewVec3s(const py::handle& value, const std::string& what) {
    Vec3View v;
    try {
        v.array = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(value);
    } catch (const py::error_already_set&) {
    }
    const auto& a = v.array;
    if (!a || a.ndim() < 1 || a.shape(a.ndim() - 1) != 3) {
        std::string got = py::str(py::type::of(value).attr("__name__")).cast<std::string>();
        if (a) {
            got = "shape (";
            for (py::ssize_t i = 0; i < a.ndim(); ++i) got += (i ? ", " : "") + std::to_string(a.shape(i));
            got += a.ndim() == 1 ? ",)" : ")";
        }
        throw InputError(what + ": expected an array of shape (n, 3), got " + got);
    }
    const std::size_t n = static_cast<std::size_t>(a.size() / 3);
    const double* p = a.data();
    for (std::size_t i = 0; i < 3 * n; ++i)
        if (!std::isfinite(p[i]))
            throw InputError(what + "[" + std::to_string(i / 3) + "]: expected 3 finite numbers, got [" +
                             std::to_string(p[i - i % 3]) + ", " + std::to_string(p[i - i % 3 + 1]) + ", " +
                             std::to_string(p[i - i % 3 + 2]) + "]");
    v.vectors = std::span<const Vec3>(reinterpret_cast<const Vec3*>(p), n);
    v.leading.assign(a.shape(), a.shape() + a.ndim() - 1);
    return v;
}

std::vector<Vec3> toVec3s(const py::handle& value, const std::string& what) {
    const Vec3View v = viewVec3s(value, what);
    return std::vector<Vec3>(v.vectors.begin(), v.vectors.end());
}

std::pair<py::array_t<double>, std::span<Vec3>> newVec3s(const std::vector<py::ssize_t>& leading) {
    std::vector<py::ssize_t> shape = leading;
    shape.push_back(3);
    py::array_t<double> a(shape);
    const std::size_t n = static_cast<std::size_t>(a.size() / 3);
    return {a, std::span<Vec3>(reinterpret_cast<Vec3*>(a.mutable_data()), n)};
}

py::array_t<double> toArray(const std::vector<Vec3>& v, std::optional<std::vector<py::ssize_t>> shape) {
    std::vector<py::ssize_t> dims = shape.value_or(std::vector<py::ssize_t>{static_cast<py::ssize_t>(v.size())});
    dims.push_back(3);
    py::array_t<double> a(dims);
    double* p = a.mutable_data();
    for (std::size_t i = 0; i < v.size(); ++i) std::memcpy(p + 3 * i, v[i].data(), 3 * sizeof(double));
    return a;
}

py::array_t<double> toArray(const Vec3& v) {
    py::array_t<double> a(3);
    std::memcpy(a.mutable_data(), v.data(), 3 * sizeof(double));
    return a;
}

py::array_t<double> toArray(const Quat& q) {
    py::array_t<double> a(4);
    double* p = a.mutable_data();
    p[0] = q.w(), p[1] = q.x(), p[2] = q.y(), p[3] = q.z();
    return a;
}

} // namespace mag::python
