#include "CaseBinding.hpp"

#include "Convert.hpp"
#include "System.hpp"

#include "ForceSweep.hpp"
#include "Solver.hpp"

#include <magFoam/BodyOverlap.hpp>
#include <magFoam/Case.hpp>
#include <magFoam/Error.hpp>
#include <magFoam/MagneticSystem.hpp>
#include <magFoam/Threads.hpp>

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cmath>
#include <filesystem>
#include <mutex>
#include <optional>

namespace mag::python {

namespace {

namespace py = pybind11;

// Rows of k x nBodies values as an array of shape (k, nBodies, width).
template <class Get>
py::array_t<double> table(std::size_t k, std::size_t nBodies, py::ssize_t width, Get get) {
    py::array_t<double> a({static_cast<py::ssize_t>(k), static_cast<py::ssize_t>(nBodies), width});
    auto v = a.mutable_unchecked<3>();
    for (std::size_t s = 0; s < k; ++s)
        for (std::size_t b = 0; b < nBodies; ++b)
            for (py::ssize_t c = 0; c < width; ++c) v(s, b, c) = get(s, b, c);
    return a;
}

class PyCase {
public:
    PyCase(const std::filesystem::path& dir, const std::optional<std::filesystem::path>& schemes,
           std::optional<int> threads)
        : case_(Case::read(dir, schemes.value_or(std::filesystem::path()))), threads_(threads) {
        // The models are built now, so that a bad magSchemes.yaml fails here.
        applyThreads();
        system_ = std::make_unique<MagneticSystem>(case_);
    }

    // As magForces: the configuration or system/forcesDict.yaml's sweep.
    py::dict forces() {
        struct Row {
            int step;
            double offset;
            std::vector<Wrench> w;
        };
        std::vector<Row> rows;
        std::optional<forces::Sweep> sweep;
        double seconds = 0;
        {
            py::gil_scoped_release release;
            std::lock_guard lock(mutex_);
            applyThreads();
            warnOverlaps(case_.bodies(), (case_.dir() / "constant" / "bodies.yaml").string(),
                         "their forces follow the overlap model (docs/physics.md#overlap-models), not a contact");
            sweep = forces::readForcesDict(case_);
            std::vector<Body> bodies = case_.bodies();  // each call starts from the case's state
            seconds = forces::evaluate(bodies, *system_, sweep, [&](const forces::Evaluation& e) {
                rows.push_back(Row{e.step, e.offset, e.wrenches});
            });
        }
        const std::size_t n = case_.bodies().size(), k = rows.size();
        py::dict out;
        out["bodies"] = names();
        if (sweep) {
            std::vector<int> steps;
            std::vector<double> offsets;
            for (const Row& r : rows) steps.push_back(r.step), offsets.push_back(r.offset);
            out["step"] = py::array(py::cast(steps));
            out[sweep->rotate ? "angle" : "offset"] = py::array(py::cast(offsets));
        }
        out["F"] = table(k, n, 3, [&](auto s, auto b, auto c) { return rows[s].w[b].force[c]; });
        out["T"] = table(k, n, 3, [&](auto s, auto b, auto c) { return rows[s].w[b].totalTorque()[c]; });
        out["Tmag"] = table(k, n, 3, [&](auto s, auto b, auto c) { return rows[s].w[b].torque[c]; });
        out["energy"] = table(k, n, 1, [&](auto s, auto b, auto) { return rows[s].w[b].bodyEnergy(); })
                            .attr("reshape")(k, n);
        out["seconds"] = seconds;  // converging and the wrenches, as magForces times them
        return out;
    }

