// Plugin loader (OpenFOAM's dlLibraryTable): loads libmag<Name>.so files whose
// static registration objects add model types to the registries.
//
// Search order for a bare name `magFoo` (-> libmagFoo.so): each folder of
// MAG_PLUGIN_PATH (colon separated), then the folder holding libmagCore itself
// (build/lib in the build tree, <prefix>/lib after install). A name with a '/'
// or ending in ".so" is a path (relative paths resolved against `baseDir`).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace mag::plugins {

// The standard modules that every app loads by default (missing ones are
// skipped: a trimmed build still runs what it has).
const std::vector<std::string>& standardModules();

// Load the standard modules once per process.
void loadStandardModules();

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
