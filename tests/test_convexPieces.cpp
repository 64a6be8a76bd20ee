// Convex pieces of concave meshes (docs/rigid-bodies.md#convex-pieces): the
// hull of a point set against closed forms, the exact decompositions of the
// generated parts (their hulls tile the mesh: volumes add up to the mesh's),
// the pieces file read beside a mesh, and thin concave parts resting on the
// ground and on each other through their pieces, on ODE and on Bullet.
#include "backendFixture.hpp"
#include "caseFixture.hpp"

#include "../solvers/utilities/magMakeGeometry/PartShapes.hpp"

#include <magFoam/BodyOverlap.hpp>
#include <magFoam/ConvexPieces.hpp>
#include <magFoam/MassProperties.hpp>
#include <magFoam/MeshIO.hpp>
#include <magFoam/MeshTopology.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <random>

using Catch::Matchers::Contains;
using mag::ConvexHull;
using mag::Vec3;

TEST_CASE("convex hull: vertices, faces and volume of closed-form solids", "[convexPieces]") {
    SECTION("a box with points inside, on its faces and on its edges") {
        std::vector<Vec3> p;
        for (int i = 0; i < 8; ++i) p.emplace_back(i & 1 ? 0.02 : 0, i & 2 ? 0.01 : 0, i & 4 ? 0.005 : 0);
        p.emplace_back(0.01, 0.005, 0.0025);  // inside
        p.emplace_back(0.01, 0.005, 0.005);   // on the top face
        p.emplace_back(0.01, 0.0, 0.0);       // on an edge
        const ConvexHull h = mag::convexHull(p, "box");
        CHECK(h.points.size() == 8);
        CHECK(h.faces.size() == 6);  // coplanar triangles merged into one face each
        CHECK(h.volume == Approx(0.02 * 0.01 * 0.005).epsilon(1e-12));
        CHECK((h.centroid - Vec3(0.01, 0.005, 0.0025)).norm() < 1e-15);
        for (std::size_t f = 0; f < h.faces.size(); ++f) {
            CHECK(h.faces[f].size() == 4);
            // Counter-clockwise about the outward normal.
            const auto& loop = h.faces[f];
            const Vec3 n = (h.points[loop[1]] - h.points[loop[0]]).cross(h.points[loop[2]] - h.points[loop[1]]);
            CHECK(n.normalized().dot(h.normals[f]) == Approx(1.0));
        }
    }
    SECTION("a regular octahedron and a tetrahedron") {
        const double a = 0.003;
        const std::vector<Vec3> oct = {{a, 0, 0}, {-a, 0, 0}, {0, a, 0}, {0, -a, 0}, {0, 0, a}, {0, 0, -a}};
        const ConvexHull h = mag::convexHull(oct, "octahedron");
        CHECK(h.faces.size() == 8);
        CHECK(h.volume == Approx(4.0 / 3.0 * a * a * a).epsilon(1e-12));
        const ConvexHull t = mag::convexHull({{0, 0, 0}, {a, 0, 0}, {0, a, 0}, {0, 0, a}}, "tetrahedron");
        CHECK(t.volume == Approx(a * a * a / 6).epsilon(1e-12));
        CHECK((t.centroid - Vec3::Constant(a / 4)).norm() < 1e-18);
    }
    SECTION("points on a sphere: the hull is inside it and every point is inside the hull") {
        std::mt19937 rng(5);
        std::normal_distribution<double> g;
        std::vector<Vec3> p;
        for (int i = 0; i < 60; ++i) p.push_back(0.01 * Vec3(g(rng), g(rng), g(rng)).normalized());
        const ConvexHull h = mag::convexHull(p, "sphere");
        CHECK(h.points.size() == 60);  // all on the sphere: all vertices
        CHECK(h.volume < 4.0 / 3.0 * std::numbers::pi * 1e-6);
        CHECK(h.volume > 0.7 * 4.0 / 3.0 * std::numbers::pi * 1e-6);
        for (const Vec3& q : p)
            for (std::size_t f = 0; f < h.normals.size(); ++f) CHECK(h.normals[f].dot(q) <= h.offsets[f] + 1e-15);
        // Euler: V - E + F = 2 with E = (sum of face sizes) / 2.
        std::size_t edges = 0;
        for (const auto& face : h.faces) edges += face.size();
        CHECK(static_cast<long>(h.points.size()) - static_cast<long>(edges / 2) + static_cast<long>(h.faces.size()) == 2);
    }
    SECTION("too few, flat or non-finite point sets are errors naming the piece") {
        CHECK_THROWS_WITH(mag::convexHull({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, "piece 3"),
                          Contains("piece 3") && Contains("at least 4"));
        CHECK_THROWS_WITH(mag::convexHull({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}}, "piece 4"),
                          Contains("piece 4") && Contains("one plane"));
        CHECK_THROWS_WITH(mag::convexHull({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, NAN}}, "piece 5"),
                          Contains("not finite"));
    }
}

