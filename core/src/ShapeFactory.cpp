#include "magFoam/ShapeFactory.hpp"

#include "magFoam/Error.hpp"
#include "magFoam/Log.hpp"
#include "magFoam/MassProperties.hpp"
#include "magFoam/MeshIO.hpp"
#include "magFoam/MeshPrimitives.hpp"
#include "magFoam/MeshTopology.hpp"

#include <sstream>

namespace mag {

std::shared_ptr<const Shape> makeShape(SurfaceMesh mesh, const ShapeKind& kind,
                                       const ConvexPieces& pieces, const std::string& piecesName) {
    requireUsable(mesh);
    auto shape = std::make_shared<Shape>();
    const MassProperties mp = computeMassProperties(mesh, 1.0);
    const Vec3 centre = recentre(mesh);
    if (!pieces.empty()) {
        double mismatch = 0;
        shape->pieces = buildConvexPieces(pieces, -centre, mesh, mp.volume, piecesName, mismatch);
        // An exact decomposition tiles the mesh (float STL: ~1e-6); a looser
        // one (overlapping or approximate hulls) still collides, but not as the mesh.
        if (std::abs(mismatch) > 0.01)
            spdlog::warn("{}: the convex pieces' volumes add up to {:+.1f} % of the mesh's: they collide as "
                         "their union, not as the mesh", piecesName, 100 * mismatch);
    }
    shape->volume = mp.volume;
    shape->unitInertia = mp.inertia;
    shape->boundingRadius = boundingSphereRadius(mesh, Vec3::Zero());
    shape->mesh = std::move(mesh);
    shape->kind = kind;
    return shape;
}

namespace {

double positive(const Dict& d, const std::string& key, const std::string& what) {
    const double v = d.get<double>(key);
    if (!(v > 0)) d.fail(key, what + " must be positive (metres), got " + std::to_string(v));
    return v;
}

} // namespace

SurfaceMesh geometryMesh(const Dict& g, const std::filesystem::path& baseDir, ShapeKind& kind, std::string& key,
                         bool keyOnly) {
    const std::vector<std::string> kinds = {"box", "sphere", "cylinder", "file"};
    int count = 0;
    for (const auto& k : kinds) count += g.has(k) ? 1 : 0;
    if (count != 1) g.failHere("give exactly one of box, sphere, cylinder or file");

    kind = ShapeKind{};
    SurfaceMesh mesh;
    std::ostringstream os;
    os.precision(17);
    if (g.has("box")) {
        const Dict d = g.sub("box");
        kind.kind = ShapeKind::Kind::box;
        kind.size = d.get<Vec3>("size");
        if ((kind.size.array() <= 0).any()) d.fail("size", "box edge lengths must be positive (metres)");
        d.reportUnused();
        os << "box " << kind.size.transpose();
        if (!keyOnly) mesh = makeBox(kind.size);
    } else if (g.has("sphere")) {
        const Dict d = g.sub("sphere");
        kind.kind = ShapeKind::Kind::sphere;
        kind.radius = positive(d, "radius", "sphere radius");
        const int sub = d.get<int>("subdivisions", 3);
        if (sub < 0 || sub > 7) d.fail("subdivisions", "icosphere subdivisions must be 0..7");
        d.reportUnused();
        os << "sphere " << kind.radius << " " << sub;
        if (!keyOnly) mesh = makeIcosphere(kind.radius, sub);
    } else if (g.has("cylinder")) {
        const Dict d = g.sub("cylinder");
        kind.kind = ShapeKind::Kind::cylinder;
        kind.radius = positive(d, "radius", "cylinder radius");
        kind.height = positive(d, "height", "cylinder height");
        const int segments = d.get<int>("segments", 32);
        if (segments < 3 || segments > 4096) d.fail("segments", "cylinder segments must be 3..4096");
        d.reportUnused();
        os << "cylinder " << kind.radius << " " << kind.height << " " << segments;
        if (!keyOnly) mesh = makeCylinder(kind.radius, kind.height, segments);
    } else {
        kind.kind = ShapeKind::Kind::mesh;
        const std::filesystem::path file = baseDir / g.get<std::string>("file");
        const double s = g.get<double>("scale", 1.0);
        if (!(s > 0)) g.fail("scale", "scale must be positive (e.g. 0.001 for a mesh in mm)");
        kind.file = file.string();
        os << "file " << std::filesystem::weakly_canonical(file).string() << " " << s;
        if (!keyOnly) {
            try {
                mesh = loadMesh(file, s);
            } catch (const InputError& e) {
                g.fail("file", e.what());
            }
        }
    }
    g.reportUnused();
    key = os.str();
    return mesh;
}

std::shared_ptr<const Shape> ShapeCache::get(const Dict& g, const std::filesystem::path& baseDir) {
    ShapeKind kind;
    std::string key;
    geometryMesh(g, baseDir, kind, key, true);  // identical entries share a shape: no reload
    if (auto it = shapes_.find(key); it != shapes_.end()) return it->second;
    SurfaceMesh mesh = geometryMesh(g, baseDir, kind, key);
    ConvexPieces pieces;
    std::string piecesName;
    if (kind.kind == ShapeKind::Kind::mesh) {
        const std::filesystem::path file = piecesFileFor(kind.file);
        if (std::filesystem::exists(file)) {
            pieces = readConvexPieces(file, g.get<double>("scale", 1.0));
            piecesName = file.string();
        }
    }
    try {
        auto shape = makeShape(std::move(mesh), kind, pieces, piecesName);
        shapes_[key] = shape;
        return shape;
    } catch (const InputError& e) {
        g.failHere(std::string("unusable mesh: ") + e.what());
    }
}

} // namespace mag
