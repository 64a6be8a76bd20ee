#include "magFoam/Plugins.hpp"

#include "magFoam/AppliedField.hpp"
#include "magFoam/Dictionary.hpp"
#include "magFoam/Error.hpp"
#include "magFoam/FieldEvaluator.hpp"
#include "magFoam/InductionModel.hpp"
#include "magFoam/Log.hpp"
#include "magFoam/RigidBodyBackend.hpp"

#include <dlfcn.h>

#include <algorithm>
#include <cstdlib>
#include <map>
#include <mutex>
#include <set>
#include <sstream>
#include <string_view>

namespace mag {

namespace {
std::string& currentLibrary() {
    static std::string name = "libmagCore";
    return name;
}

std::map<std::string, void*>& openLibraries() {
    static std::map<std::string, void*> libs;
    return libs;
}

std::size_t registeredCount() {
    return FieldEvaluator::registry().size() + InductionModel::registry().size() +
           RigidBodyBackend::registry().size() + AppliedField::registry().size();
}

std::string joinNames(const std::vector<std::string>& names) {
    std::string out;
    for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
    return out.empty() ? "(none)" : out;
}

// The folder holding libmagCore: plugins live next to it.
std::filesystem::path coreLibraryDir() {
    Dl_info info{};
    if (dladdr(reinterpret_cast<void*>(&coreLibraryDir), &info) && info.dli_fname)
        return std::filesystem::absolute(info.dli_fname).parent_path();
    return {};
}
} // namespace

const std::string& libraryBeingLoaded() { return currentLibrary(); }

namespace {
std::string& layoutMismatch() {
    static std::string message;
    return message;
}
} // namespace

void noteModelLayout(std::size_t bodySize, std::size_t quatAlign) {
    if (bodySize == sizeof(Body) && quatAlign == alignof(Quat)) return;
    layoutMismatch() = "it was compiled for another CPU target than libmagCore (there a Body is " +
                       std::to_string(bodySize) + " bytes and a quaternion aligned to " + std::to_string(quatAlign) +
                       ", here " + std::to_string(sizeof(Body)) + " and " + std::to_string(alignof(Quat)) +
                       "): build it with the compile options of magFoam::core (find_package(magFoam) and "
                       "mag_add_plugin give them; by hand: the -march libmagCore was built with)";
}

FieldEvaluator::Registry& FieldEvaluator::registry() {
    static Registry r;
    return r;
}
InductionModel::Registry& InductionModel::registry() {
    static Registry r;
    return r;
}
RigidBodyBackend::Registry& RigidBodyBackend::registry() {
    static Registry r;
    return r;
}
AppliedField::Registry& AppliedField::registry() {
    static Registry r;
    return r;
}

template <class Base>
std::unique_ptr<Base> selectFromRegistry(Registry<Base>& registry, const Dict& dict, const std::string& what,
                                         const std::string& manifestKey) {
    const std::string type = dict.get<std::string>("type");
    dict.noteSelected(what);
    if (!registry.has(type) && !plugins::loadForType(manifestKey, type)) plugins::tryLoadForType("mag" + type);
    const auto* entry = registry.find(type);
    if (!entry) {
        dict.fail("type", "unknown " + what + " type '" + type + "'; valid types: " + joinNames(registry.names()) +
                              "; libraries loaded: " + joinNames(plugins::loaded()));
    }
    std::unique_ptr<Base> model = entry->factory(dict);
    dict.reportUnused();
    return model;
}

std::unique_ptr<FieldEvaluator> FieldEvaluator::New(const Dict& dict) {
    plugins::loadStandardModules();
    return selectFromRegistry(registry(), dict, "field evaluator", "field");
}
std::unique_ptr<InductionModel> InductionModel::New(const Dict& dict) {
    plugins::loadStandardModules();
    return selectFromRegistry(registry(), dict, "induction model", "induction");
}
std::unique_ptr<RigidBodyBackend> RigidBodyBackend::New(const Dict& dict) {
    plugins::loadStandardModules();
    return selectFromRegistry(registry(), dict, "rigid-body backend", "rigidBody");
}
std::unique_ptr<AppliedField> AppliedField::New(const Dict& dict) {
    plugins::loadStandardModules();
    return selectFromRegistry(registry(), dict, "applied field", "appliedField");
}

namespace plugins {

const std::vector<std::string>& registryNames() {
    static const std::vector<std::string> names = {"field", "induction", "rigidBody", "appliedField"};
    return names;
}

std::vector<std::filesystem::path> searchPath() {
    std::vector<std::filesystem::path> dirs;
    if (const char* env = std::getenv("MAG_PLUGIN_PATH")) {
        std::stringstream ss(env);
        std::string item;
        while (std::getline(ss, item, ':'))
            if (!item.empty()) dirs.emplace_back(item);
    }
    if (auto d = coreLibraryDir(); !d.empty()) dirs.push_back(d);
    return dirs;
}

namespace {
std::filesystem::path resolve(const std::string& nameOrPath, const std::filesystem::path& baseDir) {
    const bool isPath = nameOrPath.find('/') != std::string::npos ||
                        (nameOrPath.size() > 3 && nameOrPath.ends_with(".so"));
    if (isPath) {
        std::filesystem::path p(nameOrPath);
        if (p.is_relative()) p = baseDir / p;
        return std::filesystem::exists(p) ? p : std::filesystem::path();
    }
    const std::string file = "lib" + nameOrPath + ".so";
    for (const auto& dir : searchPath())
        if (std::filesystem::exists(dir / file)) return dir / file;
    return {};
}

constexpr std::string_view kManifestSuffix = ".magPlugins.yaml";

// The entries of one manifest file, read once per process.
const std::vector<ManifestEntry>& readManifest(const std::filesystem::path& file) {
    static std::map<std::string, std::vector<ManifestEntry>> cache;
    const std::string key = std::filesystem::weakly_canonical(file).string();
    if (auto it = cache.find(key); it != cache.end()) return it->second;
    const Dict d = Dict::fromFile(file);
    std::vector<ManifestEntry> entries;
    for (const std::string& lib : d.keys()) {
        if (lib.find('/') != std::string::npos || !lib.ends_with(".so"))
            d.fail(lib, "expected a library file name (libmagFoo.so) mapped to its types, e.g. {field: [Foo]}");
        const Dict types = d.subOrEmpty(lib);
        ManifestEntry e{file.parent_path() / lib, file, {}};
        for (const std::string& registry : types.keys()) {
            if (std::find(registryNames().begin(), registryNames().end(), registry) == registryNames().end())
                types.fail(registry, "unknown registry '" + registry + "'; valid: " + joinNames(registryNames()));
            auto names = types.get<std::vector<std::string>>(registry);
            std::sort(names.begin(), names.end());
            if (!names.empty()) e.types[registry] = std::move(names);
        }
        entries.push_back(std::move(e));
    }
    return cache[key] = std::move(entries);
}

// The manifests of one folder, by file name.
std::vector<std::filesystem::path> manifestsIn(const std::filesystem::path& dir) {
    std::vector<std::filesystem::path> out;
    std::error_code ec;
    for (const auto& entry : std::filesystem::directory_iterator(dir, ec))
        if (entry.path().filename().string().ends_with(kManifestSuffix)) out.push_back(entry.path());
    std::sort(out.begin(), out.end());
    return out;
}

// The types each registry holds from library `file` (by file name).
std::map<std::string, std::vector<std::string>> typesFrom(const std::string& file) {
    std::map<std::string, std::vector<std::string>> out;
    auto collect = [&](const std::string& registry, const auto& r) {
        for (const auto& [name, entry] : r.entries())
            if (entry.library == file) out[registry].push_back(name); // std::map: sorted
    };
    collect("field", FieldEvaluator::registry());
    collect("induction", InductionModel::registry());
    collect("rigidBody", RigidBodyBackend::registry());
    collect("appliedField", AppliedField::registry());
    return out;
}

std::string typesText(const std::map<std::string, std::vector<std::string>>& types) {
    std::string out;
    for (const auto& [registry, names] : types)
        out += (out.empty() ? "" : ", ") + registry + ": [" + joinNames(names) + "]";
    return "{" + out + "}";
}

// A library that a manifest of its own folder lists registers exactly the types listed.
void checkAgainstManifest(const std::filesystem::path& path) {
    const std::string file = path.filename().string();
    for (const auto& manifest : manifestsIn(path.parent_path())) {
        for (const ManifestEntry& e : readManifest(manifest)) {
            if (e.library.filename() != file) continue;
            const auto registered = typesFrom(file);
            if (registered != e.types)
                throw InputError(path.string() + ": registers " + typesText(registered) + " but " + manifest.string() +
                                 " lists " + typesText(e.types) +
                                 " (the TYPES of its mag_add_plugin in CMake must name what it registers)");
        }
    }
}

bool openLibrary(const std::filesystem::path& path) {
    const std::string key = std::filesystem::weakly_canonical(path).string();
    if (openLibraries().count(key)) return false;
    const std::size_t before = registeredCount();
    const std::string saved = currentLibrary();
    currentLibrary() = path.filename().string();
    layoutMismatch().clear();
    void* handle = dlopen(key.c_str(), RTLD_NOW | RTLD_GLOBAL);
    currentLibrary() = saved;
    if (!handle) throw InputError(path.string() + ": cannot load plugin: " + dlerror());
    openLibraries()[key] = handle;
    if (!layoutMismatch().empty()) {
        const std::string lib = path.filename().string();
        FieldEvaluator::registry().removeLibrary(lib);
        InductionModel::registry().removeLibrary(lib);
        RigidBodyBackend::registry().removeLibrary(lib);
        AppliedField::registry().removeLibrary(lib);
        throw InputError(path.string() + ": cannot use plugin: " + layoutMismatch());
    }
    if (registeredCount() == before)
        spdlog::warn("library {} registered no new model types", path.filename().string());
    else
        spdlog::debug("loaded {}", key);
    checkAgainstManifest(path);
    return true;
}
} // namespace

bool load(const std::string& nameOrPath, const std::filesystem::path& baseDir) {
    const auto path = resolve(nameOrPath, baseDir);
    if (path.empty()) {
        std::string dirs;
        for (const auto& d : searchPath()) dirs += (dirs.empty() ? "" : ", ") + d.string();
        throw InputError("cannot find plugin library '" + nameOrPath + "' (searched: " +
                         (dirs.empty() ? std::string("nothing") : dirs) +
                         "; set MAG_PLUGIN_PATH to add folders, or give a path)");
    }
    return openLibrary(path);
}

bool tryLoadForType(const std::string& libName) {
    const auto path = resolve(libName, ".");
    if (path.empty()) return false;
    openLibrary(path);
    return true;
}

std::vector<ManifestEntry> manifestEntries() {
    std::vector<ManifestEntry> out;
    std::set<std::string> seen;
    for (const auto& dir : searchPath())
        for (const auto& manifest : manifestsIn(dir))
            for (const ManifestEntry& e : readManifest(manifest))
                if (seen.insert(e.library.filename().string()).second) out.push_back(e);
    return out;
}

std::vector<std::string> standardModules() {
    std::vector<std::string> out;
    for (const ManifestEntry& e : manifestEntries()) out.push_back(e.library.filename().string());
    return out;
}

void loadStandardModules() {
    static std::once_flag once;
    std::call_once(once, [] {
        for (const ManifestEntry& e : manifestEntries()) {
            if (!std::filesystem::exists(e.library)) {
                spdlog::debug("standard module {} not found; skipped", e.library.string());
                continue;
            }
            openLibrary(e.library);
        }
    });
}

bool loadForType(const std::string& registry, const std::string& type) {
    for (const ManifestEntry& e : manifestEntries()) {
        const auto it = e.types.find(registry);
        if (it == e.types.end() || !std::binary_search(it->second.begin(), it->second.end(), type)) continue;
        if (!std::filesystem::exists(e.library)) {
            spdlog::debug("{} lists {} type {} in {}, which is missing", e.manifest.string(), registry, type,
                          e.library.string());
            return false;
        }
        openLibrary(e.library);
        return true;
    }
    return false;
}

std::vector<std::string> loaded() {
    std::vector<std::string> out;
    for (const auto& kv : openLibraries()) out.push_back(std::filesystem::path(kv.first).filename().string());
    return out;
}

std::string listModules() {
    loadStandardModules();
    // Show what is there: every libmag*.so on the search path, not only the
    // standard ones.
    for (const auto& dir : searchPath()) {
        std::error_code ec;
        for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
            const std::string f = entry.path().filename().string();
            if (f.starts_with("libmag") && f.ends_with(".so") && f != "libmagCore.so") openLibrary(entry.path());
        }
    }
    std::ostringstream os;
    auto table = [&os](const std::string& title, const auto& registry) {
        os << title << ":\n";
        if (registry.size() == 0) os << "    (none)\n";
        for (const auto& [name, entry] : registry.entries())
            os << "    " << name << std::string(name.size() < 16 ? 16 - name.size() : 1, ' ') << "(" << entry.library
               << ")\n";
    };
    table("field evaluators (magSchemes.yaml field.type)", FieldEvaluator::registry());
    table("induction models (magSchemes.yaml induction.type)", InductionModel::registry());
    table("rigid-body backends (rigidBody.yaml type)", RigidBodyBackend::registry());
    table("applied fields (appliedField.yaml type)", AppliedField::registry());
    os << "plugin search path:";
    for (const auto& d : searchPath()) os << " " << d.string();
    os << "\n";
    return os.str();
}

} // namespace plugins

} // namespace mag