namespace {

// Sum of the pieces' hull volumes against the mesh's volume, and every piece's
// points are vertices of the mesh (the pieces are cut along the mesh's own rings).
void checkTiles(const mag::SurfaceMesh& mesh, const mag::ConvexPieces& pieces, std::size_t expected) {
    INFO(mesh.source);
    CHECK(pieces.size() == expected);
    double sum = 0;
    for (std::size_t k = 0; k < pieces.size(); ++k) {
        sum += mag::convexHull(pieces[k], "piece " + std::to_string(k)).volume;
        for (const Vec3& p : pieces[k])
            CHECK(std::any_of(mesh.vertices.begin(), mesh.vertices.end(), [&](const Vec3& v) { return v == p; }));
    }
    // Same numbers summed in another order: round-off only. Pieces that
    // overlapped or left gaps would miss by whole pieces (~1/expected).
    CHECK(sum == Approx(mag::computeMassProperties(mesh).volume).epsilon(1e-11));
}

} // namespace

TEST_CASE("convex pieces tile the generated parts exactly", "[convexPieces][geometry]") {
    using mag::TubeCap;
    SECTION("paperclip, round and flat caps") {
        // Round caps of 6 sides: 2 latitude rings each; 3 bends of 6 chords -> 24 path points.
        const mag::SurfaceMesh round = mag::makePaperclip(0.033, 0.008, 0.0009, 6, 6);
        const int rings = (round.nVertices() - 2) / 6;
        checkTiles(round, mag::tubePieces(round, 6), rings + 1);
        const mag::SurfaceMesh flat = mag::makePaperclip(0.033, 0.008, 0.0009, 8, 4, 0.0, TubeCap::flat);
        checkTiles(flat, mag::tubePieces(flat, 8), (flat.nVertices() - 2) / 8 - 1);
    }
    SECTION("a tube along a 3-D path") {
        const mag::SurfaceMesh tube =
            mag::makeTube({{0, 0, 0}, {0.01, 0, 0}, {0.01, 0.01, 0.005}, {0, 0.02, 0.01}}, 0.001, 8);
        checkTiles(tube, mag::tubePieces(tube, 8), (tube.nVertices() - 2) / 8 + 1);
    }
    SECTION("bent plate, washer, hex nut, binder clip") {
        const mag::SurfaceMesh plate = mag::makeBentPlate(0.008, 0.0012, 0.014, 0.009, 90, 0.0012, 2);
        checkTiles(plate, mag::platePieces(plate), plate.nVertices() / 4 - 1);
        const mag::SurfaceMesh washer = mag::makeWasher(0.012, 0.0055, 0.0012, 16);
        checkTiles(washer, mag::annulusPieces(washer), 16);
        const mag::SurfaceMesh nut = mag::makeHexNut(0.008, 0.005, 0.004, 12);
        checkTiles(nut, mag::annulusPieces(nut), 12);
        const auto clip = mag::makeBinderClip(0.019);
        checkTiles(clip[0], mag::platePieces(clip[0]), clip[0].nVertices() / 4 - 1);
        checkTiles(clip[1], mag::tubePieces(clip[1], mag::binderClipOptions(0.019).handleSegments),
                   (clip[1].nVertices() - 2) / 8 + 1);
    }
    SECTION("crane disc with its rim") {
        const mag::SurfaceMesh crane = mag::makeCraneDisc(0.06, 0.025, 0.008, 0.005, 32);
        const mag::ConvexPieces pieces = mag::craneDiscPieces(0.06, 0.025, 0.008, 0.005, 32);
        CHECK(pieces.size() == 33);
        double sum = 0;
        for (const auto& p : pieces) sum += mag::convexHull(p, "crane piece").volume;
        CHECK(sum == Approx(mag::computeMassProperties(crane).volume).epsilon(1e-11));
        CHECK(mag::craneDiscPieces(0.06, 0.025, 0.0, 0.0, 32).empty());  // no rim: convex, one hull
    }
    SECTION("a mesh of another layout is refused") {
        CHECK_THROWS_WITH(mag::tubePieces(mag::makeWasher(), 6), Contains("not a tube"));
        CHECK_THROWS_WITH(mag::platePieces(mag::makePaperclip()), Contains("not an extruded plate"));
        CHECK_THROWS_WITH(mag::annulusPieces(mag::makeBarMagnet()), Contains("not an annulus"));
    }
}

