#include "magFoam/ResultsWriter.hpp"

#include "magFoam/Dictionary.hpp"
#include "magFoam/Error.hpp"
#include "magFoam/Log.hpp"
#include "magFoam/Parts.hpp"
#include "magFoam/VtkWriter.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <regex>
#include <sstream>

namespace mag {

Energies bodyEnergies(const std::vector<Body>& bodies, const Vec3& gravity, double magnetic) {
    Energies e;
    e.magnetic = magnetic;
    for (const auto& b : bodies) {
        if (b.fixed) continue;
        const double m = b.mass();
        e.kinetic += kineticEnergy(b, b);
        e.gravitational -= m * gravity.dot(b.position);
    }
    return e;
}

std::string timeName(double t) {
    const double rounded = std::round(t * 1e12) / 1e12;
    char buf[64];
    auto res = std::to_chars(buf, buf + sizeof buf, rounded == 0 ? 0.0 : rounded);
    return std::string(buf, res.ptr);
}

std::vector<std::filesystem::path> timeFolders(const std::filesystem::path& caseDir) {
    std::vector<std::pair<double, std::filesystem::path>> found;
    std::error_code ec;
    for (const auto& entry : std::filesystem::directory_iterator(caseDir, ec)) {
        if (!entry.is_directory() || !std::filesystem::exists(entry.path() / "bodies.yaml")) continue;
        const std::string name = entry.path().filename().string();
        double t;
        auto [p, err] = std::from_chars(name.data(), name.data() + name.size(), t);
        if (err != std::errc() || p != name.data() + name.size() || !std::isfinite(t)) continue;  // "inf", "nan"
        found.emplace_back(t, entry.path());
    }
    std::sort(found.begin(), found.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
    std::vector<std::filesystem::path> out;
    for (auto& f : found) out.push_back(std::move(f.second));
    return out;
}

std::optional<std::filesystem::path> latestTimeFolder(const std::filesystem::path& caseDir) {
    const auto all = timeFolders(caseDir);
    if (all.empty()) return std::nullopt;
    return all.front();
}

namespace {

// The orientation as written: Dict's Quat is renormalised, which can change
// the last bit of a unit quaternion; a written one is kept exactly when it is
// unit to round-off, renormalised otherwise (edited by hand).
Quat exactOrientation(const Dict& b) {
    const Quat normalized = b.get<Quat>("orientation");  // checks the four numbers
    const std::vector<double> c = b.get<std::vector<double>>("orientation");
    const Quat q(c[0], c[1], c[2], c[3]);
    return std::abs(q.squaredNorm() - 1) <= 1e-14 ? q : normalized;
}

// Nothing non-finite is ever written: a state or result holding NaN or inf
// is refused before the first byte, naming the body and the quantity.
void requireFinite(double time, long step, const std::vector<Body>& bodies, const std::vector<Wrench>* wrenches,
                   const Energies* energies) {
    auto fail = [&](const std::string& what) {
        throw StateError("not written: " + what + " at t = " + formatExact(time) + " s (step " +
                         std::to_string(step) + ") is not finite");
    };
    if (!std::isfinite(time)) fail("the time");
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        const Body& b = bodies[i];
        const std::string body = "body '" + b.name + "': ";
        if (!b.position.allFinite()) fail(body + "position");
        if (!b.orientation.coeffs().allFinite()) fail(body + "orientation");
        if (!b.velocity.allFinite()) fail(body + "velocity");
        if (!b.angularVelocity.allFinite()) fail(body + "angular velocity");
        if (!b.magnetizationBody.allFinite()) fail(body + "magnetization");
        for (const Vec3& m : b.partMagnetization)
            if (!m.allFinite()) fail(body + "a part's magnetization");
        if (wrenches && !((*wrenches)[i].force.allFinite() && (*wrenches)[i].totalTorque().allFinite()))
            fail(body + "force or torque");
    }
    if (energies && !(std::isfinite(energies->kinetic) && std::isfinite(energies->gravitational) &&
                      std::isfinite(energies->magnetic) && std::isfinite(energies->total())))
        fail("an energy (kinetic " + formatExact(energies->kinetic) + ", gravitational " +
             formatExact(energies->gravitational) + ", magnetic " + formatExact(energies->magnetic) + " J)");
}

} // namespace

std::string formatExact(double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.17g", x);
    return buf;
}

std::string formatExact(const Vec3& v) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "[%.17g, %.17g, %.17g]", v.x(), v.y(), v.z());
    return buf;
}

