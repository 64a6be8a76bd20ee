// `-doc TYPE`: the keys of a model type, generated from the code that reads
// them. Each type is built from the examples of its TypeDoc (Registry.hpp)
// with a recording dictionary (Dict::recording); the keys it read, their value
// types and defaults come from those reads, units and meaning from the TypeDoc.
// Keys of a nested model selected by its own `type` (the hybrid's near and far)
// are that model's: -doc names it instead of repeating its keys.
#pragma once

#include "magFoam/Dictionary.hpp"

#include <string>
#include <vector>

namespace mag::plugins {

struct TypeDocumentation {
    std::string registry; // "field", "induction", "rigidBody"
    std::string name, library, summary;
    std::vector<KeyRecord> keys;         // read, in reading order (the type's own keys)
    std::vector<std::string> undocumented; // read but not described in the TypeDoc
    std::vector<std::string> unread;       // described but never read by the examples
    std::vector<std::string> failures;     // examples that did not build, with the error
    std::string text;                      // what -doc prints
};

// Every registered type of every registry (standard modules loaded).
std::vector<TypeDocumentation> documentAll();

// -doc NAME: the documentation of every type of that name; an unknown name is
// an InputError listing the types. NAME "all": every type, as markdown
// (docs/model-keys.md).
std::string documentType(const std::string& name);

// -doc alone: the registries and their types, one line each.
std::string documentIndex();

} // namespace mag::plugins
