// Embedding and shell nesting of a body's mesh (MeshTopology): the field kernels
// integrate over the boundary of the solid whose winding number is 1, so
// triangles must not cross or touch away from their shared elements, and nested
// shells must alternate outward / inverted (cavity) from the outside in.
// Meshes are built from the primitives, moved and flipped, so every expected
// answer follows from the construction.
#include "expectError.hpp"

#include <catch2/catch.hpp>

#include <magFoam/Dictionary.hpp>
#include <magFoam/Error.hpp>
#include <magFoam/MassProperties.hpp>
#include <magFoam/MeshIO.hpp>
#include <magFoam/MeshPrimitives.hpp>
#include <magFoam/MeshTopology.hpp>
#include <magFoam/ShapeFactory.hpp>
#include <magFoam/SurfaceMesh.hpp>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

using namespace mag;
namespace fs = std::filesystem;

namespace {

// Box of edge lengths `size` centred at `centre`; inverted: triangles reversed.
SurfaceMesh box(const Vec3& size, const Vec3& centre = Vec3::Zero(), bool inverted = false) {
    SurfaceMesh mesh = makeBox(size);
    translate(mesh, centre);
    if (inverted) flipOrientation(mesh);
    return mesh;
}

SurfaceMesh cube(double side, const Vec3& centre = Vec3::Zero(), bool inverted = false) {
    return box(Vec3::Constant(side), centre, inverted);
}

// The parts in order (part k's triangles follow part k-1's), not welded.
SurfaceMesh combine(const std::vector<SurfaceMesh>& parts) {
    SurfaceMesh mesh;
    mesh.source = "combined";
    for (const SurfaceMesh& part : parts) append(mesh, part);
    return mesh;
}

// The message requireUsable throws (the one case reading gives).
std::string inputErrorOf(const SurfaceMesh& mesh) {
    return magtest::inputErrorOf([&] { requireUsable(mesh); });
}

using magtest::contains;

bool has(const std::vector<std::string>& names, const std::string& name) {
    return std::find(names.begin(), names.end(), name) != names.end();
}

// Every stored pair joins a triangle below `split` with one at or above it.
bool allPairsAcross(const TopologyReport& report, int split) {
    return std::all_of(report.intersectingTriangles.begin(), report.intersectingTriangles.end(),
                       [&](const std::array<int, 2>& p) { return p[0] < split && p[1] >= split; });
}

} // namespace

TEST_CASE("two overlapping boxes are rejected, naming the triangles and shells", "[mesh][shells]") {
    const SurfaceMesh mesh = combine({cube(1.0), cube(1.0, Vec3(0.5, 0.5, 0.5))});
    const TopologyReport report = checkTopology(mesh);
    // Every other check passes: closed, manifold, oriented, outward, two shells.
    CHECK(report.closed());
    CHECK(report.manifold());
    CHECK(report.consistentlyOriented());
    CHECK(report.outward());
    CHECK(report.shells == 2);

    CHECK_FALSE(report.nonIntersecting());
    CHECK_FALSE(report.usable());
    CHECK(report.intersectingPairs == report.intersectingTriangles.size());
    CHECK(report.intersectingPairs >= 6);  // three faces of each cube cross three of the other's
    CHECK(allPairsAcross(report, 12));
    CHECK(std::is_sorted(report.intersectingTriangles.begin(), report.intersectingTriangles.end()));
    CHECK_FALSE(report.nestingChecked);  // inside and outside are undefined
    CHECK(has(problemNames(report), "self-intersecting"));

    const auto [a, b] = report.intersectingTriangles.front();
    const std::string message = inputErrorOf(mesh);
    CHECK(contains(message, "combined: surface intersects itself"));
    CHECK(contains(message, "triangle " + std::to_string(a) + " (vertices"));
    CHECK(contains(message, "and triangle " + std::to_string(b) + " (vertices"));
    CHECK(contains(message, "the shell of triangles 0-11 and the shell of triangles 12-23 overlap"));
    CHECK(contains(message, "magCheckMesh lists every problem"));
}