std::size_t stateBodyIndex(const Dict& entry, const std::vector<Body>& bodies) {
    const std::string name = entry.get<std::string>("name");
    std::size_t i = 0;
    while (i < bodies.size() && bodies[i].name != name) ++i;
    if (i == bodies.size()) entry.fail("name", "body '" + name + "' is not in constant/bodies.yaml");
    return i;
}

RestartState readState(const std::filesystem::path& file, std::vector<Body>& bodies) {
    std::error_code ec;
    if (std::filesystem::is_regular_file(file, ec) && std::filesystem::file_size(file, ec) == 0 && !ec)
        throw InputError(file.string() + ": the file is empty (a write that was cut off?)");
    const Dict d = Dict::fromFile(file);
    RestartState s;
    s.time = d.get<double>("time");
    s.step = d.get<int>("step");
    std::vector<bool> seen(bodies.size(), false);
    for (const Dict& b : d.list("bodies")) {
        const std::size_t i = stateBodyIndex(b, bodies);
        const std::string& name = bodies[i].name;
        Body& body = bodies[i];
        body.position = b.get<Vec3>("position");
        body.orientation = exactOrientation(b);
        body.velocity = b.get<Vec3>("velocity");
        body.angularVelocity = b.get<Vec3>("angularVelocity");
        body.magnetizationBody = b.get<Vec3>("magnetization");
        if (body.compound) {
            // Each part's, in its own frame; the mean follows from them.
            const auto rows = b.get<std::vector<std::vector<double>>>("partMagnetization");
            if (rows.size() != body.compound->parts.size())
                b.fail("partMagnetization", fmt::format("{} magnetizations for the {} parts of body '{}'", rows.size(),
                                                        body.compound->parts.size(), name));
            std::vector<Vec3> parts;
            for (const auto& r : rows) {
                if (r.size() != 3) b.fail("partMagnetization", "each part's magnetization is [x, y, z] (A/m)");
                parts.emplace_back(r[0], r[1], r[2]);
            }
            body.partMagnetization = parts;
            body.magnetizationBody = meanMagnetization(*body.compound, parts);
        }
        b.reportUnused();
        seen[i] = true;
    }
    d.reportUnused();
    for (std::size_t i = 0; i < bodies.size(); ++i)
        if (!seen[i]) throw InputError(file.string() + ": no state for body '" + bodies[i].name + "'");
    return s;
}

namespace {

void vec(std::ostream& os, const Vec3& v) { os << formatExact(v); }

} // namespace

ResultsWriter::ResultsWriter(const std::filesystem::path& caseDir, std::optional<double> restartTime,
                             bool sleepColumn)
    : dir_(caseDir), restartTime_(restartTime), sleepColumn_(sleepColumn) {
    const auto post = dir_ / "postProcessing";
    makeFolder(post);
    makeFolder(dir_ / "VTK");
    if (restartTime) {
        cutCsvAfter(post / "bodies.csv", *restartTime);
        cutCsvAfter(post / "energy.csv", *restartTime);
        // Keep the series entries up to the restart time.
        std::ifstream pvd(dir_ / "VTK/bodies.pvd");
        const std::regex entry("timestep=\"([^\"]+)\"[^>]*file=\"([^\"]+)\"");
        std::string line;
        std::smatch m;
        while (std::getline(pvd, line))
            if (std::regex_search(line, m, entry) && std::stod(m[1]) <= *restartTime + 1e-12)
                series_.emplace_back(std::stod(m[1]), m[2]);
    }
    bodiesCsv_ = AppendedFile(post / "bodies.csv",
                              std::string("time,body,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz,Fx,Fy,Fz,Tx,Ty,Tz") +
                                  (sleepColumn ? ",asleep" : ""),
                              restartTime.has_value());
    energyCsv_ = AppendedFile(post / "energy.csv", "time,kinetic,gravitational,magnetic,total", restartTime.has_value());
}