namespace {

// A case folder's geometry: the paperclip's STL and its pieces file, the
// mesh written in millimetres (scale 0.001 in bodies.yaml).
std::shared_ptr<const mag::Shape> loadClip(magtest::TempCase& c, double fileScale, const std::string& piecesText = "") {
    mag::SurfaceMesh clip = mag::makePaperclip(0.033, 0.008, 0.0009, 6, 6);
    const mag::ConvexPieces pieces = mag::tubePieces(clip, 6);
    mag::ConvexPieces scaled = pieces;
    for (auto& p : scaled)
        for (Vec3& v : p) v /= fileScale;
    for (Vec3& v : clip.vertices) v /= fileScale;
    std::filesystem::create_directories(c.path("constant/geometry"));
    mag::writeStlBinary(clip, c.path("constant/geometry/clip.stl"));
    if (piecesText.empty())
        mag::writeConvexPieces(c.path("constant/geometry/clip.pieces.yaml"), "clip.stl", scaled);
    else
        c.write("constant/geometry/clip.pieces.yaml", piecesText);
    mag::ShapeCache cache;
    return cache.get(mag::Dict::fromString("file: geometry/clip.stl\nscale: " + std::to_string(fileScale), "bodies.yaml"),
                     c.path("constant"));
}

} // namespace

TEST_CASE("a mesh file's pieces are read beside it, scaled and moved into the body frame", "[convexPieces]") {
    magtest::TempCase c;
    const auto shape = loadClip(c, 0.001);
    REQUIRE(shape->pieces.size() > 20);
    // The pieces tile the mesh: their volumes add up to it (the STL is single
    // precision: 1e-6) and their volume-weighted centroid is the mesh's centre
    // of mass, the body frame's origin.
    double volume = 0;
    Vec3 moment = Vec3::Zero();
    for (const ConvexHull& h : shape->pieces) volume += h.volume, moment += h.volume * h.centroid;
    CHECK(volume == Approx(shape->volume).epsilon(1e-5));
    CHECK(moment.norm() / volume < 1e-8);  // m; the clip is 33 mm long

    SECTION("a pieces file of another scale is refused, naming it") {
        magtest::TempCase d;
        CHECK_THROWS_WITH(loadClip(d, 1.0, "mesh: clip.stl\npieces:\n  - [0, 0, 0, 10, 0, 0, 0, 10, 0, 0, 0, 10]\n"),
                          Contains("clip.pieces.yaml") && Contains("piece 0") && Contains("bounding box"));
    }
    SECTION("malformed pieces files name the file and the key") {
        magtest::TempCase d;
        CHECK_THROWS_WITH(loadClip(d, 1.0, "mesh: clip.stl\npieces:\n  - [0, 0, 0, 0.001, 0, 0]\n"),
                          Contains("clip.pieces.yaml") && Contains("pieces") && Contains("at least 4 points"));
        magtest::TempCase e;
        CHECK_THROWS_WITH(loadClip(e, 1.0, "mesh: clip.stl\npeices: []\n"),
                          Contains("clip.pieces.yaml") && Contains("peices"));
    }
}