TEST_CASE("a box inside a box with the same orientation is rejected", "[mesh][shells]") {
    const SurfaceMesh mesh = combine({cube(2.0), cube(1.0)});
    const TopologyReport report = checkTopology(mesh);
    CHECK(report.nonIntersecting());
    CHECK(report.outward());
    REQUIRE(report.nestingChecked);
    CHECK(report.shellContainers == std::vector<int>{-1, 0});
    CHECK(report.misnestedShells == std::vector<int>{1});
    CHECK_FALSE(report.usable());
    CHECK(has(problemNames(report), "shells nested wrongly"));
    CHECK(contains(inputErrorOf(mesh),
                   "combined: shells are nested wrongly: the shell of triangles 12-23 lies inside the "
                   "shell of triangles 0-11 with the same orientation (both outward): its volume "
                   "counts twice"));

    // Listed the other way round, the inner shell is still the one named first.
    const TopologyReport swapped = checkTopology(combine({cube(1.0), cube(2.0)}));
    CHECK(swapped.shellContainers == std::vector<int>{1, -1});
    CHECK(swapped.misnestedShells == std::vector<int>{0});
}

TEST_CASE("a box with an inverted inner box is a hollow body", "[mesh][shells]") {
    const SurfaceMesh hollow = combine({cube(2.0), cube(1.0, Vec3(0.2, -0.1, 0.3), true)});
    const TopologyReport report = checkTopology(hollow);
    REQUIRE(report.nestingChecked);
    CHECK(report.shellContainers == std::vector<int>{-1, 0});
    CHECK(report.properlyNested());
    CHECK(report.usable());
    CHECK_NOTHROW(requireUsable(hollow));
    CHECK(computeMassProperties(hollow, 1.0).volume == Approx(8.0 - 1.0).epsilon(1e-14));

    // An island in the cavity is outward again: 27 - 8 + 1.
    const SurfaceMesh island = combine({cube(3.0), cube(2.0, Vec3::Zero(), true), cube(1.0)});
    const TopologyReport islandReport = checkTopology(island);
    CHECK(islandReport.shellContainers == std::vector<int>{-1, 0, 1});
    CHECK(islandReport.usable());
    CHECK(computeMassProperties(island, 1.0).volume == Approx(27.0 - 8.0 + 1.0).epsilon(1e-14));

    // A cavity in the cavity would cut the same space out twice.
    const SurfaceMesh twice =
        combine({cube(3.0), cube(2.0, Vec3::Zero(), true), cube(1.0, Vec3::Zero(), true)});
    const TopologyReport twiceReport = checkTopology(twice);
    CHECK(twiceReport.misnestedShells == std::vector<int>{2});
    CHECK_FALSE(twiceReport.usable());
    CHECK(contains(inputErrorOf(twice), "the shell of triangles 24-35 lies inside the shell of triangles "
                                        "12-23 with the same orientation (both inverted)"));
}

TEST_CASE("an inverted shell inside no outward shell is rejected", "[mesh][shells]") {
    // Total volume 8 - 1 > 0: only the nesting check sees the stray cavity.
    const SurfaceMesh mesh = combine({cube(2.0), cube(1.0, Vec3(5, 0, 0), true)});
    const TopologyReport report = checkTopology(mesh);
    CHECK(report.outward());
    CHECK(report.shellContainers == std::vector<int>{-1, -1});
    CHECK(report.misnestedShells == std::vector<int>{1});
    CHECK_FALSE(report.usable());
    CHECK(contains(inputErrorOf(mesh), "the shell of triangles 12-23 is inverted (a cavity) but lies "
                                       "inside no outward shell"));
}

