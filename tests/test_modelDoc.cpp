// -doc TYPE (ModelDoc.hpp): every registered type documents exactly the keys
// its reader reads. The documentation is recorded from the reads; this test
// checks it against the other thing the reader does with its keys: the list
// of valid keys it gives when a mapping holds an unknown one (Dict::reportUnused).
#include <magFoam/AppliedField.hpp>
#include <magFoam/Error.hpp>
#include <magFoam/FieldEvaluator.hpp>
#include <magFoam/InductionModel.hpp>
#include <magFoam/ModelDoc.hpp>
#include <magFoam/Plugins.hpp>
#include <magFoam/RigidBodyBackend.hpp>

#include <catch2/catch.hpp>

#include <set>
#include <sstream>

using namespace mag;

namespace {

// The keys of the mapping at `path` ("" the top) that the doc lists.
std::set<std::string> documentedChildren(const plugins::TypeDocumentation& d, const std::string& path) {
    std::set<std::string> out;
    for (const KeyRecord& r : d.keys) {
        const std::string& p = r.path;
        if (path.empty() ? p.find('.') == std::string::npos
                         : p.starts_with(path + ".") && p.find('.', path.size() + 1) == std::string::npos)
            out.insert(path.empty() ? p : p.substr(path.size() + 1));
    }
    if (path.empty()) out.insert("type");
    return out;
}

// Build `example` of a `registry` type with the unknown key zzUnknown in the
// mapping at `path`; returns the valid keys the error lists there.
std::set<std::string> validKeysAt(const std::string& registry, const std::string& example, const std::string& path) {
    YAML::Node root = YAML::Load(example);
    YAML::Node node = root;
    std::stringstream ss(path);
    for (std::string part; std::getline(ss, part, '.');) {
        if (!node[part] || !node[part].IsMap()) node[part] = YAML::Node(YAML::NodeType::Map);
        node.reset(node[part]); // rebind: operator= would overwrite the mapping
    }
    node["zzUnknown"] = 1;
    std::ostringstream os;
    os << root;
    const Dict d = Dict::fromString(os.str(), "example");
    std::string message;
    try {
        if (registry == "field") (void)FieldEvaluator::New(d);
        if (registry == "induction") (void)InductionModel::New(d);
        if (registry == "rigidBody") (void)RigidBodyBackend::New(d);
        if (registry == "appliedField") (void)AppliedField::New(d);
    } catch (const InputError& e) {
        message = e.what();
    }
    INFO(os.str());
    REQUIRE_THAT(message, Catch::Matchers::Contains("unknown key 'zzUnknown'"));
    std::set<std::string> keys;
    const auto at = message.find("valid keys: ");
    REQUIRE(at != std::string::npos);
    std::stringstream list(message.substr(at + 12));
    for (std::string k; std::getline(list, k, ',');) keys.insert(k.substr(k.find_first_not_of(' ')));
    return keys;
}

} // namespace

TEST_CASE("model doc: -doc lists every registered type, and for each exactly the keys its reader accepts", "[doc]") {
    const auto docs = plugins::documentAll();
    std::set<std::string> names;
    for (const auto& d : docs) names.insert(d.name);
    // The standard modules: a missing one would be missing from -doc.
    for (const char* t : {"MBM", "EDM", "hybrid", "LLG", "demag", "none", "ODE", "Bullet", "free", "uniform", "gradient"})
        CHECK(names.count(t));

    for (const auto& d : docs) {
        INFO(d.registry << " " << d.name << "\n" << d.text);
        CHECK(d.failures.empty());     // every example builds
        CHECK(d.undocumented.empty()); // every key read is described
        CHECK(d.unread.empty());       // every key described is read
        CHECK_FALSE(d.summary.empty());
        CHECK(d.text.find(d.name + ": ") == 0);
        for (const KeyRecord& r : d.keys) {
            CHECK((!r.type.empty() || r.checked)); // a type or a presence check
            CHECK(d.text.find("  " + r.path + "\n") != std::string::npos);
        }

        // The mappings the doc shows (the top and every nested mapping that is
        // not a model of its own), each holding an unknown key in turn.
        std::vector<std::string> mappings = {""};
        for (const KeyRecord& r : d.keys)
            if (r.type == "mapping" && r.selected.empty()) mappings.push_back(r.path);
        const auto& entry = [&]() -> const std::vector<std::string>& {
            static const std::vector<std::string> none;
            if (d.registry == "field") return FieldEvaluator::registry().find(d.name)->doc.examples;
            if (d.registry == "induction") return InductionModel::registry().find(d.name)->doc.examples;
            if (d.registry == "rigidBody") return RigidBodyBackend::registry().find(d.name)->doc.examples;
            if (d.registry == "appliedField") return AppliedField::registry().find(d.name)->doc.examples;
            return none;
        }();
        REQUIRE_FALSE(entry.empty());
        for (const std::string& m : mappings) {
            std::set<std::string> accepted;
            for (const std::string& example : entry) {
                const auto valid = validKeysAt(d.registry, example, m);
                accepted.insert(valid.begin(), valid.end());
            }
            INFO("mapping '" << m << "'");
            CHECK(accepted == documentedChildren(d, m));
        }
    }
}

TEST_CASE("model doc: -doc of a type prints its defaults as the reader has them", "[doc]") {
    const std::string mbm = plugins::documentType("MBM");
    CHECK_THAT(mbm, Catch::Matchers::Contains("quadrature.tolerance\n      number; default 0.0001"));
    CHECK_THAT(mbm, Catch::Matchers::Contains("word: adaptive | regular | gauss; default adaptive"));
    const std::string ode = plugins::documentType("ODE");
    CHECK_THAT(ode, Catch::Matchers::Contains("contact.surfaceLayer\n      number; default 1e-06; unit m"));
    CHECK_THAT(plugins::documentType("hybrid"), Catch::Matchers::Contains("a field evaluator selected by its type"));
    CHECK_THROWS_WITH(plugins::documentType("MBN"), Catch::Matchers::Contains("valid types: "));
    CHECK_THAT(plugins::documentIndex(), Catch::Matchers::Contains("  ODE "));
}
