// Results of a transient run (docs/case-reference.md), all under the case folder:
//   <time>/bodies.yaml            full restartable state of every body: time,
//                                 step, and per body position, orientation
//                                 [w, x, y, z], velocity, angularVelocity and
//                                 magnetization (body frame), every number
//                                 with 17 significant digits (reads back bit
//                                 for bit)
//   <time>/induction.yaml         state the induction model carries between
//                                 steps (LLG: each soft body's pair of unit
//                                 sub-magnetizations, body frame); only when
//                                 the model has such state
//   <time>/rigidBody.yaml         state the rigid-body backend carries between
//                                 steps (free/verlet: the closing half kick
//                                 and angular momentum; ODE: its random
//                                 generator and collision-space order); only
//                                 when it has such state
//   VTK/bodies_<k>.vtp, bodies.pvd surfaces (world frame) with per-cell body
//                                 index, magnetization and force; one series
//   postProcessing/bodies.csv     time,body,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz,
//                                 Fx,Fy,Fz,Tx,Ty,Tz (magnetic force, total
//                                 magnetic torque about the COM)
//   postProcessing/energy.csv     time,kinetic,gravitational,magnetic,total
// A restart (startFrom: latestTime) reads the newest valid <time>/bodies.yaml
// and hands the model files back to their models, so that it continues bit
// for bit (docs/architecture.md#restart). Every write is checked and stops the
// run with an OutputError naming the file (OutputFile.hpp). At a write time
// the CSV rows go first, then the VTK surface and series, then the model
// files and last bodies.yaml, each whole file by write-then-rename: a time
// folder with a bodies.yaml is complete, whenever a run was cut. On restart
// the CSV files are cut to the restart time and appended.
#pragma once

#include "magFoam/Body.hpp"
#include "magFoam/InductionModel.hpp"
#include "magFoam/FieldEvaluator.hpp"
#include "magFoam/OutputFile.hpp"

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace mag {

struct Energies {
    double kinetic = 0, gravitational = 0, magnetic = 0;
    double total() const { return kinetic + gravitational + magnetic; }
};

// Kinetic and gravitational energy of the bodies (potential zero at z = 0
// for gravity g); `magnetic` is passed in (it comes from the field model).
Energies bodyEnergies(const std::vector<Body>& bodies, const Vec3& gravity, double magnetic);

// Folder name of a time: shortest decimal that reads back as the same value
// after rounding to 1e-12 s (so 0.1 + 0.2 writes "0.3").
std::string timeName(double t);

// The time folders holding a bodies.yaml, newest first (names that are not
// finite numbers, such as "inf", are no time folders).
std::vector<std::filesystem::path> timeFolders(const std::filesystem::path& caseDir);
// The newest of them (nullopt when none).
std::optional<std::filesystem::path> latestTimeFolder(const std::filesystem::path& caseDir);

struct RestartState {
    double time = 0;
    long step = 0;
};
// Read <time>/bodies.yaml into the matching bodies (by name), every value as
// written (a unit quaternion is not renormalised); InputError when the file
// is empty, a body is missing or a value is not finite.
RestartState readState(const std::filesystem::path& file, std::vector<Body>& bodies);

// The body an entry of a state file's `bodies:` list names (its `name`);
// InputError at that key when no body of the case has it.
std::size_t stateBodyIndex(const Dict& entry, const std::vector<Body>& bodies);

// Numbers for the restart files: 17 significant digits ("%.17g"), which
// strtod (Dict) reads back bit for bit. formatExact(Vec3) is "[x, y, z]".
std::string formatExact(double x);
std::string formatExact(const Vec3& v);

// A model's state file in a time folder (InductionModel::writeState,
// RigidBodyBackend::writeState): its name and YAML text, empty for none.
struct StateFile {
    std::string name;
    std::string text;
};

// World positions of the centres of a body's triangles, in triangle order
// (where the VTK surfaces' per-face fields are taken).
std::vector<Vec3> faceCentres(const Body& body);

class ResultsWriter {
public:
    // restartTime: drop CSV rows after it (nullopt: start the files anew).
    // sleepColumn: bodies.csv ends with a column `asleep` (1: the body sleeps,
    // docs/dynamics.md#sleeping).
    ResultsWriter(const std::filesystem::path& caseDir, std::optional<double> restartTime, bool sleepColumn = false);

    // One write time. `states` go into the time folder before bodies.yaml;
    // one with empty text removes an older file of that name there.
    // `faceB`: per body, B of all the other bodies at its triangles' centres
    // (faceCentres(), world frame, T); empty: the surfaces carry no field.
    // `asleep`: per body, for the column of sleepColumn.
    void write(double time, long step, const std::vector<Body>& bodies, const std::vector<Wrench>& wrenches,
               const Energies& energies, const std::vector<StateFile>& states = {},
               const std::vector<std::vector<Vec3>>& faceB = {}, const std::vector<char>* asleep = nullptr);

    // The time folder alone (bodies.yaml and `states`), without CSV rows or
    // surfaces: the last good state of a run whose wrenches are not finite.
    void writeStateOnly(double time, long step, const std::vector<Body>& bodies,
                        const std::vector<StateFile>& states = {}) const {
        writeState(time, step, bodies, states);
    }

    // One row of postProcessing/induction.csv (time,step,iterations,residual,
    // converged) per step of a scene with soft bodies; the file is opened at
    // the first row (and cut at the restart time like the others).
    void writeInduction(double time, long step, const InductionReport& report);

private:
    void writeState(double time, long step, const std::vector<Body>& bodies,
                    const std::vector<StateFile>& states) const;
    void writeVtk(double time, const std::vector<Body>& bodies, const std::vector<std::vector<Vec3>>& faceB);

    std::filesystem::path dir_;
    std::optional<double> restartTime_;
    bool sleepColumn_ = false;
    AppendedFile bodiesCsv_, energyCsv_, inductionCsv_;
    std::vector<std::pair<double, std::string>> series_;  // (time, vtp file) for the .pvd
};

} // namespace mag
