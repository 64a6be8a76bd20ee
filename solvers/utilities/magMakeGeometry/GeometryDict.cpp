// geometryDict.yaml front end: a registry of part types (name -> reader), the
// per-entry checks and the writing of a case's STL files.
#include "GeometryDict.hpp"

#include "PartShapes.hpp"

#include <magFoam/ConvexPieces.hpp>
#include <magFoam/Error.hpp>
#include <magFoam/MeshIO.hpp>
#include <magFoam/OutputFile.hpp>
#include <magFoam/MeshPrimitives.hpp>
#include <magFoam/MeshTopology.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <functional>
#include <map>
#include <set>
#include <string>

namespace mag {

namespace {

// What a reader returns: the build step, run after every key is read (so
// misspelled keys are reported before any work), and whether the parts are
// written as separate meshes; the convex pieces of part k of the build (none
// for convex parts, which collide as their hull, and concave ones without a
// decomposition).
struct PartBuild {
    std::function<std::vector<SurfaceMesh>()> build;
    bool split = false;
    std::function<ConvexPieces(std::size_t, const SurfaceMesh&)> pieces;
};

TubeCap readCaps(const Dict& d) {
    return d.getWord("caps", {"round", "flat"}, "round") == "round" ? TubeCap::round : TubeCap::flat;
}

// tube path: a list of [x, y, z] points.
std::vector<Vec3> readPath(const Dict& d) {
    if (!d.has("path")) d.fail("path", "required key is missing (a list of [x, y, z] points)");
    const YAML::Node node = d.node()["path"];
    if (!node.IsSequence() || node.size() < 2)
        d.fail("path", "expected a list of at least two [x, y, z] points");
    std::vector<Vec3> path;
    for (std::size_t i = 0; i < node.size(); ++i) {
        const YAML::Node& p = node[i];
        bool ok = p.IsSequence() && p.size() == 3;
        Vec3 x = Vec3::Zero();
        for (int k = 0; ok && k < 3; ++k) {
            try {
                x[k] = p[k].as<double>();
                ok = std::isfinite(x[k]);
            } catch (const YAML::Exception&) {
                ok = false;
            }
        }
        if (!ok) d.fail("path", "point " + std::to_string(i) + " is not a vector of 3 finite numbers");
        path.push_back(x);
    }
    return path;
}

// One reader per type: its keys with their defaults (documented in
// magMakeGeometry.cpp), in the order they are read.

PartBuild readPaperclip(const Dict& e) {
    const double length = e.get<double>("length", 0.033), width = e.get<double>("width", 0.008);
    const double wire = e.get<double>("wire", 0.0009), spacing = e.get<double>("spacing", 0.0);
    const int segments = e.get<int>("segments", 12), bend = e.get<int>("bendSegments", 16);
    const TubeCap caps = readCaps(e);
    return {[=] { return std::vector{makePaperclip(length, width, wire, segments, bend, spacing, caps)}; }, false,
            [=](std::size_t, const SurfaceMesh& m) { return tubePieces(m, segments); }};
}

// Every default scales with width (binderClipOptions); split: true writes the
// sheet and both handles as separate meshes.
PartBuild readBinderClip(const Dict& e) {
    BinderClipOptions o = binderClipOptions(e.get<double>("width", 0.025));
    o.depth = e.get<double>("depth", o.depth);
    o.spine = e.get<double>("spine", o.spine);
    o.thickness = e.get<double>("thickness", o.thickness);
    o.mouthGap = e.get<double>("mouthGap", o.mouthGap);
    o.lip = e.get<double>("lip", o.lip);
    o.lipAngle = e.get<double>("lipAngle", o.lipAngle);
    o.foldRadius = e.get<double>("foldRadius", o.foldRadius);
    o.foldSegments = e.get<int>("foldSegments", o.foldSegments);
    o.handles = e.get<bool>("handles", o.handles);
    o.handleWire = e.get<double>("handleWire", o.handleWire);
    o.handleLength = e.get<double>("handleLength", o.handleLength);
    o.handleSpan = e.get<double>("handleSpan", o.handleSpan);
    o.handleLoop = e.get<double>("handleLoop", o.handleLoop);
    o.handlePivot = e.get<double>("handlePivot", o.handlePivot);
    o.handleCorner = e.get<double>("handleCorner", o.handleCorner);
    o.handleSegments = e.get<int>("handleSegments", o.handleSegments);
    o.handleBendSegments = e.get<int>("handleBendSegments", o.handleBendSegments);
    const bool split = e.get<bool>("split", false);
    return {[=] { return makeBinderClip(o); }, split, [=](std::size_t k, const SurfaceMesh& m) {
                return k == 0 ? platePieces(m) : tubePieces(m, o.handleSegments);
            }};
}

PartBuild readHexNut(const Dict& e) {
    const double f = e.get<double>("acrossFlats", 0.008), hole = e.get<double>("hole", 0.005);
    const double t = e.get<double>("thickness", 0.004);
    const int segments = e.get<int>("segments", 24);
    return {[=] { return std::vector{makeHexNut(f, hole, t, segments)}; }, false,
            [](std::size_t, const SurfaceMesh& m) { return annulusPieces(m); }};
}

PartBuild readWasher(const Dict& e) {
    const double outer = e.get<double>("outer", 0.010), inner = e.get<double>("inner", 0.0053);
    const double t = e.get<double>("thickness", 0.001);
    const int segments = e.get<int>("segments", 32);
    return {[=] { return std::vector{makeWasher(outer, inner, t, segments)}; }, false,
            [](std::size_t, const SurfaceMesh& m) { return annulusPieces(m); }};
}

PartBuild readBentPlate(const Dict& e) {
    const double width = e.get<double>("width", 0.02), t = e.get<double>("thickness", 0.0015);
    const double legA = e.get<double>("legA", 0.03), legB = e.get<double>("legB", 0.02);
    const double angle = e.get<double>("angle", 90.0), radius = e.get<double>("bendRadius", t);
    const int segments = e.get<int>("bendSegments", 6);
    return {[=] { return std::vector{makeBentPlate(width, t, legA, legB, angle, radius, segments)}; }, false,
            [](std::size_t, const SurfaceMesh& m) { return platePieces(m); }};
}

PartBuild readRod(const Dict& e) {
    const double radius = e.get<double>("radius", 0.003), length = e.get<double>("length", 0.05);
    const int segments = e.get<int>("segments", 24);
    return {[=] { return std::vector{makeRod(radius, length, segments)}; }, false, {}};  // convex: no pieces
}

// An ellipsoid (a soft needle or a ball): the icosphere scaled per axis,
// 20 4^subdivisions triangles.
PartBuild readEllipsoid(const Dict& e) {
    const Vec3 semiAxes = e.get<Vec3>("semiAxes", Vec3(0.005, 0.0005, 0.0005));
    if (!(semiAxes.minCoeff() > 0)) e.fail("semiAxes", "three semi-axes > 0 (m)");
    const int subdivisions = e.get<int>("subdivisions", 4);
    if (subdivisions < 0 || subdivisions > 6) e.fail("subdivisions", "0..6 (20 4^subdivisions triangles)");
    return {[=] { return std::vector{makeEllipsoid(semiAxes, subdivisions)}; }, false, {}};  // convex: no pieces
}

PartBuild readBarMagnet(const Dict& e) {
    const Vec3 size = e.get<Vec3>("size", Vec3(0.05, 0.01, 0.01));
    return {[=] { return std::vector{makeBarMagnet(size)}; }, false, {}};  // convex: no pieces
}

PartBuild readCraneDisc(const Dict& e) {
    const double radius = e.get<double>("radius", 0.15), height = e.get<double>("height", 0.05);
    const double rimWidth = e.get<double>("rimWidth", 0.015), rimDepth = e.get<double>("rimDepth", 0.01);
    const int segments = e.get<int>("segments", 64);
    return {[=] { return std::vector{makeCraneDisc(radius, height, rimWidth, rimDepth, segments)}; }, false,
            [=](std::size_t, const SurfaceMesh&) { return craneDiscPieces(radius, height, rimWidth, rimDepth, segments); }};
}

// path and wire (a diameter) are required; cornerRadius > 0 rounds the corners.
PartBuild readTube(const Dict& e) {
    const std::vector<Vec3> path = readPath(e);
    const double wire = e.get<double>("wire");
    const int segments = e.get<int>("segments", 12);
    const TubeCap caps = readCaps(e);
    const double corner = e.get<double>("cornerRadius", 0.0);
    const int bend = e.get<int>("bendSegments", 4);
    return {[=] {
                return std::vector{makeTube(corner > 0.0 ? roundCorners(path, corner, bend) : path, 0.5 * wire,
                                            segments, caps)};
            },
            false, [=](std::size_t, const SurfaceMesh& m) { return tubePieces(m, segments); }};
}

// The one list of part types: a new type is one reader and one line here.
// A map, so shapeTypes() and the error for an unknown type list them sorted.
using PartReader = PartBuild (*)(const Dict&);
const std::map<std::string, PartReader>& partTypes() {
    static const std::map<std::string, PartReader> types = {
        {"barMagnet", readBarMagnet}, {"bentPlate", readBentPlate}, {"binderClip", readBinderClip},
        {"craneDisc", readCraneDisc}, {"ellipsoid", readEllipsoid}, {"hexNut", readHexNut},
        {"paperclip", readPaperclip},
        {"rod", readRod},             {"tube", readTube},           {"washer", readWasher},
    };
    return types;
}

bool validName(const std::string& name) {
    if (name.empty() || name == "." || name == "..") return false;
    return std::all_of(name.begin(), name.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.';
    });
}

} // namespace