    // As magFoam, writing the same files into the case folder.
    py::dict run(std::optional<double> endTime, bool strict) {
        if (endTime && !(std::isfinite(*endTime) && *endTime > case_.control().startTime))
            throw InputError("magfoam.Case.run: end_time: expected a finite time > startTime (" +
                             std::to_string(case_.control().startTime) + " s), got " + std::to_string(*endTime));
        struct Record {
            double t;
            long step;
            std::vector<BodyState> states;
            std::vector<Wrench> w;
            Energies e;
        };
        std::vector<Record> records;
        {
            py::gil_scoped_release release;
            std::lock_guard lock(mutex_);
            applyThreads();
            Case c = case_;  // the run moves the bodies of a copy: run() again starts where the case does
            solver::RunOptions options;
            options.strict = strict;
            options.endTime = endTime;
            options.onWrite = [&](const solver::WriteRecord& r) {
                records.push_back(Record{r.time, r.step, std::vector<BodyState>(r.bodies.begin(), r.bodies.end()),
                                         r.wrenches, r.energies});
            };
            solver::run(c, options);
        }
        const std::size_t n = case_.bodies().size(), k = records.size();
        py::dict out;
        std::vector<double> t, kinetic, gravitational, magnetic, total;
        std::vector<long> steps;
        for (const Record& r : records) {
            t.push_back(r.t), steps.push_back(r.step);
            kinetic.push_back(r.e.kinetic), gravitational.push_back(r.e.gravitational);
            magnetic.push_back(r.e.magnetic), total.push_back(r.e.total());
        }
        out["bodies"] = names();
        out["time"] = py::array(py::cast(t));
        out["step"] = py::array(py::cast(steps));
        auto state = [&](auto get, py::ssize_t width) {
            return table(k, n, width, [&](auto s, auto b, auto c) { return get(records[s].states[b], c); });
        };
        out["position"] = state([](const BodyState& s, auto c) { return s.position[c]; }, 3);
        out["quaternion"] = state(
            [](const BodyState& s, auto c) {
                const double q[4] = {s.orientation.w(), s.orientation.x(), s.orientation.y(), s.orientation.z()};
                return q[c];
            },
            4);
        out["velocity"] = state([](const BodyState& s, auto c) { return s.velocity[c]; }, 3);
        out["angularVelocity"] = state([](const BodyState& s, auto c) { return s.angularVelocity[c]; }, 3);
        out["F"] = table(k, n, 3, [&](auto s, auto b, auto c) { return records[s].w[b].force[c]; });
        out["T"] = table(k, n, 3, [&](auto s, auto b, auto c) { return records[s].w[b].totalTorque()[c]; });
        py::dict energy;
        energy["kinetic"] = py::array(py::cast(kinetic));
        energy["gravitational"] = py::array(py::cast(gravitational));
        energy["magnetic"] = py::array(py::cast(magnetic));
        energy["total"] = py::array(py::cast(total));
        out["energy"] = energy;
        return out;
    }

    std::unique_ptr<System> system() const { return std::make_unique<System>(case_, threads()); }

    std::vector<std::string> names() const {
        std::vector<std::string> out;
        for (const auto& b : case_.bodies()) out.push_back(b.name);
        return out;
    }
    std::string dir() const { return case_.dir().string(); }
    std::string describe() const {
        return "magfoam.Case('" + dir() + "', " + std::to_string(case_.bodies().size()) +
               " bodies, field: " + system_->fieldEvaluator().describe() + ")";
    }

private:
    // -threads N when given, else controlDict threads (1 without a controlDict), as the apps.
    int threads() const {
        if (threads_) return *threads_;
        return std::filesystem::exists(case_.dir() / "system/controlDict.yaml") ? case_.control().threads : 1;
    }
    void applyThreads() const { setThreads(threads()); }

    Case case_;
    std::optional<int> threads_;
    std::unique_ptr<MagneticSystem> system_;
    std::mutex mutex_;  // one evaluation at a time (the GIL is released meanwhile)
};

} // namespace

void bindCase(py::module_& m) {
    py::class_<PyCase>(m, "Case", R"(A case folder, read as the apps read it (docs/python.md#cases).

Case(path, schemes=None, threads=None)
  schemes: replaces system/magSchemes.yaml (as -schemes); threads: as -threads
  (default: controlDict threads).)")
        .def(py::init<const std::filesystem::path&, const std::optional<std::filesystem::path>&, std::optional<int>>(),
             py::arg("path"), py::arg("schemes") = py::none(), py::arg("threads") = py::none())
        .def("forces", &PyCase::forces,
             R"(magForces in memory: the configuration, or the sweep of system/forcesDict.yaml.

Returns a dict: bodies (names), F, T, Tmag (k, n, 3) (N, N m about the centre
of mass, the magnetic part), energy (k, n) (J), for a sweep step (k,) and
offset (m) or angle (degrees) (k,); k = 1 without a sweep; seconds: the time
spent converging and in the wrenches, as magForces' "ms each".)")
        .def("run", &PyCase::run, py::arg("end_time") = py::none(), py::arg("strict") = false,
             R"(magFoam: the transient run (writes the same files into the case folder).

end_time replaces controlDict endTime; strict stops on an audit warning.
Returns, per write time: bodies, time (k,), step (k,), position, velocity,
angularVelocity, F, T (k, n, 3), quaternion (k, n, 4) [w, x, y, z], energy
{kinetic, gravitational, magnetic, total} (k,) in SI units.)")
        .def("system", &PyCase::system, "A magfoam.System with the case's models and bodies.")
        .def_property_readonly("bodies", &PyCase::names)
        .def_property_readonly("path", &PyCase::dir)
        .def("__repr__", &PyCase::describe);
}

} // namespace mag::python
