// tutorials/magnetChain as a contact test for the rigid-body backends: four
// 1 cm N42 cubes dropped together snap into a chain that lands on the ground,
// pressed together by up to 55 N while resting on 0.07 N. Magnets holding
// each other are where a backend's friction fails first
// (docs/rigid-bodies.md#friction-bounds, #bullet).
#pragma once

#include "caseFixture.hpp"

#include <catch2/catch.hpp>

#include <functional>
#include <regex>
#include <string>

namespace magtest {

// Runs the tutorial to 0.8 s without sleeping, its controlDict and
// rigidBody.yaml texts changed by `edit` first; returns how many of the four
// magnets the log's end summary counts at rest (< 1 mm/s).
inline int magnetChainAtRest(const std::function<void(std::string& control, std::string& rigid)>& edit) {
    TempCase c;
    const std::filesystem::path tutorial = std::filesystem::path(MAG_SOURCE_DIR) / "tutorials/magnetChain";
    for (const char* dir : {"constant", "system"})
        std::filesystem::copy(tutorial / dir, c.path(dir),
                              std::filesystem::copy_options::recursive | std::filesystem::copy_options::overwrite_existing);
    std::string control = slurp(c.path("system/controlDict.yaml"));
    control = std::regex_replace(control, std::regex("endTime: 1\\n"), "endTime: 0.8\n");
    std::string rigid = slurp(c.path("constant/rigidBody.yaml"));
    edit(control, rigid);
    c.write("system/controlDict.yaml", control);
    c.write("constant/rigidBody.yaml", rigid);
    REQUIRE(runApp(c.dir(), "magFoam", "log") == 0);
    const std::string log = slurp(c.dir() / "log");
    REQUIRE(log.find("from t = 0 to 0.8") != std::string::npos);
    std::smatch m;
    REQUIRE(std::regex_search(log, m, std::regex("([0-9]+) of 4 dynamic bodies at rest at the end")));
    return std::stoi(m[1]);
}

} // namespace magtest