TEST_CASE("magCheckMesh reports a mesh file's convex pieces", "[convexPieces][app]") {
    magtest::TempCase c;
    loadClip(c, 0.001);
    CHECK(magtest::runApp(c.dir(), "magCheckMesh", "log", "constant/geometry/clip.stl -scale 0.001") == 0);
    CHECK_THAT(magtest::slurp(c.path("log")), Contains("convex pieces") && Contains("26 (clip.pieces.yaml)") &&
                                                  Contains("exact decomposition"));
    // Pieces of another scale: unusable, naming the file and the piece.
    c.write("constant/geometry/clip.pieces.yaml", "pieces:\n  - [0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1]\n");
    CHECK(magtest::runApp(c.dir(), "magCheckMesh", "log", "constant/geometry/clip.stl -scale 0.001") == 1);
    CHECK_THAT(magtest::slurp(c.path("log")),
               Contains("convex pieces UNUSABLE") && Contains("clip.pieces.yaml: piece 0"));
}

namespace {

// Two paperclips dropped on the ground, the second crossing the first 2 mm
// higher: both must come to rest, the lower flat on the ground, the upper on
// the lower, without gaining energy.
struct ClipDrop {
    double speed = 0, lowZ = 0, highZ = 0, rise = 0;
    std::string describe;
};
ClipDrop dropClips(const std::string& yaml) {
    magtest::TempCase c;
    auto shape = loadClip(c, 0.001);
    std::vector<mag::Body> bodies(2);
    for (int k = 0; k < 2; ++k) {
        bodies[k].name = "clip" + std::to_string(k);
        bodies[k].shape = shape;
        bodies[k].material.density = 7850;
    }
    bodies[0].position = Vec3(0, 0, 0.001);
    bodies[1].position = Vec3(0.003, 0.001, 0.003);
    bodies[1].orientation = mag::Quat(Eigen::AngleAxisd(1.2, Vec3::UnitZ()));
    auto rb = backendtest::backend(yaml);
    rb->setup(bodies);
    const backendtest::Run run = backendtest::simulate(*rb, bodies, Vec3(0, 0, -9.81), Vec3::Zero(), 1e-4, 4000);
    ClipDrop d;
    d.rise = run.energyRise;
    for (const mag::Body& b : bodies)
        d.speed = std::max(d.speed, b.velocity.norm() + b.angularVelocity.norm() * b.shape->boundingRadius);
    d.lowZ = backendtest::lowestZ(bodies[0]);
    d.highZ = backendtest::lowestZ(bodies[1]);
    d.describe = rb->describe();
    return d;
}

} // namespace

TEST_CASE("paperclips rest on the ground and on each other through their convex pieces", "[convexPieces][odeBackend][bulletBackend]") {
    const std::string engine = GENERATE(std::string("ODE"), std::string("Bullet"));
    INFO(engine);
    // Measured: ODE 5e-12 m/s, Bullet 4e-7 m/s at the end; Bullet's GImpact
    // meshes (collisionShapes: trimesh) leave the upper clip 50 um into the
    // lower one and rocking at 2 cm/s.
    const ClipDrop d = dropClips("type: " + engine + "\ngravity: [0, 0, -9.81]\nground: {}\ncontact: {friction: 0.4}\n");
    INFO(d.describe);
    CHECK_THAT(d.describe, Contains(engine == "ODE" ? "convex" : "convex pieces"));
    // At rest after 0.4 s (the drop takes 20 ms): every point below 1 mm/s.
    CHECK(d.speed < 1e-3);
    // The lower clip flat on the ground (the backends' contact layers: ODE
    // rests 1 um deep, Bullet within its 10 um margin).
    CHECK(std::abs(d.lowZ) < 2e-5);
    // The upper clip lies flat across the lower one (it crosses both long
    // legs on each side of its centre): its lowest point one wire (0.9 mm) up.
    CHECK(std::abs(d.highZ - 0.0009) < 2e-5);
    // No energy gained (the start is the highest energy; contacts only take).
    CHECK(d.rise < 1e-9);
}