TEST_CASE("disjoint outward boxes are one body of two pieces", "[mesh][shells]") {
    const SurfaceMesh mesh = combine({cube(1.0), box({1, 2, 0.5}, Vec3(3, 0, 0))});
    const TopologyReport report = checkTopology(mesh);
    CHECK(report.shells == 2);
    CHECK(report.nonIntersecting());
    CHECK(report.nestingChecked);
    CHECK(report.shellContainers == std::vector<int>{-1, -1});
    CHECK(report.usable());
    CHECK(computeMassProperties(mesh, 1.0).volume == Approx(2.0).epsilon(1e-14));
}

TEST_CASE("a box with a corner pushed through the opposite face is rejected", "[mesh][shells]") {
    SurfaceMesh mesh = cube(1.0);
    mesh.source = "pushed";
    const auto corner = std::find(mesh.vertices.begin(), mesh.vertices.end(), Vec3(0.5, 0.5, 0.5));
    REQUIRE(corner != mesh.vertices.end());
    *corner = Vec3(-1.0, 0.1, 0.2);
    const TopologyReport report = checkTopology(mesh);
    CHECK(report.closed());
    CHECK(report.consistentlyOriented());
    CHECK(report.degenerateTriangles.empty());
    CHECK_FALSE(report.nonIntersecting());
    CHECK_FALSE(report.usable());
    const std::string message = inputErrorOf(mesh);
    CHECK(contains(message, "pushed: surface intersects itself"));
    CHECK_FALSE(contains(message, "overlap)"));  // one shell
}

TEST_CASE("a face folded back onto its neighbour is an intersection", "[mesh][shells]") {
    // Tetrahedron a b c d with d lowered into the base: the three side triangles
    // fold onto the base triangle, each over an edge they share.
    auto tetra = [](double height) {
        SurfaceMesh mesh;
        mesh.source = "tetra";
        mesh.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.2, 0.3, height}};
        mesh.triangles = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}};
        return mesh;
    };
    const TopologyReport flat = checkTopology(tetra(0.0));
    CHECK(flat.degenerateTriangles.empty());
    CHECK(flat.intersectingPairs == 3);  // the base with each side; the sides tile the base
    CHECK(std::find(flat.intersectingTriangles.begin(), flat.intersectingTriangles.end(),
                    std::array<int, 2>{0, 1}) != flat.intersectingTriangles.end());
    CHECK_FALSE(flat.usable());
    // Within the tolerance (1e-9 of the size) still folded; above it a thin solid.
    CHECK_FALSE(checkTopology(tetra(1e-12)).nonIntersecting());
    CHECK(checkTopology(tetra(1e-6)).usable());
}

TEST_CASE("boxes touching face to face, edge to edge or corner to corner are rejected", "[mesh][shells]") {
    // Documented choice: shells that share a face region lie on each other
    // (coplanar overlapping triangles), and shells that touch along an edge or at
    // a point make the solid non-manifold there; both are intersections. Merge
    // such parts into one shell, or leave a gap.
    for (const Vec3& offset : {Vec3(1, 0, 0), Vec3(1, 0.3, 0.2), Vec3(1, 1, 0), Vec3(1, 1, 1)}) {
        INFO("offset " << offset.transpose());
        const TopologyReport report = checkTopology(combine({cube(1.0), cube(1.0, offset)}));
        CHECK(report.closed());
        CHECK(report.manifold());  // by index: the corners are not shared
        CHECK_FALSE(report.nonIntersecting());
        CHECK(allPairsAcross(report, 12));
        CHECK_FALSE(report.usable());
    }
    // Welded, the shared face makes non-manifold edges as well.
    SurfaceMesh welded = combine({cube(1.0), cube(1.0, Vec3(1, 0, 0))});
    weldVertices(welded);
    const TopologyReport weldedReport = checkTopology(welded);
    CHECK_FALSE(weldedReport.manifold());
    CHECK_FALSE(weldedReport.nonIntersecting());

    // A gap below the tolerance (1e-9 of the size) still touches; a real gap does not.
    CHECK_FALSE(checkTopology(combine({cube(1.0), cube(1.0, Vec3(1 + 1e-12, 0, 0))})).nonIntersecting());
    CHECK(checkTopology(combine({cube(1.0), cube(1.0, Vec3(1 + 1e-6, 0, 0))})).usable());
}

