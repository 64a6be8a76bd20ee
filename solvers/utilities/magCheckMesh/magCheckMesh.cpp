// magCheckMesh: says whether surface meshes can be magnet bodies, and if not,
// what is wrong and where.
//
//   magCheckMesh -case DIR          check the mesh of every body of a case
//   magCheckMesh FILE [-scale S]    check one mesh file
//
// Exit status: 0 all usable, 1 a mesh unusable or unreadable (or a case
// error), 2 usage error.
#include <magFoam/ArgList.hpp>
#include <magFoam/BodyOverlap.hpp>
#include <magFoam/ConvexPieces.hpp>
#include <magFoam/Case.hpp>
#include <magFoam/Error.hpp>
#include <magFoam/MassProperties.hpp>
#include <magFoam/MeshIO.hpp>
#include <magFoam/MeshTopology.hpp>
#include <magFoam/ShapeFactory.hpp>
#include <magFoam/SurfaceMesh.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <iostream>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace mag {

namespace {

std::string num(double x) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.9g", x);
    return buffer;
}

std::string vec(const Vec3& v) { return formatPoint(v); }

void row(std::ostream& out, const std::string& key, const std::string& value) {
    out << "  " << key << std::string(key.size() < 22 ? 22 - key.size() : 1, ' ') << value
        << '\n';
}

std::string yesNo(bool ok, const std::string& whyNot) { return ok ? "yes" : "NO (" + whyNot + ")"; }

} // namespace

// Prints the table and the verdict for one mesh; true if the mesh is usable.
// Shared by the single-file mode and (later) the -case mode.
bool checkAndReport(const SurfaceMesh& mesh, std::ostream& out) {
    const TopologyReport report = checkTopology(mesh);
    const BoundingBox box = boundingBox(mesh);

    row(out, "mesh", mesh.source);
    row(out, "triangles", std::to_string(mesh.nTriangles()));
    row(out, "vertices", std::to_string(mesh.nVertices()) +
                             (report.unusedVertices ? " (" + std::to_string(report.unusedVertices) +
                                                          " unused)"
                                                    : ""));
    row(out, "edges", std::to_string(report.edgeTable.edges.size()));
    row(out, "shells", std::to_string(report.shells) + " (Euler characteristic " +
                           std::to_string(report.eulerCharacteristic) + ")");
    row(out, "bounding box", vec(box.lower) + " to " + vec(box.upper));
    if (report.invalidTriangles.empty()) row(out, "surface area", num(surfaceArea(mesh)));

    // Mass properties exist only for a solid; unit density, since the material
    // (and so the density) is not part of the mesh.
    if (report.usable()) {
        try {
            const MassProperties mp = computeMassProperties(mesh, 1.0);
            row(out, "volume", num(mp.volume));
            row(out, "centre of mass", vec(mp.centreOfMass));
            row(out, "principal moments", vec(mp.principalMoments) +
                                              "  (unit density; times density = kg m^2)");
            for (int i = 0; i < 3; ++i)
                row(out, "principal axis " + std::to_string(i + 1), vec(mp.principalAxes.col(i)));
            row(out, "bounding radius", num(mp.boundingRadius) + "  (about the centre of mass)");
        } catch (const std::exception& e) {
            row(out, "mass properties", std::string("failed: ") + e.what());
        }
    } else {
        row(out, "signed volume", num(report.signedVolume));
        row(out, "mass properties", "n/a (mesh unusable)");
    }

    // The checks.
    row(out, "closed", yesNo(report.closed(), std::to_string(report.boundaryEdges.size()) +
                                                  " boundary edges"));
    row(out, "manifold", yesNo(report.manifold(),
                               std::to_string(report.nonManifoldEdges.size()) +
                                   " edges with more than two triangles, " +
                                   std::to_string(report.nonManifoldVertices.size()) +
                                   " vertices joining separate sheets"));
    row(out, "consistently oriented",
        yesNo(report.consistentlyOriented(),
              std::to_string(report.inconsistentEdges.size()) + " edges"));
    // Inside and outside exist only for a closed, manifold, oriented surface.
    if (report.closed() && report.manifold() && report.consistentlyOriented())
        row(out, "outward",
            yesNo(report.outward(), report.zeroVolume() ? "zero volume" : "inverted"));
    else
        row(out, "outward", "n/a (not a closed, manifold, oriented surface)");
    row(out, "degenerate triangles", std::to_string(report.degenerateTriangles.size()));
    row(out, "non-intersecting",
        yesNo(report.nonIntersecting(),
              std::to_string(report.intersectingPairs) +
                  (report.intersectingPairs == 1 ? " pair" : " pairs") +
                  " of triangles crossing or touching away from a shared vertex or edge"));
    // Nesting is defined only once inside and outside are (see TopologyReport).
    if (report.shells > 1)
        row(out, "shells nested",
            report.nestingChecked
                ? yesNo(report.properlyNested(),
                        std::to_string(report.misnestedShells.size()) +
                            (report.misnestedShells.size() == 1 ? " shell" : " shells") +
                            " nested wrongly")
                : "n/a (not a closed, manifold, oriented, non-intersecting surface)");
    for (int s = 0; s < static_cast<int>(report.shellVolumes.size()) && report.shells > 1; ++s) {
        if (report.shellVolumes[s] >= 0.0) continue;
        const int around = report.nestingChecked ? report.shellContainers[s] : -1;
        out << "  note: the " << describeShell(report, s) << " has negative volume "
            << num(report.shellVolumes[s])
            << (around >= 0 ? " (a cavity in the " + describeShell(report, around) + ")"
                            : std::string(" (a cavity, or an inverted part)"))
            << '\n';
    }

    const auto problems = describeProblems(mesh, report, 10);
    for (const auto& line : problems) out << "\n  problem: " << line << '\n';

    if (report.usable()) {
        out << "\nmesh OK\n";
        return true;
    }
    std::string reasons;
    for (const auto& name : problemNames(report)) reasons += (reasons.empty() ? "" : ", ") + name;
    out << "\nmesh UNUSABLE: " << reasons << '\n';
    return false;
}

