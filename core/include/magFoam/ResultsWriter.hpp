// Results of a transient run (DESIGN.md §5), all under the case folder:
//   <time>/bodies.yaml            full restartable state of every body
//   VTK/bodies_<k>.vtp, bodies.pvd surfaces (world frame) with per-cell body
//                                 index, magnetization and force; one series
//   postProcessing/bodies.csv     time,body,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz,
//                                 Fx,Fy,Fz,Tx,Ty,Tz (magnetic force, total
//                                 magnetic torque about the COM)
//   postProcessing/energy.csv     time,kinetic,gravitational,magnetic,total
// On restart the CSV files are truncated to the restart time and appended.
#pragma once

#include "magFoam/Body.hpp"
#include "magFoam/InductionModel.hpp"
#include "magFoam/FieldEvaluator.hpp"

#include <filesystem>
#include <fstream>
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

// The newest time folder holding a bodies.yaml (nullopt when none).
std::optional<std::filesystem::path> latestTimeFolder(const std::filesystem::path& caseDir);

struct RestartState {
    double time = 0;
    long step = 0;
};
// Read <time>/bodies.yaml into the matching bodies (by name); InputError when
// a body is missing or a value is not finite.
RestartState readState(const std::filesystem::path& file, std::vector<Body>& bodies);

class ResultsWriter {
public:
    // restartTime: drop CSV rows after it (nullopt: start the files anew).
    ResultsWriter(const std::filesystem::path& caseDir, std::optional<double> restartTime);

    void write(double time, long step, const std::vector<Body>& bodies, const std::vector<Wrench>& wrenches,
               const Energies& energies);

    // One row of postProcessing/induction.csv (time,step,iterations,residual,
    // converged) per step of a scene with soft bodies; the file is opened at
    // the first row (and cut at the restart time like the others).
    void writeInduction(double time, long step, const InductionReport& report);

private:
    void writeState(double time, long step, const std::vector<Body>& bodies) const;
    void writeVtk(double time, const std::vector<Body>& bodies, const std::vector<Wrench>& wrenches);

    std::filesystem::path dir_;
    std::optional<double> restartTime_;
    std::ofstream bodiesCsv_, energyCsv_, inductionCsv_;
    std::vector<std::pair<double, std::string>> series_;  // (time, vtp file) for the .pvd
};

} // namespace mag
