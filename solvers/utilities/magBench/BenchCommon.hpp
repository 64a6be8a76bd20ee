// Shared pieces of the magBench studies: the paper's cube pair, evaluators
// from inline YAML, exact references (timing and CSV output: BenchHarness.hpp).
#pragma once

#include <magFoam/BenchHarness.hpp>
#include <magFoam/Body.hpp>
#include <magFoam/FieldEvaluator.hpp>

#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace mag::bench {

// A cube of edge `edge` (m), remanence Br (T) along body +z, at `position`.
Body cube(const std::string& name, double edge, double Br, const Vec3& position, const Quat& q = Quat::Identity());

// The paper's Fig. 4 pair: 1 cm cubes, 1 T, coaxial, face gap d (m); the
// second body is the upper one.
std::vector<Body> cubePair(double gap);

// Evaluator from an inline YAML mapping, e.g. "{type: MBM, quadrature: {n: 4}}".
std::unique_ptr<FieldEvaluator> evaluator(const std::string& yaml);


// Exact force on the upper cube of a parallel cuboid pair (Akoun-Yonnet).
Vec3 exactCubeForce(const Body& lower, const Body& upper);

// A named configuration with its exact force on the second body.
struct Configuration {
    std::string name;
    std::vector<Body> bodies;
    Vec3 exactForce;
};

// A fresh copy of a case's constant/ and system/ (no time folders) at dst,
// with its meshes made there by magMakeGeometry (the one beside this
// executable) when it has system/geometryDict.yaml; `what` names the study in
// errors. table2 runs cases from it so that nothing is written to them.
std::filesystem::path scratchCase(const std::filesystem::path& src, const std::filesystem::path& dst,
                                  const std::string& what);


} // namespace mag::bench
