// Plugins: a field evaluator in a separate shared library is selectable by
// name from a case's `libs:`; unknown types list the valid ones; a library
// that registers nothing warns.
#include "caseFixture.hpp"

#include <magFoam/Case.hpp>
#include <magFoam/Error.hpp>
#include <magFoam/FieldEvaluator.hpp>
#include <magFoam/Plugins.hpp>

#include <catch2/catch.hpp>

#include <cstdlib>

using Catch::Matchers::Contains;

namespace {
std::string pluginDir() { return magtest::testPluginDir(); }
} // namespace

TEST_CASE("a plugin named in libs: registers a selectable field evaluator", "[plugins]") {
    magtest::TempCase c;
    c.twoCubes(0.001, "{type: testUniformField, B0: [0, 0, 0.5]}");
    c.write("system/controlDict.yaml",
            "endTime: 0.01\ndeltaT: 0.001\nlibs: [" + pluginDir() + "/libmagTestField.so]\n");
    const mag::Case cs = mag::Case::read(c.dir());
    auto field = mag::FieldEvaluator::New(cs.fieldDict());
    REQUIRE(field->describe() == "testUniformField");
    mag::Vec3 p(1, 2, 3), B;
    field->evaluate(cs.bodies()[0], std::span<const mag::Vec3>(&p, 1), std::span<mag::Vec3>(&B, 1));
    CHECK(B == mag::Vec3(0, 0, 0.5));
}

TEST_CASE("bare plugin names are found through MAG_PLUGIN_PATH", "[plugins]") {
    setenv("MAG_PLUGIN_PATH", pluginDir().c_str(), 1);
    CHECK_NOTHROW(mag::plugins::load("magTestField"));
    CHECK(mag::FieldEvaluator::registry().has("testUniformField"));
    unsetenv("MAG_PLUGIN_PATH");
}

TEST_CASE("unknown type lists the valid types and loaded libraries", "[plugins][badInput]") {
    const auto d = mag::Dict::fromString("type: MBN\n", "system/magSchemes.yaml");
    CHECK_THROWS_WITH(mag::FieldEvaluator::New(d), Contains("system/magSchemes.yaml:1:7") &&
                                                       Contains("unknown field evaluator type 'MBN'") &&
                                                       Contains("valid types:") && Contains("libraries loaded"));
}

TEST_CASE("a missing plugin library is a clear error naming libs", "[plugins][badInput]") {
    magtest::TempCase c;
    c.twoCubes();
    c.write("system/controlDict.yaml", "endTime: 0.01\ndeltaT: 0.001\nlibs: [magNoSuchThing]\n");
    CHECK_THROWS_WITH(mag::Case::read(c.dir()), Contains("controlDict.yaml") && Contains("libs") &&
                                                    Contains("magNoSuchThing") && Contains("MAG_PLUGIN_PATH"));
}

TEST_CASE("a library that registers nothing loads with a warning", "[plugins]") {
    CHECK(mag::plugins::load(pluginDir() + "/libmagEmptyPlugin.so"));
    // Loading the same library again is a no-op.
    CHECK_FALSE(mag::plugins::load(pluginDir() + "/libmagEmptyPlugin.so"));
}

TEST_CASE("listModules shows every registry", "[plugins]") {
    const std::string text = mag::plugins::listModules();
    CHECK_THAT(text, Contains("field evaluators") && Contains("induction models") && Contains("rigid-body backends") &&
                         Contains("none"));
}
