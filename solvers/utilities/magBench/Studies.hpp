// The magBench studies; each reads its mapping of system/benchDict.yaml and
// writes postProcessing/<study>.csv.
#pragma once

#include <magFoam/Dictionary.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace mag::bench {

// A method: a label and an evaluator template in which "$n" (or "$t") is
// replaced by each value of the list, e.g.
//   {label: MBM gauss, field: "{type: MBM, quadrature: {type: gauss, n: $n}}", n: [1, 2, 4]}
struct Method {
    std::string label, field;
    std::vector<double> values;  // empty: the template as is
};
std::vector<Method> readMethods(const Dict& study, const std::string& valueKey = "n");
std::string substitute(const std::string& text, const std::string& var, double value);

void accuracyCostStudy(const Dict& study, const std::filesystem::path& caseDir);
void divergenceStudy(const Dict& study, const std::filesystem::path& caseDir);
void switchErrorStudy(const Dict& study, const std::filesystem::path& caseDir);
void tableOneStudy(const Dict& study, const std::filesystem::path& caseDir);
void tableTwoStudy(const Dict& study, const std::filesystem::path& caseDir);
// table2's `scenes:` (SceneRateStudy.cpp): whole runs, simulated s per wall s.
void sceneRateStudy(const Dict& scenes, const std::vector<int>& counts, const std::filesystem::path& caseDir);
void scalingStudy(const Dict& study, const std::filesystem::path& caseDir);

} // namespace mag::bench
