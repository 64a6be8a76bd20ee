// Case reading: every geometry and orientation form (docs/case-reference.md#bodies), and the
// errors users get for bad dictionaries (file, key, what was expected).
#include "caseFixture.hpp"

#include <magFoam/Case.hpp>
#include <magFoam/Error.hpp>

#include <catch2/catch.hpp>

using Catch::Matchers::Contains;
using mag::Case;
using mag::Vec3;

namespace {
const char* kMaterials = "N42: {model: permanent, Br: 1.3, density: 7500}\n"
                         "steel: {model: soft, k: 5.0, Js: 2.0, density: 7850}\n";

// A case with one body given by `bodyYaml` (a flow mapping).
magtest::TempCase& oneBody(magtest::TempCase& c, const std::string& bodyYaml,
                           const std::string& materials = kMaterials) {
    c.write("constant/materials.yaml", materials);
    c.write("constant/bodies.yaml", "bodies:\n  - " + bodyYaml + "\n");
    return c;
}
} // namespace

TEST_CASE("all geometry and orientation forms", "[case]") {
    magtest::TempCase c;
    c.write("system/controlDict.yaml", "startTime: 0\nendTime: 1\ndeltaT: 0.001\nwriteInterval: 0.01\n"
                                       "startFrom: latestTime\nlibs: []\nthreads: 2\n");
    c.write("constant/materials.yaml", kMaterials);
    c.write("constant/bodies.yaml",
            "bodies:\n"
            "  - name: cube\n"
            "    geometry: {box: {size: [0.01, 0.02, 0.03]}}\n"
            "    material: N42\n"
            "    magnetization: [0, 0, 2]\n"
            "    position: [0, 0, 0.011]\n"
            "    orientation: {axis: [0, 0, 1], angle: 90}\n"
            "    velocity: [1, 0, 0]\n"
            "    angularVelocity: [0, 0, 3]\n"
            "    motion: fixed\n"
            "  - {name: ball, geometry: {sphere: {radius: 0.005, subdivisions: 2}}, material: steel,\n"
            "     position: [0.1, 0, 0], orientation: {quaternion: [0, 1, 0, 0]}}\n"
            "  - {name: rod, geometry: {cylinder: {radius: 0.002, height: 0.05, segments: 16}},\n"
            "     material: N42, magnetization: [1, 0, 0], position: [0, 0.1, 0]}\n"
            "  - {name: cube2, geometry: {box: {size: [0.01, 0.02, 0.03]}}, material: N42,\n"
            "     magnetization: [0, 1, 0], position: [0, 0.2, 0]}\n");
    const Case cs = Case::read(c.dir());
    REQUIRE(cs.bodies().size() == 4);
    const auto& cube = cs.bodies()[0];
    CHECK(cube.fixed);
    CHECK(cs.control().threads == 2);
    CHECK(cs.control().startFrom == "latestTime");
    // |M| = Br / mu0 along the normalized direction.
    CHECK(cube.magnetizationBody.z() == Approx(1.3 / mag::mu0).epsilon(1e-14));
    CHECK(cube.mass() == Approx(7500 * 6e-6).epsilon(1e-12));
    CHECK((cube.orientation * Vec3::UnitX() - Vec3::UnitY()).norm() < 1e-15);
    CHECK(cube.shape->kind.kind == mag::ShapeKind::Kind::box);
    // Identical geometry entries share one shape (tables are built once).
    CHECK(cs.bodies()[3].shape == cube.shape);
    const auto& ball = cs.bodies()[1];
    CHECK(ball.soft());
    CHECK(ball.magnetizationBody.norm() == 0);
    CHECK((ball.orientation * Vec3::UnitY() + Vec3::UnitY()).norm() < 1e-15);
    CHECK(cs.bodies()[2].shape->kind.kind == mag::ShapeKind::Kind::cylinder);
    CHECK(cs.hasSoftBodies());
}

