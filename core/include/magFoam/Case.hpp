// A case folder (docs/case-reference.md#case-folder): reads every dictionary into the object model.
//
//   case/system/controlDict.yaml    run controls        (ControlDict)
//   case/system/magSchemes.yaml     field: / induction: (kept as Dicts for the
//                                                         selected models)
//   case/constant/materials.yaml    named materials     (Material)
//   case/constant/bodies.yaml       bodies              (Body, Shape)
//   case/constant/rigidBody.yaml    backend dictionary  (kept as a Dict)
//
// Plugins named in controlDict `libs:` are loaded while reading, so models
// they register are selectable by the other dictionaries.
#pragma once

#include "magFoam/Body.hpp"
#include "magFoam/ControlDict.hpp"
#include "magFoam/Dictionary.hpp"
#include "magFoam/Material.hpp"
#include "magFoam/SleepSettings.hpp"

#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace mag {

class Case {
public:
    // Read the case in `dir`. Missing optional dictionaries are allowed here;
    // the accessors below fail with the missing file's name when used.
    // `schemes` replaces system/magSchemes.yaml (relative to the case).
    static Case read(const std::filesystem::path& dir, const std::filesystem::path& schemes = {});

    const std::filesystem::path& dir() const { return dir_; }
    const ControlDict& control() const;
    const Dict& magSchemes() const;
    const Dict& rigidBody() const;
    // rigidBody.yaml `sleep:` (disabled without the file or the key).
    const SleepSettings& sleep() const { return sleep_; }
    // magSchemes.yaml `field:` and `induction:` (default {type: none}).
    Dict fieldDict() const;
    Dict inductionDict() const;
    // constant/appliedField.yaml ({type: none} when the file is absent).
    Dict appliedFieldDict() const;

    const std::map<std::string, Material>& materials() const { return materials_; }
    std::vector<Body>& bodies() { return bodies_; }
    const std::vector<Body>& bodies() const { return bodies_; }
    // Index of a body by name; InputError naming `context` when unknown.
    std::size_t bodyIndex(const std::string& name, const std::string& context) const;

    bool hasSoftBodies() const;

private:
    std::filesystem::path dir_;
    std::optional<ControlDict> control_;
    std::optional<Dict> magSchemes_, rigidBody_, appliedField_;
    SleepSettings sleep_;
    std::map<std::string, Material> materials_;
    std::vector<Body> bodies_;
};

class ShapeCache;

// One entry of the `bodies:` list, as readBodies reads it (the Python module
// builds its bodies through it too). Its shape comes from `shapes` (geometry
// files resolved against `caseDir/constant`), or is `shape` when given: the
// entry then must not have a geometry key.
Body readBody(const Dict& entry, const std::map<std::string, Material>& materials, const std::filesystem::path& caseDir,
              ShapeCache& shapes, std::shared_ptr<const Shape> shape = nullptr);

// Body names are words: letters, digits and _ - . (at most bodyNameLimit
// characters), because they appear unquoted in every output (CSV rows, the
// restart bodies.yaml, VTK blocks, log lines). Empty when `name` is one,
// otherwise why not.
inline constexpr std::size_t bodyNameLimit = 64;
std::string bodyNameProblem(const std::string& name);

// Read constant/bodies.yaml (`bodies:` list) given the materials; geometry
// files are resolved against `caseDir/constant`.
std::vector<Body> readBodies(const Dict& dict, const std::map<std::string, Material>& materials,
                             const std::filesystem::path& caseDir);

} // namespace mag