TEST_CASE("ODE: convex pieces rest on a fixed concave triangle mesh", "[convexPieces][odeBackend]") {
    // ODE's convex-trimesh collider (libccd) needs the mesh's face angles:
    // without them the first contact stopped the run with an ODE error.
    magtest::TempCase c;
    std::vector<mag::Body> bodies(2);
    bodies[0] = backendtest::makeBody("L", backendtest::makeL(0.01, 0.03), mag::ShapeKind{});
    bodies[0].fixed = true;
    bodies[1].name = "clip";
    bodies[1].shape = loadClip(c, 0.001);
    bodies[1].material.density = 7850;
    // The L lies with its flat L-shaped cap up (z = 15 mm); the clip falls
    // onto it from 20 mm, its centre over the L's centre of mass.
    bodies[1].position = Vec3(0.0, 0.0, 0.02);
    auto rb = backendtest::backend("type: ODE\ngravity: [0, 0, -9.81]\ncontact: {friction: 0.4}\n");
    rb->setup(bodies);
    INFO(rb->describe());
    CHECK_THAT(rb->describe(), Contains("trimesh") && Contains("convex"));
    const backendtest::Run run = backendtest::simulate(*rb, bodies, Vec3(0, 0, -9.81), Vec3::Zero(), 1e-4, 4000);
    const double speed = bodies[1].velocity.norm() + bodies[1].angularVelocity.norm() * bodies[1].shape->boundingRadius;
    CHECK(speed < 1e-3);
    CHECK(run.energyRise < 1e-9);
    // Resting on the L (not through it): its lowest point on the L's highest face under it.
    double highest = -1e300;
    for (const Vec3& v : bodies[0].shape->mesh.vertices) highest = std::max(highest, bodies[0].toWorld(v).z());
    CHECK(backendtest::lowestZ(bodies[1]) > highest - 2e-5);
}

TEST_CASE("two paperclips interlocked at their bends are pushed apart", "[convexPieces][odeBackend][bulletBackend]") {
    // Fig. 8's clip1 and clip2 as an earlier Bullet run left them at 0.5 s:
    // 0.37 mm into each other at their bends (Bullet's GJK, with tolerances
    // made for metre-sized shapes, had reported their bend pieces as apart;
    // the backend now collides hulls by the separating-axis test). From this
    // state, pressed together, both backends push them apart; GJK did too,
    // so this checks the recovery, not that miss, which needs the pieces'
    // configurations of the run (docs/rigid-bodies.md#bullet).
    const std::string engine = GENERATE(std::string("ODE"), std::string("Bullet"));
    INFO(engine);
    magtest::TempCase c;
    auto shape = loadClip(c, 0.001);
    std::vector<mag::Body> bodies(2);
    for (int k = 0; k < 2; ++k) {
        bodies[k].name = "clip" + std::to_string(k + 1);
        bodies[k].shape = shape;
        bodies[k].material.density = 7850;
    }
    bodies[0].position = Vec3(0.040472472032279806, 0.00027325086934647957, 0.007869792125203615);
    bodies[0].orientation = mag::Quat(0.5570711867410403, -0.8175749483984918, -0.051620352733610625, -0.13630200232494855);
    bodies[1].position = Vec3(0.04052942545100177, -0.0015161623052730236, 0.00748932318036504);
    bodies[1].orientation = mag::Quat(0.8189286846493112, 0.5575916661308121, -0.10516051969228188, 0.08595701494388527);
    for (auto& b : bodies) b.orientation.normalize();
    auto depth = [&] {
        double d = 0;
        for (const auto& o : mag::findOverlaps(bodies)) d = std::max(d, o.depth);
        return d;
    };
    const double before = depth();
    auto rb = backendtest::backend("type: " + engine + "\ngravity: [0, 0, 0]\n");
    rb->setup(bodies);
    // Pressed together as their magnetization pulls them (0.05 N, ten times
    // a clip's weight), for 0.2 s.
    const Vec3 pull = 0.05 * (bodies[1].position - bodies[0].position).normalized();
    std::vector<mag::Wrench> w(2);
    w[0].force = pull, w[1].force = -pull;
    double deepest = 0;
    for (int n = 0; n < 2000; ++n) {
        rb->step(bodies, w, 1e-4);
        if (n >= 100) deepest = std::max(deepest, depth());
    }
    const double after = depth();
    INFO("deepest overlap " << before << " m at the start, " << after << " m at the end, " << deepest
                            << " m at most after 10 ms\n" << rb->describe());
    CHECK(before > 1.5e-4);
    // Out to the contact layers (ODE 1 um, Bullet's 10 um margins).
    CHECK(after < 2e-5);
}

