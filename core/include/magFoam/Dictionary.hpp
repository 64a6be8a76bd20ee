// Dict: a YAML dictionary with typed reads, defaults, and errors that cite
// file:line:column and the key path (pbrt's ParameterDictionary, OpenFOAM's
// dictionary). Every key a model reads is remembered, so reportUnused() can
// reject misspelled keys and list the valid ones.
//
//   Dict d = Dict::fromFile("system/controlDict.yaml");
//   double dt = d.get<double>("deltaT");              // required
//   int n     = d.get<int>("threads", 1);              // with default
//   Dict q    = d.sub("quadrature");                   // nested mapping
//   d.reportUnused();                                  // typo -> InputError
//
// Supported value types: double (finite, |x| <= dictionaryNumberLimit), int, bool, std::string, Vec3,
// Quat (w, x, y, z), std::vector<double>, std::vector<std::string>,
// std::vector<std::vector<double>> (rows: matrices, tables).
#pragma once

#include "magFoam/Types.hpp"

#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <memory>
#include <set>
#include <string>
#include <vector>

namespace mag {

// The largest magnitude of any number read from a dictionary (and a mesh
// coordinate, MeshFormats.hpp). In SI units no input comes near it, and the
// products the models form of a few such numbers (r^5, M^2 V, m v^2) stay
// finite, where 1e308 would overflow to inf in the first of them.
inline constexpr double dictionaryNumberLimit = 1e30;

// What a model read, recorded while it is built from an example dictionary:
// the source of `-doc TYPE` (ModelDoc.hpp), so that the keys, types and
// defaults printed are the ones the code reads, not a copy that can drift.
struct KeyRecord {
    std::string path;             // dotted key path, e.g. "quadrature.tolerance"
    std::string type;             // "number", "integer", "word", "mapping", ...
    std::string fallback;         // the default as text; empty when required
    bool required = false;        // read without a default
    bool checked = false;         // has() asked first: optional despite a required read
    std::vector<std::string> words; // getWord's valid values
    std::string selected;         // a nested model chosen by its `type` ("field evaluator")
};
struct KeyLog {
    std::vector<KeyRecord> records;
    KeyRecord& at(const std::string& path);
};

class Dict {
public:
    // An empty mapping (all reads fall back to defaults).
    Dict();

    // Parse a YAML file; malformed YAML or a top level that is not a mapping
    // throws InputError "file:line:col: ...". So do a file that is not a
    // regular one or above dictionaryFileLimit (InputFile.hpp), a second YAML
    // document, and aliases ('*name') that would expand to more than a million
    // values or refer to a node that contains them (a cycle): what the reader
    // accepts, every later walk over it can afford.
    static Dict fromFile(const std::filesystem::path& file);
    static Dict fromString(const std::string& text, const std::string& name);
    // A mapping built in code (the Python module converts dicts to nodes):
    // read and checked as a file's, its messages name `name` where a file's
    // name line:column.
    static Dict fromNode(const YAML::Node& node, const std::string& name);
    // As fromString, recording every read of this dictionary and its
    // sub-dictionaries into `log`.
    static Dict recording(const std::string& text, const std::string& name, std::shared_ptr<KeyLog> log);
    // Marks this mapping as a model selected by `type` (for the documentation
    // of the enclosing model; a no-op unless recording).
    void noteSelected(const std::string& what) const;

    bool has(const std::string& key) const;
    bool isMap(const std::string& key) const;
    bool isList(const std::string& key) const;

    template <class T> T get(const std::string& key) const;
    template <class T> T get(const std::string& key, const T& fallback) const;

    // Nested mapping (required / optional: empty mapping when absent).
    Dict sub(const std::string& key) const;
    Dict subOrEmpty(const std::string& key) const;
    // A required sequence of mappings.
    std::vector<Dict> list(const std::string& key) const;
    // The keys present, in file order.
    std::vector<std::string> keys() const;

    // Throw for keys present but never asked for; names the closest valid key.
    void reportUnused() const;

    // A required key limited to a set of words (enums): error lists them.
    std::string getWord(const std::string& key, const std::vector<std::string>& valid) const;
    std::string getWord(const std::string& key, const std::vector<std::string>& valid,
                        const std::string& fallback) const;

    // "file:line:col" of this mapping, or of a key's value.
    std::string where() const;
    std::string where(const std::string& key) const;
    const std::string& file() const { return state_->file; }
    // Dotted key path of this mapping inside its file, e.g. "bodies[2].geometry".
    const std::string& path() const { return path_; }
    std::string keyPath(const std::string& key) const;

    // An InputError for `key` with position and key path: "file:l:c: path.key: msg".
    [[noreturn]] void fail(const std::string& key, const std::string& message) const;
    [[noreturn]] void failHere(const std::string& message) const;
    // A warning in the same form (the log): a value that is allowed but
    // implausible, e.g. a unit slip (docs/case-reference.md#plausibility).
    void warn(const std::string& key, const std::string& message) const;

    const YAML::Node& node() const { return node_; }

private:
    struct FileState {
        std::string file;
        std::string text;
        std::shared_ptr<KeyLog> log; // null unless recording
    };
    KeyRecord* record(const std::string& key) const;
    Dict(std::shared_ptr<const FileState> state, YAML::Node node, std::string path);
    YAML::Node value(const std::string& key) const;
    YAML::Node required(const std::string& key) const;

    std::shared_ptr<const FileState> state_;
    YAML::Node node_;
    std::string path_;
    // Keys asked for through this mapping (present or not): the valid keys.
    std::shared_ptr<std::set<std::string>> asked_;

    template <class T> friend struct DictConvert;
};

// Explicit instantiations live in Dictionary.cpp.
extern template double Dict::get<double>(const std::string&) const;
extern template int Dict::get<int>(const std::string&) const;
extern template bool Dict::get<bool>(const std::string&) const;
extern template std::string Dict::get<std::string>(const std::string&) const;
extern template Vec3 Dict::get<Vec3>(const std::string&) const;
extern template Quat Dict::get<Quat>(const std::string&) const;
extern template std::vector<double> Dict::get<std::vector<double>>(const std::string&) const;
extern template std::vector<std::string> Dict::get<std::vector<std::string>>(const std::string&) const;
extern template std::vector<std::vector<double>> Dict::get<std::vector<std::vector<double>>>(const std::string&) const;
extern template std::vector<std::vector<double>> Dict::get<std::vector<std::vector<double>>>(
    const std::string&, const std::vector<std::vector<double>>&) const;
extern template double Dict::get<double>(const std::string&, const double&) const;
extern template int Dict::get<int>(const std::string&, const int&) const;
extern template bool Dict::get<bool>(const std::string&, const bool&) const;
extern template std::string Dict::get<std::string>(const std::string&, const std::string&) const;
extern template Vec3 Dict::get<Vec3>(const std::string&, const Vec3&) const;
extern template Quat Dict::get<Quat>(const std::string&, const Quat&) const;
extern template std::vector<double> Dict::get<std::vector<double>>(const std::string&, const std::vector<double>&) const;
extern template std::vector<std::string> Dict::get<std::vector<std::string>>(const std::string&, const std::vector<std::string>&) const;

} // namespace mag