std::vector<std::string> shapeTypes() {
    std::vector<std::string> names;
    for (const auto& [name, reader] : partTypes()) names.push_back(name);
    return names;
}

std::vector<NamedMesh> makeNamedShapes(const Dict& e) {
    const std::string name = e.get<std::string>("name");
    if (!validName(name))
        e.fail("name", "'" + name + "' is not a file name: use letters, digits, '_', '-', '.'");
    const std::string type = e.get<std::string>("type");
    const auto reader = partTypes().find(type);
    if (reader == partTypes().end()) {
        std::string list;
        for (const auto& t : shapeTypes()) list += (list.empty() ? "" : ", ") + t;
        e.fail("type", "unknown shape type '" + type + "'; valid types: " + list);
    }

    // A generator's complaint is re-thrown at the entry's position.
    const PartBuild part = reader->second(e);
    e.reportUnused();

    std::vector<SurfaceMesh> meshes;
    std::vector<ConvexPieces> pieces;
    try {
        meshes = part.build();
        for (std::size_t k = 0; k < meshes.size(); ++k) {
            requireUsable(meshes[k]);
            pieces.push_back(part.pieces ? part.pieces(k, meshes[k]) : ConvexPieces{});
        }
    } catch (const InputError& err) {
        e.failHere(type + " '" + name + "': " + err.what());
    }

    std::vector<NamedMesh> out;
    if (meshes.size() == 1 || !part.split) {
        ConvexPieces all;
        for (ConvexPieces& p : pieces) all.insert(all.end(), p.begin(), p.end());
        out.push_back({name, type, meshes.size() == 1 ? std::move(meshes[0]) : mergeParts(meshes), std::move(all)});
        out.back().mesh.source = name + ": " + out.back().mesh.source;
    } else {
        const std::vector<std::string> suffix = {"_sheet", "_handle1", "_handle2"};
        for (std::size_t i = 0; i < meshes.size(); ++i) {
            out.push_back({name + suffix.at(i), type, std::move(meshes[i]), std::move(pieces[i])});
            out.back().mesh.source = out.back().name + ": " + out.back().mesh.source;
        }
    }
    return out;
}

