#include "magFoam/Plugins.hpp"

#include "magFoam/Error.hpp"
#include "magFoam/FieldEvaluator.hpp"
#include "magFoam/InductionModel.hpp"
#include "magFoam/Log.hpp"
#include "magFoam/RigidBodyBackend.hpp"

#include <dlfcn.h>

#include <cstdlib>
#include <map>
#include <mutex>
#include <set>
#include <sstream>

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
           RigidBodyBackend::registry().size();
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

template <class Base>
std::unique_ptr<Base> selectFromRegistry(Registry<Base>& registry, const Dict& dict, const std::string& what) {
    const std::string type = dict.get<std::string>("type");
    if (!registry.has(type)) plugins::tryLoadForType("mag" + type);
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
    return selectFromRegistry(registry(), dict, "field evaluator");
}
std::unique_ptr<InductionModel> InductionModel::New(const Dict& dict) {
    plugins::loadStandardModules();
    return selectFromRegistry(registry(), dict, "induction model");
}
std::unique_ptr<RigidBodyBackend> RigidBodyBackend::New(const Dict& dict) {
    plugins::loadStandardModules();
    return selectFromRegistry(registry(), dict, "rigid-body backend");
}

namespace plugins {

const std::vector<std::string>& standardModules() {
    static const std::vector<std::string> names = {"magMBM", "magEDM", "magHybrid", "magLLG", "magODE", "magFreeBody"};
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

bool openLibrary(const std::filesystem::path& path) {
    const std::string key = std::filesystem::weakly_canonical(path).string();
    if (openLibraries().count(key)) return false;
    const std::size_t before = registeredCount();
    const std::string saved = currentLibrary();
    currentLibrary() = path.filename().string();
    void* handle = dlopen(key.c_str(), RTLD_NOW | RTLD_GLOBAL);
    currentLibrary() = saved;
    if (!handle) throw InputError(path.string() + ": cannot load plugin: " + dlerror());
    openLibraries()[key] = handle;
    if (registeredCount() == before)
        spdlog::warn("library {} registered no new model types", path.filename().string());
    else
        spdlog::debug("loaded {}", key);
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

void loadStandardModules() {
    static std::once_flag once;
    std::call_once(once, [] {
        for (const auto& name : standardModules()) {
            const auto path = resolve(name, ".");
            if (path.empty()) {
                spdlog::debug("standard module {} not found; skipped", name);
                continue;
            }
            openLibrary(path);
        }
    });
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
    os << "plugin search path:";
    for (const auto& d : searchPath()) os << " " << d.string();
    os << "\n";
    return os.str();
}

} // namespace plugins

} // namespace mag