TEST_CASE("fine primitives have no false intersections", "[mesh][shells]") {
    const std::vector<SurfaceMesh> meshes = {
        makeIcosphere(0.01, 5),                       // 20480 triangles
        makeEllipsoid(Vec3(1.0, 1.0, 0.002), 4),      // thin: the two faces 1e-3 of the size apart
        makeCylinder(0.005, 0.001, 4096),             // long fans in the caps
        makeCylinder(1e-4, 1.0, 256),                 // a needle
    };
    for (const SurfaceMesh& mesh : meshes) {
        INFO(mesh.source);
        const TopologyReport report = checkTopology(mesh);
        CHECK(report.intersectingPairs == 0);
        CHECK(report.usable());
    }
}

TEST_CASE("all intersecting pairs are counted, the lowest stored", "[mesh][shells]") {
    // The same sphere twice, not welded: every triangle lies on its twin and
    // touches its neighbours' twins.
    const SurfaceMesh sphere = makeIcosphere(1.0, 3);  // 1280 triangles
    const TopologyReport report = checkTopology(combine({sphere, sphere}));
    const std::size_t keep = TopologyReport::maxStoredIntersections;
    CHECK(report.intersectingPairs > keep);
    REQUIRE(report.intersectingTriangles.size() == keep);
    CHECK(std::is_sorted(report.intersectingTriangles.begin(), report.intersectingTriangles.end()));
    CHECK(report.intersectingTriangles.front() == std::array<int, 2>{0, 1280});
    CHECK(allPairsAcross(report, 1280));
    CHECK(contains(describeProblems(combine({sphere, sphere}), report, 2).back(),
                   "; ... (" + std::to_string(report.intersectingPairs - 2) + " more)"));
}

// tests/badMeshes: files that load but are not solids; reading them as a case
// does (ShapeCache) fails naming the file and the triangles or shells.
TEST_CASE("overlapping, nested and self-intersecting mesh files are rejected", "[mesh][shells][bad]") {
    const fs::path dir = fs::path(MAG_SOURCE_DIR) / "tests";
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"overlappingShells.obj", ": surface intersects itself: "},
        {"nestedShell.obj", ": shells are nested wrongly: the shell of triangles 12-23 lies inside the "
                            "shell of triangles 0-11 with the same orientation"},
        {"selfIntersecting.obj", ": surface intersects itself: "},
    };
    for (const auto& [name, expected] : cases) {
        INFO(name);
        const fs::path file = dir / "badMeshes" / name;
        const SurfaceMesh mesh = loadSurfaceMesh(file);
        CHECK_FALSE(checkTopology(mesh).usable());
        const std::string message = inputErrorOf(mesh);
        CHECK(contains(message, file.string() + expected));
        CHECK(contains(message, "triangle"));
        if (contains(expected, "intersects"))
            CHECK(contains(message, ") and triangle "));

        ShapeCache cache;
        const Dict geometry = Dict::fromString("file: badMeshes/" + name, "bodies.yaml");
        std::string caseMessage;
        try {
            (void)cache.get(geometry, dir);
        } catch (const InputError& e) {
            caseMessage = e.what();
        }
        CHECK(contains(caseMessage, file.string() + expected));
    }
}

// Not run by default: `test_meshShells "[.timing]"` prints the check's time on
// a 20480-triangle sphere (the figure docs/architecture.md quotes).
TEST_CASE("time of the checks on 20480 triangles", "[.timing]") {
    const SurfaceMesh sphere = makeIcosphere(0.01, 5);
    const auto start = std::chrono::steady_clock::now();
    int runs = 0;
    std::size_t pairs = 0;
    for (; runs < 10; ++runs) pairs += checkTopology(sphere).intersectingPairs;
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    WARN("checkTopology on " << sphere.nTriangles() << " triangles: " << seconds / runs * 1e3 << " ms");
    CHECK(pairs == 0);
}