// The convex pieces beside a mesh file (docs/rigid-bodies.md#convex-pieces),
// when there is a pieces file: their count and how their volumes add up;
// false when they cannot be used.
bool reportPieces(const std::filesystem::path& meshFile, double scale, const SurfaceMesh& mesh, std::ostream& out) {
    const std::filesystem::path file = piecesFileFor(meshFile);
    if (!std::filesystem::exists(file)) return true;
    try {
        const auto pieces = readConvexPieces(file, scale);
        double mismatch = 0;
        const double volume = computeMassProperties(mesh).volume;
        buildConvexPieces(pieces, Vec3::Zero(), mesh, volume, file.string(), mismatch);
        row(out, "convex pieces", std::to_string(pieces.size()) + " (" + file.filename().string() +
                                      "), volumes add up to the mesh's " +
                                      (std::abs(mismatch) <= 1e-4 ? "(exact decomposition)"
                                                                  : "within " + num(100 * mismatch) + " %"));
        if (std::abs(mismatch) > 0.01)
            out << "  note: the pieces collide as their union, not as the mesh (overlapping or approximate)\n";
        return true;
    } catch (const std::exception& e) {
        out << "convex pieces UNUSABLE: " << e.what() << '\n';
        return false;
    }
}

} // namespace mag

namespace {

int checkFile(const std::string& file, double scale) {
    std::cout << "magCheckMesh " << file;
    if (scale != 1.0) std::cout << " (scale " << scale << ")";
    std::cout << "\n\n";
    try {
        mag::MeshLoadReport load;
        const mag::SurfaceMesh mesh = mag::loadSurfaceMesh(file, {.scale = scale}, &load);
        mag::row(std::cout, "read", std::to_string(load.trianglesRead) + " triangles, " +
                                        std::to_string(load.verticesRead) + " vertices (" + load.format + ")");
        mag::row(std::cout, "welded",
                 std::to_string(load.verticesMerged) + " vertices merged, " +
                     std::to_string(load.collapsedTrianglesRemoved) + " collapsed triangles removed" +
                     (load.pointsAndLinesIgnored
                          ? ", " + std::to_string(load.pointsAndLinesIgnored) + " points/lines ignored"
                          : ""));
        const bool ok = mag::checkAndReport(mesh, std::cout);
        return ok && mag::reportPieces(file, scale, mesh, std::cout) ? 0 : 1;
    } catch (const std::exception& e) {
        std::cout << "mesh UNUSABLE: " << e.what() << '\n';
        return 1;
    }
}

// Every body's geometry, reported one by one (a broken mesh does not hide the
// others), then the whole case read as the solver reads it.
int checkCase(const std::filesystem::path& dir) {
    const auto bodiesFile = dir / "constant/bodies.yaml";
    const mag::Dict bodies = mag::Dict::fromFile(bodiesFile);
    int unusable = 0, n = 0;
    auto check = [&](const mag::Dict& entry) {
        ++n;
        try {
            mag::ShapeKind kind;
            std::string key;
            const mag::SurfaceMesh mesh = mag::geometryMesh(entry.sub("geometry"), dir / "constant", kind, key);
            std::cout << "  geometry: " << mesh.source << "\n";
            const bool ok = mag::checkAndReport(mesh, std::cout);
            if (!ok ||
                (kind.kind == mag::ShapeKind::Kind::mesh &&
                 !mag::reportPieces(kind.file, entry.sub("geometry").get<double>("scale", 1.0), mesh, std::cout)))
                ++unusable;
        } catch (const std::exception& e) {
            std::cout << "mesh UNUSABLE: " << e.what() << '\n';
            ++unusable;
        }
    };
    for (const mag::Dict& b : bodies.list("bodies")) {
        const std::string name = b.get<std::string>("name", "(unnamed)");
        std::cout << "body " << name << " (" << b.where() << ")\n";
        if (b.has("parts")) {
            // A compound (docs/compound-bodies.md): each part's mesh.
            const std::vector<mag::Dict> parts = b.list("parts");
            for (std::size_t k = 0; k < parts.size(); ++k) {
                std::cout << " part " << k << " (" << parts[k].where() << ")\n";
                check(parts[k]);
            }
        } else {
            check(b);
        }
        std::cout << "\n";
    }
    if (unusable) {
        std::cout << "magCheckMesh: " << unusable << " of " << n << " meshes UNUSABLE\n";
        return 1;
    }
    // The rest of the case (materials, poses, ...) as the solver sees it.
    const mag::Case c = mag::Case::read(dir);
    mag::warnOverlaps(c.bodies(), (dir / "constant" / "bodies.yaml").string(),
                      "a contact solver pushes them apart at the start of magFoam");
    std::cout << "magCheckMesh: all " << n << " meshes OK; case " << dir.string() << " reads cleanly\n";
    return 0;
}

} // namespace

