// Plugins: a field evaluator in a separate shared library is selectable by
// name from a case's `libs:`; unknown types list the valid ones; a library
// that registers nothing warns; the plugin manifests list what each library
// registers, and a library that disagrees with its manifest does not load.
#include "caseFixture.hpp"

#include <magFoam/Case.hpp>
#include <magFoam/Error.hpp>
#include <magFoam/FieldEvaluator.hpp>
#include <magFoam/InductionModel.hpp>
#include <magFoam/Plugins.hpp>
#include <magFoam/RigidBodyBackend.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>

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

TEST_CASE("a plugin compiled for another CPU target is refused, naming the layout", "[plugins][badInput]") {
#if defined(__x86_64__) && defined(__AVX__)
    const std::string lib = pluginDir() + "/libmagLayoutMismatch.so";
    CHECK_THROWS_WITH(mag::plugins::load(lib), Contains("another CPU target") && Contains("libmagLayoutMismatch.so"));
    CHECK_FALSE(mag::FieldEvaluator::registry().has("layoutMismatchField")); // its types are gone again
#else
    SUCCEED("the core is built without AVX here: the test plugin has the same layout");
#endif
}

TEST_CASE("listModules shows every registry", "[plugins]") {
    const std::string text = mag::plugins::listModules();
    CHECK_THAT(text, Contains("field evaluators") && Contains("induction models") && Contains("rigid-body backends") &&
                         Contains("none"));
}

// Plugin manifests (<project>.magPlugins.yaml, written by mag_add_plugin ... TYPES).

TEST_CASE("every library of the build's plugin manifest registers exactly the types it lists", "[plugins][manifest]") {
    const auto entries = mag::plugins::manifestEntries();
    REQUIRE_FALSE(entries.empty());
    REQUIRE_NOTHROW(mag::plugins::loadStandardModules());
    auto listed = [&](const std::string& file, const std::string& registry, const std::string& type) {
        for (const auto& e : entries) {
            if (e.library.filename() != file) continue;
            const auto it = e.types.find(registry);
            return it != e.types.end() && std::find(it->second.begin(), it->second.end(), type) != it->second.end();
        }
        return false;
    };
    // Each type a manifest library registered is listed for it, and each listed type is registered by it.
    auto check = [&](const std::string& registry, const auto& r) {
        for (const auto& [name, entry] : r.entries()) {
            bool fromManifest = false;
            for (const auto& e : entries) fromManifest = fromManifest || e.library.filename() == entry.library;
            if (fromManifest) CHECK(listed(entry.library, registry, name));
        }
    };
    check("field", mag::FieldEvaluator::registry());
    check("induction", mag::InductionModel::registry());
    check("rigidBody", mag::RigidBodyBackend::registry());
    for (const auto& e : entries)
        for (const auto& [registry, names] : e.types)
            for (const auto& name : names) {
                const std::string* lib = nullptr;
                if (registry == "field" && mag::FieldEvaluator::registry().find(name))
                    lib = &mag::FieldEvaluator::registry().find(name)->library;
                if (registry == "induction" && mag::InductionModel::registry().find(name))
                    lib = &mag::InductionModel::registry().find(name)->library;
                if (registry == "rigidBody" && mag::RigidBodyBackend::registry().find(name))
                    lib = &mag::RigidBodyBackend::registry().find(name)->library;
                INFO(e.library.string() << " lists " << registry << " type " << name);
                REQUIRE(lib != nullptr);
                CHECK(*lib == e.library.filename().string());
            }
}

TEST_CASE("a type is found through the manifest even where the library is named otherwise", "[plugins][manifest]") {
    // `free` lives in libmagFreeBody.so: no libmagfree.so to guess.
    CHECK(mag::plugins::loadForType("rigidBody", "free"));
    CHECK(mag::RigidBodyBackend::registry().has("free"));
    CHECK_FALSE(mag::plugins::loadForType("rigidBody", "noSuchBackend"));
    // A manifest in a folder of MAG_PLUGIN_PATH counts too.
    setenv("MAG_PLUGIN_PATH", pluginDir().c_str(), 1);
    CHECK(mag::plugins::loadForType("field", "testUniformField"));
    CHECK(mag::FieldEvaluator::registry().has("testUniformField"));
    unsetenv("MAG_PLUGIN_PATH");
}

TEST_CASE("a library that registers other types than its manifest lists fails to load", "[plugins][manifest][badInput]") {
    magtest::TempCase c;
    const auto dir = c.dir() / "lib";
    std::filesystem::create_directories(dir);
    std::filesystem::copy_file(pluginDir() + "/libmagTestField.so", dir / "libmagTestField.so");
    std::ofstream(dir / "drift.magPlugins.yaml") << "libmagTestField.so: {field: [otherField]}\n";
    CHECK_THROWS_WITH(mag::plugins::load((dir / "libmagTestField.so").string()),
                      Contains("registers {field: [testUniformField]}") && Contains("drift.magPlugins.yaml") &&
                          Contains("lists {field: [otherField]}"));
}
