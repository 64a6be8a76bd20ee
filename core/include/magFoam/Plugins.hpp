// Plugin loader (OpenFOAM's dlLibraryTable): loads libmag<Name>.so files whose
// static registration objects add model types to the registries.
//
// Search order for a bare name `magFoo` (-> libmagFoo.so): each folder of
// MAG_PLUGIN_PATH (colon separated), then the folder holding libmagCore itself
// (build/lib in the build tree, <prefix>/lib after install). A name with a '/'
// or ending in ".so" is a path (relative paths resolved against `baseDir`).
//
// Plugin manifests: the build writes <project>.magPlugins.yaml beside the
// plugins it builds (mag_add_plugin ... TYPES, cmake/magFoamPlugin.cmake), one
// line per library with the types it registers, by registry:
//
//   libmagMBM.so: {field: [MBM]}
//   libmagFreeBody.so: {rigidBody: [free]}
//
// Registries: field (FieldEvaluator), induction (InductionModel), rigidBody
// (RigidBodyBackend). The apps load every library that the manifests on the
// search path list; an unknown type is looked up there (then as lib mag<type>)
// before it fails; and a library that a manifest of its folder lists must
// register exactly the types listed (else loading it throws InputError).
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace mag::plugins {

// One library of a plugin manifest.
struct ManifestEntry {
    std::filesystem::path library;  // the manifest's folder / the library's file name
    std::filesystem::path manifest; // the manifest file
    std::map<std::string, std::vector<std::string>> types; // registry -> type names, sorted
};

// The registries a manifest may name: field, induction, rigidBody, appliedField.
const std::vector<std::string>& registryNames();

// The libraries listed by the manifests (*.magPlugins.yaml) of the search path
// folders, in search order; of a file name listed in several folders, the
// first. Throws InputError for a malformed manifest.
std::vector<ManifestEntry> manifestEntries();

// The libraries every app loads by default: those of manifestEntries() (file
// names). Missing ones are skipped: a trimmed build still runs what it has.
std::vector<std::string> standardModules();

// Load the standard modules once per process.
void loadStandardModules();

// Load the library that a manifest on the search path names for `type` in
// `registry` (field, induction, rigidBody, appliedField); false when none names it or the
// library is missing.
bool loadForType(const std::string& registry, const std::string& type);

// Load one library by bare name or path. Returns true if it was newly
// loaded; warns when it registers nothing. Throws InputError when it cannot
// be found or opened (the message lists the folders searched).
bool load(const std::string& nameOrPath, const std::filesystem::path& baseDir = ".");

// Try to load lib<name>.so for an unknown type name; false when absent.
bool tryLoadForType(const std::string& libName);

// Libraries loaded so far (resolved paths), and the folders searched.
std::vector<std::string> loaded();
std::vector<std::filesystem::path> searchPath();

// A human-readable table of every registry and the library of each entry.
std::string listModules();

} // namespace mag::plugins