int main(int argc, char** argv) {
    mag::ArgList args("magCheckMesh",
                      "Checks that surface meshes can be magnet bodies: closed, manifold, consistently and\n"
                      "outward oriented, no degenerate triangles, non-zero volume, no two triangles crossing\n"
                      "or touching, nested shells inverted (cavities). Prints counts, volume,\n"
                      "centre of mass, principal moments of inertia (unit density), bounding radius, every\n"
                      "problem with the elements involved, and a verdict. Without FILE: every body of the\n"
                      "case. Formats: .stl (ASCII/binary) .obj .ply .off.\n"
                      "Exit status: 0 OK, 1 a mesh unusable or unreadable, 2 usage error.");
    args.positional("FILE", "check this mesh file instead of the case's bodies", false)
        .option("scale", "S", "with FILE: multiply coordinates by S (e.g. 0.001 for files in mm)");
    args.outputs("  nothing: a table on stdout; exit status 0 OK, 1 a mesh unusable or unreadable\n");
    if (!args.parse(argc, argv)) return args.exitCode();
    double scale = 1.0;
    if (args.found("scale")) {
        const std::string v = args.get("scale");
        char* end = nullptr;
        scale = std::strtod(v.c_str(), &end);
        if (end != v.c_str() + v.size() || !(scale > 0) || !std::isfinite(scale)) {
            std::cerr << "magCheckMesh: -scale " << v << ": expected a finite number > 0\n";
            return 2;
        }
    }
    if (args.positionalValue()) return checkFile(*args.positionalValue(), scale);
    return mag::runGuarded(args, [](const mag::ArgList& a) { return checkCase(a.caseDir()); });
}