TEST_CASE("bad bodies give file, key and expectation", "[case][badInput]") {
    magtest::TempCase c;
    SECTION("unknown key (typo)") {
        oneBody(c, "{name: a, geometry: {box: {size: [1, 1, 1]}}, material: N42, magnetization: [0, 0, 1], "
                   "position: [0, 0, 0], velocty: [0, 0, 0]}");
        CHECK_THROWS_WITH(Case::read(c.dir()), Contains("constant/bodies.yaml:2:") && Contains("velocty") &&
                                                   Contains("did you mean 'velocity'"));
    }
    SECTION("a required key misspelt") {
        oneBody(c, "{name: a, geometry: {box: {size: [1, 1, 1]}}, material: N42, magnetisation: [0, 0, 1], "
                   "position: [0, 0, 0]}");
        CHECK_THROWS_WITH(Case::read(c.dir()), Contains("constant/bodies.yaml:2:") &&
                                                   Contains("did you mean 'magnetization'"));
    }
    SECTION("NaN in a position") {
        oneBody(c, "{name: a, geometry: {box: {size: [1, 1, 1]}}, material: N42, magnetization: [0, 0, 1], "
                   "position: [0, .nan, 0]}");
        CHECK_THROWS_WITH(Case::read(c.dir()),
                          Contains("constant/bodies.yaml:2:") && Contains("bodies[0].position") && Contains("finite"));
    }
    SECTION("unknown material") {
        oneBody(c, "{name: a, geometry: {box: {size: [1, 1, 1]}}, material: N52, magnetization: [0, 0, 1], "
                   "position: [0, 0, 0]}");
        CHECK_THROWS_WITH(Case::read(c.dir()), Contains("bodies[0].material") && Contains("N52") && Contains("N42"));
    }
    SECTION("negative density") {
        oneBody(c, "{name: a, geometry: {box: {size: [1, 1, 1]}}, material: N42, magnetization: [0, 0, 1], "
                   "position: [0, 0, 0]}",
                "N42: {model: permanent, Br: 1.3, density: -7500}\n");
        CHECK_THROWS_WITH(Case::read(c.dir()),
                          Contains("constant/materials.yaml:1:") && Contains("N42.density") && Contains("positive"));
    }
    SECTION("wrong type for a key") {
        oneBody(c, "{name: a, geometry: {box: {size: big}}, material: N42, magnetization: [0, 0, 1], "
                   "position: [0, 0, 0]}");
        CHECK_THROWS_WITH(Case::read(c.dir()), Contains("bodies[0].geometry.box.size") && Contains("3 numbers"));
    }
    SECTION("missing mesh file") {
        oneBody(c, "{name: a, geometry: {file: geometry/nothere.stl}, material: N42, magnetization: [0, 0, 1], "
                   "position: [0, 0, 0]}");
        CHECK_THROWS_WITH(Case::read(c.dir()), Contains("bodies[0].geometry.file") && Contains("nothere.stl"));
    }
    SECTION("unsupported mesh format") {
        c.write("constant/geometry/part.xyz", "1 2 3\n4 5 6\n");
        oneBody(c, "{name: a, geometry: {file: geometry/part.xyz}, material: N42, magnetization: [0, 0, 1], "
                   "position: [0, 0, 0]}");
        CHECK_THROWS_WITH(Case::read(c.dir()), Contains("bodies[0].geometry.file") && Contains("part.xyz"));
    }
    SECTION("soft body given a magnetization") {
        oneBody(c, "{name: a, geometry: {box: {size: [1, 1, 1]}}, material: steel, magnetization: [0, 0, 1], "
                   "position: [0, 0, 0]}");
        CHECK_THROWS_WITH(Case::read(c.dir()), Contains("magnetization") && Contains("soft"));
    }
    SECTION("two geometry kinds") {
        oneBody(c, "{name: a, geometry: {box: {size: [1, 1, 1]}, sphere: {radius: 1}}, material: N42, "
                   "magnetization: [0, 0, 1], position: [0, 0, 0]}");
        CHECK_THROWS_WITH(Case::read(c.dir()), Contains("bodies[0].geometry") && Contains("exactly one"));
    }
    SECTION("missing bodies file") {
        c.write("constant/materials.yaml", kMaterials);
        CHECK_THROWS_WITH(Case::read(c.dir()), Contains("constant/bodies.yaml") && Contains("not found"));
    }
    SECTION("bad controlDict") {
        oneBody(c, "{name: a, geometry: {box: {size: [1, 1, 1]}}, material: N42, magnetization: [0, 0, 1], "
                   "position: [0, 0, 0]}");
        c.write("system/controlDict.yaml", "endTime: 1\ndeltaT: -0.1\n");
        CHECK_THROWS_WITH(Case::read(c.dir()), Contains("system/controlDict.yaml:2:") && Contains("deltaT"));
    }
}

// Unusable meshes in a case: the error names the case file, the body's key
// and the mesh problem with its element.
#include <magFoam/MeshIO.hpp>
#include <magFoam/MeshPrimitives.hpp>
#include <magFoam/SurfaceMesh.hpp>

namespace {
std::string readMeshCase(const mag::SurfaceMesh& mesh) {
    magtest::TempCase c;
    mag::writeStlBinary(mesh, c.path("constant/geometry/part.stl"));
    oneBody(c, "{name: part, geometry: {file: geometry/part.stl}, material: N42, magnetization: [0, 0, 1], "
               "position: [0, 0, 0]}");
    try {
        Case::read(c.dir());
    } catch (const mag::InputError& e) {
        return e.what();
    }
    return "no error";
}
} // namespace

void requireParts(const std::string& msg, std::initializer_list<const char*> parts) {
    INFO(msg);
    for (const char* p : {"constant/bodies.yaml:2:", "bodies[0].geometry", "part.stl"}) CHECK_THAT(msg, Contains(p));
    for (const char* p : parts) CHECK_THAT(msg, Contains(p));
}

TEST_CASE("unusable meshes in a case are named with file, key and element", "[case][badInput]") {
    SECTION("open") {
        auto m = mag::makeBox(Vec3(1, 1, 1));
        m.triangles.pop_back();
        requireParts(readMeshCase(m), {"open", "edge"});
    }
    SECTION("inverted") {
        auto m = mag::makeBox(Vec3(1, 1, 1));
        mag::flipOrientation(m);
        requireParts(readMeshCase(m), {"inverted"});
    }
    SECTION("non-manifold edge") {
        auto m = mag::makeBox(Vec3(1, 1, 1));
        auto fin = m.triangles[0];
        m.vertices.push_back(Vec3(3, 3, 3));
        m.triangles.push_back({fin[1], fin[0], m.nVertices() - 1});
        requireParts(readMeshCase(m), {"manifold"});
    }
    SECTION("zero volume") {
        mag::SurfaceMesh m;
        m.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 0)};
        m.triangles = {{0, 1, 2}, {1, 3, 2}, {0, 2, 1}, {1, 2, 3}};
        requireParts(readMeshCase(m), {});
    }
}
