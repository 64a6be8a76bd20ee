#include "System.hpp"

#include "Convert.hpp"

#include <magFoam/Error.hpp>
#include <magFoam/Log.hpp>
#include <magFoam/Threads.hpp>
#include <magFoam/Wrench.hpp>

#include <pybind11/stl.h>

#include <cmath>
#include <filesystem>

namespace mag::python {

namespace {

// Permanent magnets given by Br alone: a density for the mass properties
// (sintered NdFeB), which the field and force never use.
constexpr double kDefaultDensity = 7500;  // kg/m^3

std::string argName(const std::string& method, const std::string& name) {
    return "magfoam.System." + method + "('" + name + "')";
}

std::unique_ptr<MagneticSystem> makeSystem(const py::object& field, const py::object& induction,
                                           const py::object& applied) {
    // One mapping like system/magSchemes.yaml, so that keys read `field.type`.
    py::dict schemes;
    schemes["field"] = field.is_none() ? py::object(py::dict(py::arg("type") = "MBM")) : field;
    if (!induction.is_none()) schemes["induction"] = induction;
    const Dict d = toDict(schemes, "magfoam.System");
    auto f = FieldEvaluator::New(d.sub("field"));
    auto i = InductionModel::New(d.has("induction") ? d.sub("induction")
                                                    : Dict::fromString("type: none", "magfoam.System"));
    auto a = AppliedField::New(applied.is_none() ? Dict::fromString("type: none", "magfoam.System(applied=...)")
                                                 : toDict(applied, "magfoam.System(applied=...)"));
    d.reportUnused();
    return std::make_unique<MagneticSystem>(std::move(f), std::move(i), std::move(a));
}

// (V, F) arrays as a surface mesh: V (n, 3) metres, F (m, 3) vertex indices.
SurfaceMesh meshFromArrays(const py::handle& value, const std::string& what) {
    if (!py::isinstance<py::tuple>(value) && !py::isinstance<py::list>(value))
        throw InputError(what + ": mesh: expected (vertices, faces), arrays of shape (n, 3) and (m, 3)");
    const py::sequence vf = value.cast<py::sequence>();
    if (vf.size() != 2) throw InputError(what + ": mesh: expected (vertices, faces), got " +
                                         std::to_string(vf.size()) + " items");
    SurfaceMesh mesh;
    mesh.vertices = toVec3s(vf[0], what + ": mesh vertices");
    const auto f = py::array_t<long long, py::array::c_style | py::array::forcecast>::ensure(vf[1]);
    if (!f || f.ndim() != 2 || f.shape(1) != 3) throw InputError(what + ": mesh faces: expected an array of shape (m, 3)");
    const long long* p = f.data();
    for (py::ssize_t t = 0; t < f.shape(0); ++t) {
        std::array<int, 3> tri{};
        for (int k = 0; k < 3; ++k) {
            const long long v = p[3 * t + k];
            if (v < 0 || v >= static_cast<long long>(mesh.vertices.size()))
                throw InputError(what + ": mesh faces[" + std::to_string(t) + "]: vertex index " + std::to_string(v) +
                                 " out of range 0.." + std::to_string(mesh.vertices.size() - 1));
            tri[k] = static_cast<int>(v);
        }
        mesh.triangles.push_back(tri);
    }
    mesh.source = what + " mesh";
    return mesh;
}

Quat toQuat(const double* c, const std::string& what) {
    const Quat q(c[0], c[1], c[2], c[3]);
    if (!q.coeffs().allFinite()) throw InputError(what + ": expected a quaternion of 4 finite numbers [w, x, y, z]");
    if (q.norm() < 1e-12) throw InputError(what + ": quaternion has zero length");
    return q.normalized();
}

py::tuple pair(const Wrench& w) { return py::make_tuple(toArray(w.force), toArray(w.totalTorque())); }

} // namespace

System::System(const py::object& field, const py::object& induction, const py::object& applied,
               const py::object& materials, int threads)
    : system_(makeSystem(field, induction, applied)), threads_(threads) {
    if (!materials.is_none()) materials_ = readMaterials(toDict(materials, "magfoam.System(materials=...)"));
}

System::System(const Case& c, int threads)
    : system_(std::make_unique<MagneticSystem>(c)), bodies_(c.bodies()), materials_(c.materials()), threads_(threads) {}

void System::addBody(const std::string& name, const py::kwargs& kwargs) {
    const std::string what = argName("add_body", name);
    for (const Body& b : bodies_)
        if (b.name == name) throw InputError(what + ": name: duplicate body name '" + name + "'");
    // The bodies.yaml entry; keys not taken here go to the reader as they are,
    // which names any it does not know.
    py::dict entry;
    for (const auto& [k, v] : kwargs) entry[k] = v;
    auto pop = [&](const char* key) {
        py::object v = entry.contains(key) ? py::object(entry[key]) : py::none();
        if (entry.contains(key)) PyDict_DelItemString(entry.ptr(), key);
        return v;
    };
    entry["name"] = name;
    auto isMap = [](const py::object& o) { return py::isinstance<py::dict>(o); };
    // Files relative to the Python process's working folder, not a case's constant/.
    auto absolute = [](const py::object& path) {
        return std::filesystem::absolute(py::str(py::module_::import("os").attr("fspath")(path)).cast<std::string>())
            .string();
    };
    // A geometry dict with its file made absolute (a copy: the caller's stays as it was).
    auto absoluteGeometry = [&](const py::object& geometry) -> py::object {
        if (!isMap(geometry) || !geometry.contains("file")) return geometry;
        py::dict g = geometry.attr("copy")();
        g["file"] = absolute(g["file"]);
        return g;
    };

    // Pose and motion.
    auto poseAndMotion = [&] {
        const py::object quaternion = pop("quaternion"), fixed = pop("fixed");
        if (!quaternion.is_none()) {
            if (entry.contains("orientation"))
                throw InputError(what + ": quaternion: give quaternion= or orientation=, not both");
            entry["orientation"] = py::dict(py::arg("quaternion") = quaternion);
        }
        if (!fixed.is_none()) {
            if (entry.contains("motion")) throw InputError(what + ": fixed: give fixed= or motion=, not both");
            entry["motion"] = fixed.cast<bool>() ? "fixed" : "dynamic";
        }
        if (!entry.contains("position")) entry["position"] = py::make_tuple(0.0, 0.0, 0.0);
    };

    // A compound (docs/compound-bodies.md): parts as in bodies.yaml, their
    // materials from System(materials=...); the reader checks the rest.
    if (entry.contains("parts")) {
        py::list parts;
        for (const py::handle& p : py::iter(entry["parts"])) {
            py::object part = py::reinterpret_borrow<py::object>(p);
            if (isMap(part) && part.contains("geometry")) {
                py::dict copy = part.attr("copy")();
                copy["geometry"] = absoluteGeometry(copy["geometry"]);
                part = copy;
            }
            parts.append(part);
        }
        entry["parts"] = parts;
        poseAndMotion();
        Body body = readBody(toDict(entry, what), materials_, std::filesystem::current_path(), shapes_);
        std::lock_guard lock(mutex_);
        bodies_.push_back(std::move(body));
        return;
    }

    // Geometry: exactly one form.
    const py::object box = pop("box"), sphere = pop("sphere"), cylinder = pop("cylinder"), mesh = pop("mesh"),
                     file = pop("file"), scale = pop("scale");
    const int forms = !box.is_none() + !sphere.is_none() + !cylinder.is_none() + !mesh.is_none() + !file.is_none() +
                      entry.contains("geometry");
    if (forms != 1)
        throw InputError(what + ": give exactly one geometry: box=[a, b, c], sphere=r, cylinder=(r, h), "
                                "mesh=(vertices, faces), file=path or geometry={...} (" +
                         std::to_string(forms) + " given)");
    if (!scale.is_none() && file.is_none() && mesh.is_none())
        throw InputError(what + ": scale: only with file= or mesh=");
    std::shared_ptr<const Shape> shape;
    if (entry.contains("geometry")) entry["geometry"] = absoluteGeometry(entry["geometry"]);
    if (!box.is_none()) entry["geometry"] = py::dict(py::arg("box") = isMap(box) ? box : py::dict(py::arg("size") = box));
    if (!sphere.is_none())
        entry["geometry"] = py::dict(py::arg("sphere") = isMap(sphere) ? sphere : py::dict(py::arg("radius") = sphere));
    if (!cylinder.is_none()) {
        py::object c = cylinder;
        if (!isMap(c)) {
            const auto rh = py::cast<std::vector<py::object>>(c);
            if (rh.size() != 2) throw InputError(what + ": cylinder: expected (radius, height) in metres");
            c = py::dict(py::arg("radius") = rh[0], py::arg("height") = rh[1]);
        }
        entry["geometry"] = py::dict(py::arg("cylinder") = c);
    }
    if (!file.is_none()) {
        py::dict g(py::arg("file") = absolute(file));
        if (!scale.is_none()) g["scale"] = scale;
        entry["geometry"] = g;
    }
    if (!mesh.is_none()) {
        SurfaceMesh m = meshFromArrays(mesh, what);
        const double s = scale.is_none() ? 1.0 : scale.cast<double>();
        if (!(s > 0) || !std::isfinite(s)) throw InputError(what + ": scale: expected a finite number > 0");
        for (Vec3& v : m.vertices) v *= s;
        ShapeKind kind;
        kind.kind = ShapeKind::Kind::mesh;
        kind.file = m.source;
        shape = makeShape(std::move(m), kind);
    }

    // Material: a name of System(materials=...), a materials.yaml entry, or Br.
    const py::object material = pop("material"), Br = pop("Br"), density = pop("density");
    std::map<std::string, Material> own;
    const std::map<std::string, Material>* materials = &materials_;
    if (!material.is_none() && !Br.is_none())
        throw InputError(what + ": Br: give Br= (a permanent magnet) or material=, not both");
    if (py::isinstance<py::str>(material)) {
        entry["material"] = material;
        if (!density.is_none()) throw InputError(what + ": density: belongs to the material '" +
                                                 material.cast<std::string>() + "'");
    } else {
        py::dict m;
        if (!material.is_none()) {
            if (!isMap(material))
                throw InputError(what + ": material: expected a material name or a dict as in constant/materials.yaml");
            m = material.cast<py::dict>();
        } else if (!Br.is_none()) {
            m["model"] = "permanent", m["Br"] = Br;
        } else {
            throw InputError(what + ": give Br= (remanence of a permanent magnet, T) or material= (a name of "
                                    "System(materials=...) or a dict as in constant/materials.yaml)");
        }
        if (!density.is_none()) m["density"] = density;
        if (!m.contains("density")) m["density"] = kDefaultDensity;
        own.emplace(name, Material::read(name, toDict(m, what + ".material")));
        materials = &own;
        entry["material"] = name;
    }

    poseAndMotion();

    Body body = readBody(toDict(entry, what), *materials, std::filesystem::current_path(), shapes_, shape);
    std::lock_guard lock(mutex_);
    bodies_.push_back(std::move(body));
}

std::size_t System::index(const std::string& name, const std::string& context) const {
    for (std::size_t i = 0; i < bodies_.size(); ++i)
        if (bodies_[i].name == name) return i;
    std::string valid;
    for (const auto& b : bodies_) valid += (valid.empty() ? "" : ", ") + b.name;
    throw InputError(context + ": unknown body '" + name + "'; bodies: " + (valid.empty() ? "(none)" : valid));
}

std::vector<std::string> System::names() const {
    std::lock_guard lock(mutex_);
    std::vector<std::string> out;
    for (const auto& b : bodies_) out.push_back(b.name);
    return out;
}

void System::setPose(const std::string& name, const py::object& position, const py::object& quaternion) {
    const std::string what = argName("set_pose", name);
    const std::size_t i = index(name, what);
    py::dict pose;
    if (!position.is_none()) pose["position"] = position;
    if (!quaternion.is_none()) pose["quaternion"] = quaternion;
    const Dict d = toDict(pose, what);
    std::lock_guard lock(mutex_);
    if (d.has("position")) bodies_[i].position = d.get<Vec3>("position");
    if (d.has("quaternion")) bodies_[i].orientation = d.get<Quat>("quaternion");
}

py::tuple System::pose(const std::string& name) const {
    const std::size_t i = index(name, argName("pose", name));
    Vec3 p;
    Quat q;
    {
        std::lock_guard lock(mutex_);  // not in the middle of another thread's sweep
        p = bodies_[i].position, q = bodies_[i].orientation;
    }
    return py::make_tuple(toArray(p), toArray(q));
}

std::vector<Wrench> System::evaluate() {
    setThreads(threads_);
    const InductionReport ind = system_->converge(bodies_);
    if (!ind.converged) {
        std::string names;
        for (const auto& n : ind.unconverged) names += " " + n;
        spdlog::warn("induction did not converge ({} iterations, residual {:.3g}):{}", ind.iterations, ind.residual,
                     names);
    }
    return system_->wrenches(bodies_);
}

py::tuple System::wrench(const std::string& name) {
    const std::size_t i = index(name, argName("wrench", name));
    std::vector<Wrench> w;
    {
        py::gil_scoped_release release;
        std::lock_guard lock(mutex_);
        w = evaluate();
    }
    return pair(w[i]);
}

py::dict System::wrenches() {
    std::vector<Wrench> w;
    {
        py::gil_scoped_release release;
        std::lock_guard lock(mutex_);
        w = evaluate();
    }
    py::dict out;
    for (std::size_t i = 0; i < bodies_.size(); ++i) out[py::str(bodies_[i].name)] = pair(w[i]);
    return out;
}

double System::energy() {
    py::gil_scoped_release release;
    std::lock_guard lock(mutex_);
    const std::vector<Wrench> w = evaluate();
    return system_->magneticEnergy(bodies_, w);
}

py::tuple System::sweep(const std::string& name, const py::object& positions, const py::object& quaternions) {
    const std::string what = "magfoam.System.sweep('" + name + "')";
    const std::size_t i = index(name, what);
    if (positions.is_none() && quaternions.is_none())
        throw InputError(what + ": give positions=(k, 3) and/or quaternions=(k, 4)");
    std::vector<Vec3> p;
    std::vector<Quat> q;
    if (!positions.is_none()) p = toVec3s(positions, what + ": positions");
    if (!quaternions.is_none()) {
        const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(quaternions);
        if (!a || a.ndim() != 2 || a.shape(1) != 4)
            throw InputError(what + ": quaternions: expected an array of shape (k, 4), rows [w, x, y, z]");
        for (py::ssize_t k = 0; k < a.shape(0); ++k)
            q.push_back(toQuat(a.data() + 4 * k, what + ": quaternions[" + std::to_string(k) + "]"));
    }
    if (!p.empty() && !q.empty() && p.size() != q.size())
        throw InputError(what + ": positions has " + std::to_string(p.size()) + " rows but quaternions " +
                         std::to_string(q.size()));
    const std::size_t n = std::max(p.size(), q.size());
    std::vector<Vec3> F(n), T(n);
    {
        py::gil_scoped_release release;
        std::lock_guard lock(mutex_);
        // The whole state comes back afterwards (soft bodies' magnetizations too):
        // a sweep leaves the system as it found it.
        const std::vector<BodyState> saved(bodies_.begin(), bodies_.end());
        for (std::size_t k = 0; k < n; ++k) {
            if (!p.empty()) bodies_[i].position = p[k];
            if (!q.empty()) bodies_[i].orientation = q[k];
            const std::vector<Wrench> w = evaluate();
            F[k] = w[i].force, T[k] = w[i].totalTorque();
        }
        for (std::size_t b = 0; b < bodies_.size(); ++b) static_cast<BodyState&>(bodies_[b]) = saved[b];
    }
    return py::make_tuple(toArray(F), toArray(T));
}

py::object System::field(const py::object& points, bool withA, bool withH) {
    // In place: the points are read from the caller's array and B, A, H
    // written into the arrays returned (no copies, docs/python.md#performance).
    const Vec3View x = viewVec3s(points, "magfoam.System.field: points");
    auto [B, b] = newVec3s(x.leading);
    py::array_t<double> A, H;
    std::span<Vec3> a, h;
    if (withA) std::tie(A, a) = newVec3s(x.leading);
    if (withH) std::tie(H, h) = newVec3s(x.leading);
    {
        py::gil_scoped_release release;
        std::lock_guard lock(mutex_);
        setThreads(threads_);
        system_->converge(bodies_);  // soft bodies magnetized first, as magField does
        system_->field(bodies_, x.vectors, b, a, h);
    }
    if (!withA && !withH) return std::move(B);
    py::list out;
    out.append(B);
    if (withA) out.append(A);
    if (withH) out.append(H);
    return py::tuple(out);
}

std::string System::describe() const {
    return "magfoam.System(" + std::to_string(bodies_.size()) + " bodies, field: " +
           system_->fieldEvaluator().describe() + ")";
}

void bindSystem(py::module_& m) {
    py::class_<System>(m, "System", R"(Bodies and the models that evaluate them (docs/python.md).

System(field={"type": "MBM"}, induction=None, applied=None, materials=None, threads=1)
  field, induction: the mappings of system/magSchemes.yaml (dicts);
  applied: constant/appliedField.yaml; materials: constant/materials.yaml;
  threads: worker threads of every evaluation (0 = all cores).)")
        .def(py::init<const py::object&, const py::object&, const py::object&, const py::object&, int>(),
             py::arg("field") = py::none(), py::arg("induction") = py::none(), py::arg("applied") = py::none(),
             py::arg("materials") = py::none(), py::arg("threads") = 1)
        .def("add_body", &System::addBody, py::arg("name"),
             R"(Add a body: a bodies.yaml entry as keywords (docs/python.md#bodies).

Geometry, exactly one: box=[a, b, c], sphere=r, cylinder=(r, h), mesh=(V, F),
file=path (STL/OBJ/PLY/OFF; scale=0.001 for mm), geometry={...}.
Material: Br=T (permanent; density= kg/m^3, default 7500) or material= (a name
of System(materials=...) or a materials.yaml dict). magnetization=[x, y, z]
(body frame), position=[x, y, z] (m, default 0), quaternion=[w, x, y, z] or
orientation={...}, fixed=True, velocity=, angularVelocity=.)")
        .def("set_pose", &System::setPose, py::arg("name"), py::arg("position") = py::none(),
             py::arg("quaternion") = py::none(), "Move a body: position (m), quaternion [w, x, y, z] (body to world).")
        .def("pose", &System::pose, py::arg("name"), "(position (3,), quaternion [w, x, y, z] (4,)) of a body.")
        .def_property_readonly("bodies", &System::names, "Body names, in the order they were added.")
        .def("wrench", &System::wrench, py::arg("name"),
             "(F, T) on one body from all others: N, and N m about its centre of mass.")
        .def("wrenches", &System::wrenches, "dict name -> (F, T) for every body.")
        .def("sweep", &System::sweep, py::arg("name"), py::arg("positions") = py::none(),
             py::arg("quaternions") = py::none(),
             "(F (k, 3), T (k, 3)) of one body at k poses (positions (k, 3), quaternions (k, 4)), in one call; "
             "the system is left as it was.")
        .def("energy", &System::energy, "Magnetic energy of the scene, J.")
        .def("field", &System::field, py::arg("points"), py::arg("A") = false, py::arg("H") = false,
             "B (T) of every body (and the applied field) at points of shape (..., 3) in metres; with A=True "
             "or H=True a tuple (B, [A (T m)], [H (A/m)]).")
        .def("__repr__", &System::describe);
}

} // namespace mag::python