TEST_CASE("ODE: a piece touching a box exactly, where libccd gives no contact normal, is stepped", "[convexPieces][odeBackend][app]") {
    // Fig. 8's clip6 standing on edge against the bar magnet's side face, as a
    // run left it (poses to the last bit; meshes and pieces by magMakeGeometry
    // as in the case): one of its convex pieces touches the magnet's box at a
    // depth of 4e-17 m, and ODE's convex-box collider (libccd) returns that
    // contact with a zero normal. A contact row without a direction made the
    // LCP's solution NaN, and magFoam stopped in the first step ("ODE error 1:
    // ... dxNormalize4", ODE's quaternion normalization). The backend drops
    // such contacts (counted as dropped): there is no direction to push along.
    magtest::TempCase c;
    c.write("system/geometryDict.yaml",
            "parts:\n"
            "  - {name: paperclip, type: paperclip, length: 0.033, width: 0.008, wire: 0.0009, segments: 6, bendSegments: 6}\n"
            "  - {name: barMagnet, type: barMagnet, size: [0.05, 0.01, 0.01]}\n");
    c.write("system/controlDict.yaml", "endTime: 0.001\ndeltaT: 5e-5\nwriteInterval: 0.001\n");
    c.write("system/magSchemes.yaml",
            "field: {type: hybrid, near: {type: MBM, quadrature: {type: regular, n: 1}, overlap: exterior}}\n"
            "induction: {type: LLG}\n");
    c.write("constant/materials.yaml", "N42: {model: permanent, Br: 1.3, density: 7500}\n"
                                       "steel: {model: soft, k: 5, Js: 1.8, density: 7850}\n");
    c.write("constant/rigidBody.yaml", "type: ODE\ngravity: [0, 0, -9.81]\nground: {}\n"
                                       "contact: {friction: 0.4, restitution: 0.1}\ncollisionShapes: auto\n");
    c.write("constant/bodies.yaml",
            "bodies:\n"
            "  - {name: magnet, geometry: {file: geometry/barMagnet.stl}, material: N42, magnetization: [1, 0, 0],\n"
            "     position: [0, 0, 0.005], motion: fixed}\n"
            "  - name: clip6\n"
            "    geometry: {file: geometry/paperclip.stl}\n"
            "    material: steel\n"
            "    position: [-2.4992303223459519e-05, -0.0054496102833035557, 0.0045153542581373041]\n"
            "    orientation: {quaternion: [0.70703683580078247, -0.70714208854038008, -0.0049503664021277021, "
            "-0.0049470504395638147]}\n");
    REQUIRE(magtest::runApp(c.dir(), "magMakeGeometry") == 0);
    const int rc = magtest::runApp(c.dir(), "magFoam");
    const std::string log = magtest::slurp(c.path("log"));
    INFO(log);
    REQUIRE(rc == 0);
    // The clip stays on the magnet's face (20 steps; the field pulls it there).
    CHECK_THAT(log, Contains("20 steps") && !Contains("dropped 0,"));
    CHECK_THAT(log, !Contains("Warning: step")); // no audit warning (the start overlaps by ODE's 1 um layer)
}