void ResultsWriter::writeInduction(double time, long step, const InductionReport& report) {
    if (!inductionCsv_.isOpen()) {
        const auto file = dir_ / "postProcessing/induction.csv";
        if (restartTime_) cutCsvAfter(file, *restartTime_);
        inductionCsv_ = AppendedFile(file, "time,step,iterations,residual,converged", restartTime_.has_value());
    }
    char line[160];
    std::snprintf(line, sizeof line, "%.12g,%ld,%d,%.12g,%d\n", time, step, report.iterations, report.residual,
                  report.converged ? 1 : 0);
    inductionCsv_.append(line);
}

void ResultsWriter::write(double time, long step, const std::vector<Body>& bodies, const std::vector<Wrench>& wrenches,
                          const Energies& e, const std::vector<StateFile>& states,
                          const std::vector<std::vector<Vec3>>& faceB, const std::vector<char>* asleep) {
    requireFinite(time, step, bodies, &wrenches, &e);
    std::string rows;
    char line[1024];
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        const Body& b = bodies[i];
        const Quat& q = b.orientation;
        const Vec3 F = wrenches[i].force, T = wrenches[i].totalTorque();
        std::snprintf(line, sizeof line,
                      "%.10g,%s,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,"
                      "%.10g,%.10g,%.10g,%.10g,%.10g,%.10g",
                      time, b.name.c_str(), b.position.x(), b.position.y(), b.position.z(), q.w(), q.x(), q.y(), q.z(),
                      b.velocity.x(), b.velocity.y(), b.velocity.z(), b.angularVelocity.x(), b.angularVelocity.y(),
                      b.angularVelocity.z(), F.x(), F.y(), F.z(), T.x(), T.y(), T.z());
        rows += line;
        if (sleepColumn_) rows += asleep && i < asleep->size() && (*asleep)[i] ? ",1" : ",0";
        rows += '\n';
    }
    bodiesCsv_.append(rows);
    std::snprintf(line, sizeof line, "%.10g,%.12g,%.12g,%.12g,%.12g\n", time, e.kinetic, e.gravitational, e.magnetic,
                  e.total());
    energyCsv_.append(line);
    // bodies.yaml last: a time folder that has one is complete (the header).
    writeVtk(time, bodies, faceB);
    writeState(time, step, bodies, states);
}

std::vector<Vec3> faceCentres(const Body& body) {
    const auto& mesh = body.shape->mesh;
    std::vector<Vec3> out;
    out.reserve(mesh.triangles.size());
    for (const auto& t : mesh.triangles)
        out.push_back(body.toWorld((mesh.vertices[t[0]] + mesh.vertices[t[1]] + mesh.vertices[t[2]]) / 3.0));
    return out;
}

void ResultsWriter::writeState(double time, long step, const std::vector<Body>& bodies,
                               const std::vector<StateFile>& states) const {
    requireFinite(time, step, bodies, nullptr, nullptr);
    const auto folder = dir_ / timeName(time);
    makeFolder(folder);
    // The models' files first: a bodies.yaml (what a restart looks for)
    // always has the model state of the same step beside it. A bodies.yaml
    // of an earlier run in this folder goes first, so that a run cut between
    // the model files and the new bodies.yaml leaves no mixed folder.
    if (std::error_code ec; std::filesystem::exists(folder / "bodies.yaml")) {
        std::filesystem::remove(folder / "bodies.yaml", ec);
        if (ec) throw OutputError((folder / "bodies.yaml").string() + ": cannot replace (" + ec.message() + ")");
    }
    for (const StateFile& f : states) {
        if (!f.text.empty()) {
            writeFileAtomically(folder / f.name, f.text);
        } else {
            std::error_code ec;
            std::filesystem::remove(folder / f.name, ec);
        }
    }
    std::ostringstream os;
    char buf[128];
    std::snprintf(buf, sizeof buf, "%.17g", time);
    os << "# magFoam state: restart with startFrom: latestTime\ntime: " << buf << "\nstep: " << step << "\nbodies:\n";
    for (const auto& b : bodies) {
        const Quat& q = b.orientation;
        std::snprintf(buf, sizeof buf, "%.17g, %.17g, %.17g, %.17g", q.w(), q.x(), q.y(), q.z());
        os << "  - name: " << b.name << "\n    position: ";
        vec(os, b.position);
        os << "\n    orientation: [" << buf << "]\n    velocity: ";
        vec(os, b.velocity);
        os << "\n    angularVelocity: ";
        vec(os, b.angularVelocity);
        os << "\n    magnetization: ";
        vec(os, b.magnetizationBody);
        os << "   # A/m, body frame\n";
        if (b.compound) {
            os << "    partMagnetization:   # A/m, each in its part's frame\n";
            for (const Vec3& m : b.partMagnetization) {
                os << "      - ";
                vec(os, m);
                os << "\n";
            }
        }
    }
    writeFileAtomically(folder / "bodies.yaml", os.str());
}

