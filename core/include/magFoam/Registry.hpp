// Run-time selection (OpenFOAM's run-time selection tables, without macros):
// each extension point owns a Registry of named factories, and a plugin adds
// its types with one static registration object:
//
//   static mag::FieldEvaluator::Add<MyEvaluator> addMine("myEvaluator");
//
// The registry instance of each base class lives in libmagCore, so every
// plugin and app sees the same table.
#pragma once

#include "magFoam/Dictionary.hpp"

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace mag {

// Name of the library whose static initializers are running (set by the
// plugin loader around dlopen), so entries can say where they came from.
const std::string& libraryBeingLoaded();

// Called by every registration (the Add<T> helpers) with the layout the
// registering library was compiled with: Eigen aligns Quat to the CPU target
// (16 bytes for x86-64, 32 for x86-64-v3), which changes Body's layout, so a
// plugin compiled for another target would read garbage from every Body. The
// loader refuses such a library with a message (plugins::load).
void noteModelLayout(std::size_t bodySize, std::size_t quatAlign);

// A type's documentation, declared beside its registration (`-doc TYPE`,
// ModelDoc.hpp). Keys, value types and defaults are not written here: -doc
// records them while building the type from `examples`; this adds what the
// code cannot know (units, meaning). A key read but not described here, or
// described but never read, shows in -doc and fails the documentation test.
struct KeyDoc {
    std::string key;     // dotted path, e.g. "quadrature.tolerance"
    std::string unit;    // SI unit, "-" when dimensionless
    std::string meaning;
};
struct TypeDoc {
    std::string summary;
    std::vector<std::string> examples; // YAML of the model's mapping, `type:` included
    std::vector<KeyDoc> keys;
};

template <class Base> class Registry {
public:
    using Factory = std::function<std::unique_ptr<Base>(const Dict&)>;
    struct Entry {
        Factory factory;
        std::string library;
        TypeDoc doc;
    };

    // Registering the same name from two libraries is an error (MuJoCo rule).
    void add(const std::string& name, Factory factory, TypeDoc doc = {}) {
        const std::string& lib = libraryBeingLoaded();
        auto it = entries_.find(name);
        if (it != entries_.end() && it->second.library != lib)
            throw std::logic_error("type '" + name + "' registered twice: by " + it->second.library + " and " + lib);
        entries_[name] = Entry{std::move(factory), lib, std::move(doc)};
    }
    bool has(const std::string& name) const { return entries_.count(name) != 0; }
    const Entry* find(const std::string& name) const {
        auto it = entries_.find(name);
        return it == entries_.end() ? nullptr : &it->second;
    }
    std::vector<std::string> names() const {
        std::vector<std::string> out;
        for (const auto& kv : entries_) out.push_back(kv.first);
        return out;
    }
    const std::map<std::string, Entry>& entries() const { return entries_; }
    // Forget what `library` registered (a library refused after loading).
    void removeLibrary(const std::string& library) {
        for (auto it = entries_.begin(); it != entries_.end();)
            it = it->second.library == library ? entries_.erase(it) : std::next(it);
    }
    std::size_t size() const { return entries_.size(); }

private:
    std::map<std::string, Entry> entries_;
};

// Create a model from `dict`: reads `type`; when the name is unknown, loads the
// library that a plugin manifest names for it in registry `manifestKey`
// (field, induction, rigidBody, appliedField; Plugins.hpp), else lib<mag+type>.so (OpenFOAM's
// solverNew habit), and otherwise fails listing the valid types and the loaded
// libraries. `what` names the extension point in messages ("field evaluator").
template <class Base>
std::unique_ptr<Base> selectFromRegistry(Registry<Base>& registry, const Dict& dict, const std::string& what,
                                         const std::string& manifestKey);

} // namespace mag
