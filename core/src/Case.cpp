#include "magFoam/Case.hpp"

#include "magFoam/BodyOverlap.hpp"
#include "magFoam/Error.hpp"
#include "magFoam/InputFile.hpp"
#include "magFoam/MeshPrimitives.hpp"
#include "magFoam/Log.hpp"
#include "magFoam/Parts.hpp"
#include "magFoam/Plugins.hpp"
#include "magFoam/ShapeFactory.hpp"

#include <array>
#include <cctype>
#include <cmath>
#include <set>

namespace mag {

namespace {

std::optional<Dict> readOptional(const std::filesystem::path& file) {
    if (!inputPresent(file)) return std::nullopt;
    return Dict::fromFile(file);
}

[[noreturn]] void missing(const std::filesystem::path& dir, const std::string& file) {
    throw InputError((dir / file).string() + ": file not found (this app needs it)");
}

Quat readOrientation(const Dict& body) {
    if (!body.has("orientation")) return Quat::Identity();
    const Dict o = body.sub("orientation");
    Quat q;
    if (o.has("quaternion")) {
        q = o.get<Quat>("quaternion");
    } else {
        const Vec3 axis = o.get<Vec3>("axis");
        const double angle = o.get<double>("angle");  // degrees
        if (!(axis.stableNorm() > 0)) o.fail("axis", "rotation axis has zero length");
        // A non-integer angle within 0.1 % of a multiple of pi/12 (15 deg in
        // radians) up to 2 pi was almost certainly meant in radians.
        const double k = angle / (pi / 12);
        if (angle != std::round(angle) && std::abs(angle) <= 2 * pi + 1e-9 && std::round(k) != 0 &&
            std::abs(k - std::round(k)) < 1e-3 * std::abs(k))
            o.warn("angle", fmt::format("{:g} looks like radians ({:g} rad = {:g} deg); angles here are in degrees",
                                        angle, angle, angle * 180 / pi));
        // fmod is exact: a large angle turns as much as its remainder does.
        q = Quat(Eigen::AngleAxisd(std::fmod(angle, 360.0) * pi / 180.0, axis.stableNormalized()));
    }
    o.reportUnused();
    return q;
}

} // namespace

std::string bodyNameProblem(const std::string& name) {
    if (name.empty()) return "a body name must not be empty";
    if (name.size() > bodyNameLimit)
        return fmt::format("body name of {} characters; at most {}", name.size(), bodyNameLimit);
    for (const char c : name) {
        const auto u = static_cast<unsigned char>(c);
        if (std::isalnum(u) || c == '_' || c == '-' || c == '.') continue;
        const std::string shown = std::isprint(u) ? fmt::format("'{}'", c) : fmt::format("character {}", int(u));
        std::string printable;
        for (const char k : name) printable += std::isprint(static_cast<unsigned char>(k)) ? k : '?';
        return fmt::format("body name '{}' has {}: a name is a word of letters, digits and _ - . (it appears "
                           "unquoted in the CSV files and the restart state)",
                           printable, shown);
    }
    return {};
}

namespace {

// The material an entry (a body or a part) names.
const Material& entryMaterial(const Dict& e, const std::map<std::string, Material>& materials) {
    const std::string matName = e.get<std::string>("material");
    auto mat = materials.find(matName);
    if (mat == materials.end()) {
        std::string valid;
        for (const auto& [n, m] : materials) valid += (valid.empty() ? "" : ", ") + n;
        e.fail("material", "unknown material '" + matName + "'; materials in constant/materials.yaml: " +
                               (valid.empty() ? std::string("(none)") : valid));
    }
    return mat->second;
}

// The magnetization of an entry of `material` (A/m, in its own frame): Br/mu0
// along the given direction for a permanent one; none for a soft one (induced).
// `who` names the entry in messages ("body 'a'", "part 1 of body 'a'").
Vec3 entryMagnetization(const Dict& e, const Material& material, const std::string& who) {
    if (material.soft()) {
        if (e.has("magnetization"))
            e.fail("magnetization", who + ": a soft material takes no magnetization: it is induced (material '" +
                                        material.name + "' is soft)");
        return Vec3::Zero();
    }
    const Vec3 dir = e.get<Vec3>("magnetization");
    const double length = dir.stableNorm();
    if (length < 1e-12 && material.Br > 0) e.fail("magnetization", who + ": magnetization direction has zero length");
    return length > 0 ? Vec3(dir.stableNormalized() * material.Br / mu0) : Vec3::Zero();
}

// A compound body's `parts:` (docs/compound-bodies.md): each part's shape,
// material, magnetization and place in the layout; the body frame is the
// layout's, moved to the compound's centre of mass.
void readParts(const Dict& b, Body& body, const std::map<std::string, Material>& materials,
               const std::filesystem::path& caseDir, ShapeCache& shapes) {
    for (const char* key : {"geometry", "material", "magnetization"})
        if (b.has(key))
            b.fail(key, fmt::format("body '{}' has parts: give each part its own {} (a body takes either parts or "
                                    "geometry, material and magnetization)",
                                    body.name, key));
    const std::vector<Dict> entries = b.list("parts");
    if (entries.empty()) b.fail("parts", "body '" + body.name + "': the list of parts is empty");
    std::vector<Part> parts;
    std::vector<Vec3> magnetization;
    for (std::size_t k = 0; k < entries.size(); ++k) {
        const Dict& e = entries[k];
        const std::string who = fmt::format("part {} of body '{}'", k, body.name);
        if (!e.has("geometry")) e.failHere(who + " has no geometry (box, sphere, cylinder or file)");
        Part part;
        part.material = entryMaterial(e, materials);
        part.shape = shapes.get(e.sub("geometry"), caseDir / "constant");
        part.position = e.get<Vec3>("position", Vec3::Zero());
        part.orientation = readOrientation(e);
        magnetization.push_back(entryMagnetization(e, part.material, who));
        e.reportUnused();
        parts.push_back(std::move(part));
    }
    const CompoundLayout layout = makeCompound(std::move(parts));
    body.compound = layout.compound;
    body.shape = layout.shape;
    body.partMagnetization = std::move(magnetization);
    body.magnetizationBody = meanMagnetization(*body.compound, body.partMagnetization);
    // The compound's material stands for its parts' in messages only.
    body.material.name = "(parts)";
    body.material.density = body.compound->mass / body.shape->volume;
    if (layout.centreOfMass.norm() > 1e-9 * body.shape->boundingRadius)
        spdlog::info("{}: body '{}': centre of mass at {} in the parts' layout: the body's position is there",
                     b.where("parts"), body.name, formatPoint(layout.centreOfMass));
    // Parts that overlap count their common volume twice (mass, field). The
    // body is at the origin here (its pose is read next).
    std::vector<Body> placed;
    for (std::size_t k = 0; k < body.compound->parts.size(); ++k)
        placed.push_back(PartBodies::part(body, k, 1));
    warnOverlaps(placed, b.file() + " (body '" + body.name + "')",
                 "their common volume counts twice in the mass and the field");
}

// `cells: n` or `[nx, ny, nz]` on a soft box: the box as a compound of
// nx x ny x nz equal boxes, each magnetized on its own (the method of moments;
// docs/compound-bodies.md#cells).
void splitIntoCells(const Dict& b, Body& body) {
    const std::string who = "body '" + body.name + "'";
    if (!body.material.soft())
        b.fail("cells", who + ": cells are for soft bodies (a permanent magnet's magnetization is uniform)");
    if (body.shape->kind.kind != ShapeKind::Kind::box)
        b.fail("cells", who + ": cells split a box geometry; split other shapes into parts (docs/compound-bodies.md)");
    std::array<int, 3> n{};
    if (b.isList("cells")) {
        const auto v = b.get<std::vector<double>>("cells");
        if (v.size() != 3) b.fail("cells", "give n or [nx, ny, nz], whole numbers 1..32");
        for (int k = 0; k < 3; ++k) n[k] = static_cast<int>(v[k]);
        for (int k = 0; k < 3; ++k)
            if (v[k] != n[k]) b.fail("cells", "give n or [nx, ny, nz], whole numbers 1..32");
    } else {
        n.fill(b.get<int>("cells"));
    }
    for (int k : n)
        if (k < 1 || k > 32) b.fail("cells", "give n or [nx, ny, nz], whole numbers 1..32");
    if (n[0] * n[1] * n[2] == 1) return;
    const Vec3 size = body.shape->kind.size, cell = size.cwiseQuotient(Vec3(n[0], n[1], n[2]));
    ShapeKind kind;
    kind.kind = ShapeKind::Kind::box;
    kind.size = cell;
    const auto shape = makeShape(makeBox(cell), kind);
    std::vector<Part> parts;
    for (int i = 0; i < n[0]; ++i)
        for (int j = 0; j < n[1]; ++j)
            for (int k = 0; k < n[2]; ++k) {
                const Vec3 centre = (Vec3(i + 0.5, j + 0.5, k + 0.5).cwiseProduct(cell) - 0.5 * size).eval();
                parts.push_back(Part{shape, body.material, centre, Quat::Identity()});
            }
    const CompoundLayout layout = makeCompound(std::move(parts));
    body.compound = layout.compound;
    body.shape = layout.shape;
    body.partMagnetization.assign(body.compound->parts.size(), Vec3::Zero());
    body.magnetizationBody = Vec3::Zero();
    body.material.name += " (cells)";
}

} // namespace

Body readBody(const Dict& b, const std::map<std::string, Material>& materials, const std::filesystem::path& caseDir,
              ShapeCache& shapes, std::shared_ptr<const Shape> shape) {
    Body body;
    body.name = b.get<std::string>("name");
    if (const std::string why = bodyNameProblem(body.name); !why.empty()) b.fail("name", why);

    if (b.has("parts")) {
        if (shape) b.fail("parts", "body '" + body.name + "': a body given a shape takes no parts");
        readParts(b, body, materials, caseDir, shapes);
    } else {
        body.material = entryMaterial(b, materials);
        body.shape = shape ? std::move(shape) : shapes.get(b.sub("geometry"), caseDir / "constant");
        body.magnetizationBody = entryMagnetization(b, body.material, "body '" + body.name + "'");
        if (b.has("cells")) splitIntoCells(b, body);
    }

    body.position = b.get<Vec3>("position");
    // Plausibility (warnings; docs/case-reference.md#plausibility).
    const double across = 2 * body.shape->boundingRadius;
    if (across > 1.0)
        b.warn("geometry", fmt::format("body '{}' is {:.3g} m across: a mesh in mm without scale: 0.001?",
                                       body.name, across));
    else if (across > 0 && across < 1e-5)
        b.warn("geometry", fmt::format("body '{}' is {:.3g} m across (below 10 um): a scale that is too small?",
                                       body.name, across));
    if (body.position.norm() > 10.0)
        b.warn("position", fmt::format("{:.3g} m from the origin: in mm? Positions are in metres",
                                       body.position.norm()));
    body.orientation = readOrientation(b);
    body.velocity = b.get<Vec3>("velocity", Vec3::Zero());
    body.angularVelocity = b.get<Vec3>("angularVelocity", Vec3::Zero());
    body.fixed = b.getWord("motion", {"dynamic", "fixed"}, "dynamic") == "fixed";
    b.reportUnused();
    return body;
}

std::vector<Body> readBodies(const Dict& dict, const std::map<std::string, Material>& materials,
                             const std::filesystem::path& caseDir) {
    ShapeCache shapes;
    std::vector<Body> bodies;
    std::set<std::string> names;
    for (const Dict& b : dict.list("bodies")) {
        const std::string name = b.get<std::string>("name");
        if (const std::string why = bodyNameProblem(name); !why.empty()) b.fail("name", why);
        if (!names.insert(name).second) b.fail("name", "duplicate body name '" + name + "'");
        bodies.push_back(readBody(b, materials, caseDir, shapes));
    }
    dict.reportUnused();
    return bodies;
}

Case Case::read(const std::filesystem::path& dir, const std::filesystem::path& schemes) {
    Case c;
    c.dir_ = dir;
    if (!std::filesystem::is_directory(dir)) throw InputError(dir.string() + ": case folder not found");

    if (auto cd = readOptional(dir / "system/controlDict.yaml")) {
        c.control_ = ControlDict::read(*cd);
        for (const auto& lib : c.control_->libs) {
            try {
                plugins::load(lib, dir);
            } catch (const InputError& e) {
                cd->fail("libs", e.what());
            }
        }
    }
    if (schemes.empty()) {
        c.magSchemes_ = readOptional(dir / "system/magSchemes.yaml");
    } else {
        const auto file = schemes.is_absolute() ? schemes : dir / schemes;
        if (!std::filesystem::exists(file)) throw InputError(file.string() + ": -schemes file not found");
        c.magSchemes_ = Dict::fromFile(file);
    }
    c.rigidBody_ = readOptional(dir / "constant/rigidBody.yaml");
    if (c.rigidBody_) c.sleep_ = SleepSettings::read(*c.rigidBody_);
    c.appliedField_ = readOptional(dir / "constant/appliedField.yaml");

    const auto materialsFile = dir / "constant/materials.yaml";
    const auto bodiesFile = dir / "constant/bodies.yaml";
    if (!std::filesystem::exists(materialsFile)) missing(dir, "constant/materials.yaml");
    if (!std::filesystem::exists(bodiesFile)) missing(dir, "constant/bodies.yaml");
    c.materials_ = readMaterials(Dict::fromFile(materialsFile));
    c.bodies_ = readBodies(Dict::fromFile(bodiesFile), c.materials_, dir);
    if (c.bodies_.empty()) throw InputError(bodiesFile.string() + ": bodies: the list is empty");
    return c;
}

const ControlDict& Case::control() const {
    if (!control_) missing(dir_, "system/controlDict.yaml");
    return *control_;
}

const Dict& Case::magSchemes() const {
    if (!magSchemes_) missing(dir_, "system/magSchemes.yaml");
    return *magSchemes_;
}

const Dict& Case::rigidBody() const {
    if (!rigidBody_) missing(dir_, "constant/rigidBody.yaml");
    return *rigidBody_;
}

Dict Case::fieldDict() const { return magSchemes().sub("field"); }

Dict Case::appliedFieldDict() const {
    if (appliedField_) return *appliedField_;
    return Dict::fromString("type: none", (dir_ / "constant/appliedField.yaml").string());
}

Dict Case::inductionDict() const {
    if (magSchemes().has("induction")) return magSchemes().sub("induction");
    return Dict::fromString("type: none", magSchemes().file());
}

std::size_t Case::bodyIndex(const std::string& name, const std::string& context) const {
    for (std::size_t i = 0; i < bodies_.size(); ++i)
        if (bodies_[i].name == name) return i;
    std::string valid;
    for (const auto& b : bodies_) valid += (valid.empty() ? "" : ", ") + b.name;
    throw InputError(context + ": unknown body '" + name + "'; bodies: " + valid);
}

bool Case::hasSoftBodies() const {
    for (const auto& b : bodies_)
        if (b.soft()) return true;
    return false;
}

} // namespace mag