void ResultsWriter::writeVtk(double time, const std::vector<Body>& bodies,
                             const std::vector<std::vector<Vec3>>& faceB) {
    // Per face: what a user inspects in ParaView. B of the other bodies there,
    // its normal part, and the magnetic traction (M . n) B, the surface-charge
    // force density whose integral is the body's force (paper Eq. 16).
    std::vector<Vec3> points;
    std::vector<std::array<int, 3>> tris;
    std::vector<std::string> names;
    // A compound's faces carry its part's index ("part"; 0 for other bodies)
    // and that part's magnetization.
    vtk::PointField id{"body", 1, {}}, part{"part", 1, {}}, M{"magnetization", 3, {}}, V{"velocity", 3, {}};
    vtk::PointField Bf{"B", 3, {}}, Bn{"Bn", 1, {}}, magB{"magB", 1, {}}, traction{"traction", 3, {}};
    const bool fields = faceB.size() == bodies.size();
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        const Body& b = bodies[i];
        names.push_back(b.name);
        const int offset = static_cast<int>(points.size());
        for (const auto& v : b.shape->mesh.vertices) points.push_back(b.toWorld(v));
        const Vec3 m = b.magnetization();
        const auto& mesh = b.shape->mesh;
        for (std::size_t k = 0; k < mesh.triangles.size(); ++k) {
            const auto& t = mesh.triangles[k];
            tris.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
            id.values.push_back(double(i));
            const std::size_t p = b.compound ? b.compound->partOfTriangle(k) : 0;
            part.values.push_back(double(p));
            const Vec3 mFace = b.compound ? Vec3(b.orientation * (b.compound->parts[p].orientation * b.partMagnetization[p])) : m;
            M.values.insert(M.values.end(), {mFace.x(), mFace.y(), mFace.z()});
            const Vec3 c = b.toWorld((mesh.vertices[t[0]] + mesh.vertices[t[1]] + mesh.vertices[t[2]]) / 3.0);
            const Vec3 v = b.velocity + b.angularVelocity.cross(c - b.position);
            V.values.insert(V.values.end(), {v.x(), v.y(), v.z()});
            if (!fields) continue;
            const Vec3 n = b.orientation * mesh.normal(static_cast<int>(k));
            const Vec3& B = faceB[i][k];
            const Vec3 f = mFace.dot(n) * B;
            Bf.values.insert(Bf.values.end(), {B.x(), B.y(), B.z()});
            Bn.values.push_back(B.dot(n));
            magB.values.push_back(B.norm());
            traction.values.insert(traction.values.end(), {f.x(), f.y(), f.z()});
        }
    }
    std::vector<vtk::PointField> cells = {id, part, M, V};
    if (fields) cells.insert(cells.end(), {Bf, Bn, magB, traction});
    while (!series_.empty() && series_.back().first >= time - 1e-12) series_.pop_back();
    const std::string name = "bodies_" + std::to_string(series_.size()) + ".vtp";
    vtk::writeSurface(dir_ / "VTK" / name, points, tris, {}, cells, names);
    series_.emplace_back(time, name);
    std::ostringstream pvd;
    pvd.precision(12);
    pvd << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n<Collection>\n";
    for (const auto& [t, f] : series_)
        pvd << "  <DataSet timestep=\"" << t << "\" group=\"\" part=\"0\" file=\"" << f << "\"/>\n";
    pvd << "</Collection>\n</VTKFile>\n";
    writeFileAtomically(dir_ / "VTK/bodies.pvd", pvd.str());
}

} // namespace mag