std::vector<NamedMesh> makeCaseGeometry(const std::filesystem::path& caseDir) {
    if (!std::filesystem::is_directory(caseDir)) throw InputError(caseDir.string() + ": case folder not found");
    const std::filesystem::path dictFile = caseDir / "system/geometryDict.yaml";
    if (!std::filesystem::exists(dictFile))
        throw InputError(dictFile.string() + ": not found (it lists the parts to build: parts: [...])");
    const Dict dict = Dict::fromFile(dictFile);
    const std::vector<Dict> entries = dict.list("parts");
    dict.reportUnused();
    if (entries.empty()) dict.fail("parts", "the list of parts is empty");

    // Build and check everything before writing anything.
    std::vector<NamedMesh> meshes;
    std::set<std::string> names;
    for (const Dict& entry : entries)
        for (NamedMesh& m : makeNamedShapes(entry)) {
            if (!names.insert(m.name).second)
                entry.fail("name", "a part named '" + m.name + "' exists already");
            meshes.push_back(std::move(m));
        }

    const std::filesystem::path folder = caseDir / "constant/geometry";
    makeFolder(folder);
    for (const NamedMesh& m : meshes) {
        writeStlBinary(m.mesh, folder / (m.name + ".stl"));
        // Pieces beside the mesh; an old file of a part that has none now would not match it.
        const std::filesystem::path pieces = piecesFileFor(folder / (m.name + ".stl"));
        if (!m.pieces.empty())
            writeConvexPieces(pieces, m.name + ".stl", m.pieces);
        else
            std::filesystem::remove(pieces);
    }
    return meshes;
}

} // namespace mag
