// Surface meshes: primitives, topology checks, mass properties, file I/O.
// References are independent of the code under test: closed forms (box, sphere,
// cylinder, ellipsoid, the simplex second-moment formula), Tonon's published
// tetrahedron, and observed convergence orders.
#include "expectError.hpp"

#include <catch2/catch.hpp>

#include <magFoam/Error.hpp>
#include <magFoam/MassProperties.hpp>
#include <magFoam/MeshIO.hpp>
#include <magFoam/MeshPrimitives.hpp>
#include <magFoam/MeshTopology.hpp>
#include <magFoam/SurfaceMesh.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

using namespace mag;
namespace fs = std::filesystem;

namespace {

// A file under the temp directory with a unique name, removed on destruction.
struct TempFile {
    fs::path path;
    explicit TempFile(const std::string& extension) {
        static std::atomic<int> counter{0};
        std::random_device rd;
        path = fs::temp_directory_path() /
               ("magFoam_test_mesh_" + std::to_string(rd()) + "_" + std::to_string(counter++) +
                extension);
    }
    TempFile(const TempFile&) = delete;
    TempFile& operator=(const TempFile&) = delete;
    ~TempFile() {
        std::error_code ec;
        fs::remove(path, ec);
    }
    void write(const std::string& text) const { std::ofstream(path) << text; }
};

// Largest |A_ij - B_ij| relative to the largest |B_ij|.
double relativeDifference(const Mat3& A, const Mat3& B) {
    return (A - B).cwiseAbs().maxCoeff() / B.cwiseAbs().maxCoeff();
}

// Tetrahedron with outward triangles whatever the order of the corners.
SurfaceMesh makeTetrahedron(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
    SurfaceMesh mesh;
    mesh.source = "tetrahedron";
    mesh.vertices = {a, b, c, d};
    mesh.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    if ((b - a).dot((c - a).cross(d - a)) < 0.0) flipOrientation(mesh);
    return mesh;
}

using magtest::contains;
using magtest::inputErrorOf;

// Observed order of convergence from errors at two resolutions h1 > h2.
double observedOrder(double error1, double error2, double h1, double h2) {
    return std::log(error1 / error2) / std::log(h1 / h2);
}

} // namespace

// ---------------------------------------------------------------------------
// Mass properties against closed forms

TEST_CASE("box mass properties are exact", "[mesh][mass]") {
    const double rho = 7500.0;
    // Also far from the origin: the result must not depend on where the box sits.
    const Vec3 offset = GENERATE(Vec3(0, 0, 0), Vec3(0.5, -0.3, 0.2), Vec3(1e3, 2e3, -3e3));
    SurfaceMesh box = makeBox({0.01, 0.02, 0.03});
    translate(box, offset);
    // The reference is the box the vertices actually describe (translation rounds
    // the corners; the differences below are exact by Sterbenz's lemma).
    const BoundingBox bb = boundingBox(box);
    const double a = bb.size().x(), b = bb.size().y(), c = bb.size().z();
    const MassProperties mp = computeMassProperties(box, rho);

    const double V = a * b * c;
    const double m = rho * V;
    const Mat3 expected = Vec3(m / 12 * (b * b + c * c), m / 12 * (a * a + c * c),
                               m / 12 * (a * a + b * b)).asDiagonal();
    CHECK(std::abs(mp.volume - V) <= 1e-12 * V);
    CHECK(std::abs(mp.mass - m) <= 1e-12 * m);
    CHECK((mp.centreOfMass - bb.centre()).norm() <= 1e-12 * std::max(1.0, offset.norm()));
    CHECK(relativeDifference(mp.inertia, expected) <= 1e-12);
    // Ascending: the smallest moment is about the longest (z) side.
    CHECK(std::abs(mp.principalMoments[0] - m / 12 * (a * a + b * b)) <= 1e-12 * m * c * c);
    CHECK(std::abs(mp.principalMoments[2] - m / 12 * (b * b + c * c)) <= 1e-12 * m * c * c);
    CHECK(std::abs(mp.principalAxes.determinant() - 1.0) <= 1e-12);
    CHECK(std::abs(mp.boundingRadius - 0.5 * std::sqrt(a * a + b * b + c * c)) <= 1e-12 * c);
}

TEST_CASE("tetrahedron inertia matches the simplex formula and Tonon (2004)", "[mesh][mass]") {
    // Tonon, J. Math. Stat. 1 (2004) 8-11, worked example (density 1).
    const Vec3 p[4] = {{8.33220, -11.86875, 0.93355},
                       {0.75523, 5.00000, 16.37072},
                       {52.61236, 5.00000, -5.38580},
                       {2.00000, 5.00000, 3.00000}};
    const SurfaceMesh tet = makeTetrahedron(p[0], p[1], p[2], p[3]);
    const MassProperties mp = computeMassProperties(tet);

    // Independent closed form: integral of x x^T over a simplex =
    // V/20 (sum v v^T + s s^T), s = sum v; centroid = s/4.
    const double V = std::abs((p[1] - p[0]).dot((p[2] - p[0]).cross(p[3] - p[0]))) / 6.0;
    Vec3 s = Vec3::Zero();
    Mat3 sum = Mat3::Zero();
    for (const Vec3& v : p) {
        s += v;
        sum += v * v.transpose();
    }
    const Vec3 g = s / 4.0;
    const Mat3 S = V / 20.0 * (sum + s * s.transpose()) - V * g * g.transpose();
    const Mat3 expected = S.trace() * Mat3::Identity() - S;
    CHECK(std::abs(mp.volume - V) <= 1e-12 * V);
    CHECK((mp.centreOfMass - g).norm() <= 1e-12 * g.norm());
    CHECK(relativeDifference(mp.inertia, expected) <= 1e-12);

    // Tonon's printed values (5 decimals, agree to ~2e-8): a, b, c on the
    // diagonal, products of inertia a' (yz), b' (xz), c' (xy) with a minus sign.
    Mat3 tonon;
    tonon << 43520.33257, -11996.20119, 46343.16662,  //
        -11996.20119, 194711.28938, -4417.66150,      //
        46343.16662, -4417.66150, 191168.76173;
    CHECK(relativeDifference(mp.inertia, tonon) <= 1e-7);
}

TEST_CASE("rotated and translated mesh gives R I R^T and the moved centre", "[mesh][mass]") {
    SurfaceMesh mesh = makeTetrahedron({0.01, 0, 0.002}, {0, 0.02, 0}, {-0.003, 0.001, 0.015},
                                       {0.004, -0.005, -0.001});
    append(mesh, [] {  // a second, disjoint shell makes the shape less special
        SurfaceMesh box = makeBox({0.004, 0.006, 0.01});
        translate(box, {0.03, 0.01, -0.02});
        return box;
    }());
    const MassProperties before = computeMassProperties(mesh, 2.5);

    const Mat3 R = Eigen::AngleAxisd(0.7, Vec3(1, 2, -0.5).normalized()).toRotationMatrix();
    const Vec3 t(0.1, -0.25, 0.05);
    rotate(mesh, R);
    translate(mesh, t);
    const MassProperties after = computeMassProperties(mesh, 2.5);

    CHECK(std::abs(after.volume - before.volume) <= 1e-12 * before.volume);
    CHECK((after.centreOfMass - (R * before.centreOfMass + t)).norm() <= 1e-12 * t.norm());
    CHECK(relativeDifference(after.inertia, R * before.inertia * R.transpose()) <= 1e-11);
    CHECK((after.principalMoments - before.principalMoments).norm() <=
          1e-11 * before.principalMoments.norm());
    CHECK(std::abs(after.boundingRadius - before.boundingRadius) <= 1e-12);

    // Principal axes diagonalise the tensor.
    const Mat3 D = after.principalAxes.transpose() * after.inertia * after.principalAxes;
    CHECK(relativeDifference(D, Mat3(after.principalMoments.asDiagonal())) <= 1e-11);

    // A reflection keeps the mesh outward (transform reverses the triangles).
    transform(mesh, Vec3(-1, 1, 1).asDiagonal(), Vec3::Zero());
    CHECK(checkTopology(mesh).usable());
    CHECK(std::abs(computeMassProperties(mesh, 2.5).volume - before.volume) <=
          1e-12 * before.volume);
}

TEST_CASE("icosphere volume and inertia converge with order 2", "[mesh][mass][convergence]") {
    const double r = 0.01;
    const double volume = 4.0 / 3.0 * pi * r * r * r;
    const double moment = 2.0 / 5.0 * volume * r * r;
    std::vector<double> volumeError, momentError;
    for (int n = 2; n <= 5; ++n) {
        const SurfaceMesh sphere = makeIcosphere(r, n);
        REQUIRE(sphere.nTriangles() == 20 * (1 << (2 * n)));
        REQUIRE(checkTopology(sphere).usable());
        for (const Vec3& v : sphere.vertices) REQUIRE(std::abs(v.norm() - r) <= 1e-15);
        const MassProperties mp = computeMassProperties(sphere);
        volumeError.push_back(volume - mp.volume);  // inscribed: from below
        momentError.push_back(moment - mp.principalMoments[0]);
        CHECK(mp.centreOfMass.norm() <= 1e-15 * r);
        CHECK(mp.boundingRadius == Approx(r).epsilon(1e-14));
    }
    // Edge length halves per level, so order = log2(error ratio).
    for (std::size_t i = 0; i + 1 < volumeError.size(); ++i) {
        const double pv = observedOrder(volumeError[i], volumeError[i + 1], 2.0, 1.0);
        const double pi_ = observedOrder(momentError[i], momentError[i + 1], 2.0, 1.0);
        UNSCOPED_INFO("icosphere level " << i + 2 << "->" << i + 3 << ": volume order " << pv
                                         << ", inertia order " << pi_);
        CHECK(pv == Approx(2.0).margin(0.05));
        CHECK(pi_ == Approx(2.0).margin(0.05));
    }
    CHECK(volumeError.back() / volume < 2e-3);
}

TEST_CASE("cylinder volume and inertia converge with order 2", "[mesh][mass][convergence]") {
    const double r = 0.005, h = 0.02;
    const double volume = pi * r * r * h;
    const double axial = 0.5 * volume * r * r;
    const double transverse = volume * (3 * r * r + h * h) / 12.0;
    std::vector<double> segments, volumeError, axialError, transverseError;
    for (int n : {16, 32, 64, 128}) {
        const SurfaceMesh cylinder = makeCylinder(r, h, n);
        REQUIRE(cylinder.nTriangles() == 4 * n);
        REQUIRE(checkTopology(cylinder).usable());
        const MassProperties mp = computeMassProperties(cylinder);
        // The prism's own volume is known exactly: n/2 r^2 sin(2 pi/n) h.
        CHECK(mp.volume == Approx(0.5 * n * r * r * std::sin(2 * pi / n) * h).epsilon(1e-13));
        CHECK(mp.centreOfMass.norm() <= 1e-15);
        segments.push_back(n);
        volumeError.push_back(volume - mp.volume);
        axialError.push_back(std::abs(axial - mp.inertia(2, 2)));
        transverseError.push_back(std::abs(transverse - mp.inertia(0, 0)));
    }
    for (std::size_t i = 0; i + 1 < segments.size(); ++i) {
        const double h1 = 1.0 / segments[i], h2 = 1.0 / segments[i + 1];
        const double pv = observedOrder(volumeError[i], volumeError[i + 1], h1, h2);
        const double pa = observedOrder(axialError[i], axialError[i + 1], h1, h2);
        const double pt = observedOrder(transverseError[i], transverseError[i + 1], h1, h2);
        UNSCOPED_INFO("cylinder " << segments[i] << "->" << segments[i + 1] << ": volume order "
                                  << pv << ", Izz order " << pa << ", Ixx order " << pt);
        CHECK(pv == Approx(2.0).margin(0.05));
        CHECK(pa == Approx(2.0).margin(0.05));
        CHECK(pt == Approx(2.0).margin(0.05));
    }
}

TEST_CASE("ellipsoid volume and inertia converge with order 2", "[mesh][mass][convergence]") {
    const Vec3 s(0.01, 0.02, 0.005);
    const double volume = 4.0 / 3.0 * pi * s.prod();
    const Vec3 moments(volume / 5 * (s.y() * s.y() + s.z() * s.z()),
                       volume / 5 * (s.x() * s.x() + s.z() * s.z()),
                       volume / 5 * (s.x() * s.x() + s.y() * s.y()));
    std::vector<double> volumeError, inertiaError;
    for (int n = 3; n <= 5; ++n) {
        const MassProperties mp = computeMassProperties(makeEllipsoid(s, n));
        volumeError.push_back(volume - mp.volume);
        inertiaError.push_back((mp.inertia.diagonal() - moments).norm());
        CHECK(mp.inertia(0, 1) == Approx(0).margin(1e-15 * moments.norm()));
    }
    for (std::size_t i = 0; i + 1 < volumeError.size(); ++i) {
        const double pv = observedOrder(volumeError[i], volumeError[i + 1], 2.0, 1.0);
        const double pi_ = observedOrder(inertiaError[i], inertiaError[i + 1], 2.0, 1.0);
        UNSCOPED_INFO("ellipsoid level " << i + 3 << "->" << i + 4 << ": volume order " << pv
                                         << ", inertia order " << pi_);
        CHECK(pv == Approx(2.0).margin(0.05));
        CHECK(pi_ == Approx(2.0).margin(0.05));
    }
}

TEST_CASE("recentre moves the centre of mass to the origin", "[mesh][mass]") {
    SurfaceMesh mesh = makeTetrahedron({0, 0, 0}, {0.03, 0, 0}, {0, 0.02, 0}, {0, 0, 0.01});
    translate(mesh, {1.0, -2.0, 0.5});
    const Vec3 expectedCentre = Vec3(0.03, 0.02, 0.01) / 4.0 + Vec3(1.0, -2.0, 0.5);
    const Mat3 inertia = computeMassProperties(mesh).inertia;

    const Vec3 old = recentre(mesh);
    CHECK((old - expectedCentre).norm() <= 1e-15 * expectedCentre.norm() * 10);
    const MassProperties mp = computeMassProperties(mesh);
    CHECK(mp.centreOfMass.norm() <= 1e-15);
    CHECK(relativeDifference(mp.inertia, inertia) <= 1e-10);
}

TEST_CASE("bounding sphere radius and inertia about a point", "[mesh][mass]") {
    const SurfaceMesh box = makeBox({0.02, 0.04, 0.04});
    const MassProperties mp = computeMassProperties(box);
    CHECK(mp.boundingRadius == Approx(0.03).epsilon(1e-14));
    CHECK(boundingSphereRadius(box, {0.01, 0.02, 0.02}) == Approx(0.06).epsilon(1e-14));

    // Parallel axis theorem: about a corner, Izz = m (a^2 + b^2) / 3.
    const Mat3 I = inertiaAbout(mp, {0.01, 0.02, 0.02});
    CHECK(I(2, 2) == Approx(mp.mass * (0.02 * 0.02 + 0.04 * 0.04) / 3).epsilon(1e-13));
}

// ---------------------------------------------------------------------------
// Primitives and clean-up

TEST_CASE("primitives are closed and outward with the documented counts", "[mesh][primitives]") {
    const SurfaceMesh box = makeBox({1, 2, 3});
    CHECK(box.nTriangles() == 12);
    CHECK(box.nVertices() == 8);
    for (int t = 0; t < box.nTriangles(); ++t) {
        // Each normal is an axis and points away from the centre.
        const Vec3 n = box.normal(t);
        CHECK(n.cwiseAbs().maxCoeff() == Approx(1.0));
        CHECK(n.dot(box.centroid(t)) > 0.0);
    }
    const auto report = checkTopology(box);
    CHECK(report.usable());
    CHECK(report.edgeTable.edges.size() == 18);
    CHECK(report.eulerCharacteristic == 2);
    CHECK(report.shells == 1);
    for (const MeshEdge& e : report.edgeTable.edges) {
        CHECK(e.faceCount == 2);
        CHECK(e.direction[0] == -e.direction[1]);
    }

    const SurfaceMesh cylinder = makeCylinder(1, 2, 12);
    CHECK(cylinder.nVertices() == 26);
    CHECK(checkTopology(cylinder).usable());
    CHECK(makeIcosphere(1, 0).nVertices() == 12);
    CHECK(makeIcosphere(1, 3).nVertices() == 10 * 64 + 2);
    CHECK(checkTopology(makeEllipsoid({1, 2, 3}, 2)).usable());
    CHECK(surfaceArea(box) == Approx(2 * (2 + 6 + 3)));

    const BoundingBox bb = boundingBox(cylinder);
    CHECK((bb.lower - Vec3(-1, -1, -1)).norm() <= 1e-15);
    CHECK((bb.upper - Vec3(1, 1, 1)).norm() <= 1e-15);
}

TEST_CASE("primitives reject bad sizes", "[mesh][primitives][bad]") {
    CHECK(contains(inputErrorOf([] { makeBox({1, -1, 1}); }), "size y"));
    CHECK(contains(inputErrorOf([] { makeIcosphere(1, 9); }), "subdivisions = 9"));
    CHECK(contains(inputErrorOf([] { makeIcosphere(0, 2); }), "radius"));
    CHECK(contains(inputErrorOf([] { makeCylinder(1, 1, 2); }), "segments"));
    CHECK(contains(inputErrorOf([] { makeCylinder(1, NAN, 8); }), "height"));
}

TEST_CASE("weld merges duplicate vertices within the tolerance only", "[mesh][weld]") {
    // Triangle soup as STL stores it: every triangle has its own corners.
    const SurfaceMesh box = makeBox({0.01, 0.02, 0.03});
    SurfaceMesh soup;
    soup.source = "soup";
    for (int t = 0; t < box.nTriangles(); ++t) {
        for (int k = 0; k < 3; ++k) soup.vertices.push_back(box.corner(t, k));
        soup.triangles.push_back({3 * t, 3 * t + 1, 3 * t + 2});
    }
    // Noise far below the tolerance (1e-9 of the diagonal) must not matter.
    soup.vertices[5] += Vec3(1e-13, -1e-13, 0);
    CHECK_FALSE(checkTopology(soup).closed());

    CHECK(weldVertices(soup) == 36 - 8);
    CHECK(soup.nVertices() == 8);
    CHECK(checkTopology(soup).usable());
    // 1e-10, not exact: the kept corner may be the one moved by 1e-13.
    CHECK(computeMassProperties(soup).volume == Approx(6e-6).epsilon(1e-10));

    // Points a visible distance apart stay apart.
    SurfaceMesh two;
    two.source = "two";
    two.vertices = {{0, 0, 0}, {1e-6, 0, 0}, {1, 1, 1}};
    two.triangles = {{0, 1, 2}};
    CHECK(weldVertices(two) == 0);
    two.vertices[1] = {1e-10, 0, 0};
    CHECK(weldVertices(two) == 1);
    CHECK(two.triangles[0] == std::array<int, 3>{0, 0, 1});
    CHECK(dropCollapsedTriangles(two) == std::vector<int>{0});
    CHECK(removeUnusedVertices(two) == 2);
    CHECK(two.nVertices() == 0);
}

// ---------------------------------------------------------------------------
// Bad meshes: each must be refused with the file and the element named

TEST_CASE("open mesh is refused naming an edge", "[mesh][bad]") {
    SurfaceMesh box = makeBox({1, 1, 1});
    box.source = "open.stl";
    box.triangles.erase(box.triangles.begin());
    const auto report = checkTopology(box);
    CHECK_FALSE(report.closed());
    CHECK(report.boundaryEdges.size() == 3);
    const std::string message = inputErrorOf([&] { requireUsable(box); });
    CHECK(contains(message, "open.stl"));
    CHECK(contains(message, "open"));
    CHECK(contains(message, "edge between vertex"));
    CHECK(contains(message, "only triangle"));
}

TEST_CASE("inside-out mesh is refused as inverted", "[mesh][bad]") {
    SurfaceMesh sphere = makeIcosphere(0.01, 2);
    flipOrientation(sphere);
    const auto report = checkTopology(sphere);
    CHECK(report.closed());
    CHECK(report.consistentlyOriented());
    CHECK(report.inverted());
    CHECK_FALSE(report.usable());
    const std::string message = inputErrorOf([&] { requireUsable(sphere); });
    CHECK(contains(message, "icosphere"));
    CHECK(contains(message, "inverted"));
    CHECK(contains(message, "inward"));
    CHECK(contains(message, "triangle 0"));
    // Mass properties refuse it too rather than return negative inertia.
    CHECK(contains(inputErrorOf([&] { computeMassProperties(sphere); }), "volume"));
}

TEST_CASE("edge with three triangles is refused as non-manifold", "[mesh][bad]") {
    SurfaceMesh box = makeBox({1, 1, 1});
    box.source = "fin.obj";
    // A fin on the edge between vertices 0 and 4.
    box.vertices.emplace_back(-1.5, -1.5, 0);
    box.triangles.push_back({0, 4, 8});
    const auto report = checkTopology(box);
    REQUIRE(report.nonManifoldEdges.size() == 1);
    const MeshEdge& edge = report.edgeTable.edges[report.nonManifoldEdges[0]];
    CHECK(edge.vertices == std::array<int, 2>{0, 4});
    CHECK(edge.faceCount == 3);
    const std::string message = inputErrorOf([&] { requireUsable(box); });
    CHECK(contains(message, "fin.obj"));
    CHECK(contains(message, "not manifold"));
    CHECK(contains(message, "vertex 0 at"));
    CHECK(contains(message, "vertex 4 at"));
    CHECK(contains(message, "triangles 0, 5, 12"));
}

TEST_CASE("solids touching at one vertex are refused as non-manifold", "[mesh][bad]") {
    SurfaceMesh mesh = makeTetrahedron({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1});
    append(mesh, makeTetrahedron({0, 0, 0}, {-1, 0, 0}, {0, -1, 0}, {0, 0, -1}));
    weldVertices(mesh);  // the two origins become one vertex
    const auto report = checkTopology(mesh);
    CHECK(report.closed());
    CHECK(report.nonManifoldVertices == std::vector<int>{0});
    const std::string message = inputErrorOf([&] { requireUsable(mesh); });
    CHECK(contains(message, "not manifold at 1 vertex"));
    CHECK(contains(message, "vertex 0 at (0, 0, 0)"));
}

TEST_CASE("one reversed triangle is refused as inconsistently oriented", "[mesh][bad]") {
    SurfaceMesh box = makeBox({1, 1, 1});
    std::swap(box.triangles[3][1], box.triangles[3][2]);
    const auto report = checkTopology(box);
    CHECK(report.inconsistentEdges.size() == 3);
    const std::string message = inputErrorOf([&] { requireUsable(box); });
    CHECK(contains(message, "not consistently oriented"));
    CHECK(contains(message, "edge between vertex"));
}

TEST_CASE("flat closed mesh is refused for zero volume", "[mesh][bad]") {
    // A tetrahedron squashed into the plane z = 0: closed, oriented, no volume.
    SurfaceMesh flat = makeTetrahedron({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 1});
    flat.vertices[3].z() = 0.0;
    const auto report = checkTopology(flat);
    CHECK(report.closed());
    CHECK(report.manifold());
    CHECK(report.degenerateTriangles.empty());
    CHECK(report.zeroVolume());
    CHECK(contains(inputErrorOf([&] { requireUsable(flat); }), "zero volume"));
}

TEST_CASE("degenerate triangle is reported and can be dropped", "[mesh][bad]") {
    // A T-junction closed by a needle: edge 0-4 of the box is split at its
    // midpoint for one neighbour, and triangle (0, 4, m) of zero area closes it.
    SurfaceMesh box = makeBox({1, 1, 1});
    box.source = "needle.stl";
    const int m = box.nVertices();
    box.vertices.push_back(0.5 * (box.vertices[0] + box.vertices[4]));
    box.triangles[0] = {0, m, 6};  // was {0, 4, 6}
    box.triangles.push_back({m, 4, 6});
    box.triangles.push_back({0, 4, m});  // traverses 0->4 and closes the gap
    const int needle = box.nTriangles() - 1;

    const auto report = checkTopology(box);
    CHECK(report.closed());
    CHECK(report.degenerateTriangles == std::vector<int>{needle});
    const std::string message = inputErrorOf([&] { requireUsable(box); });
    CHECK(contains(message, "needle.stl"));
    CHECK(contains(message, "degenerate"));
    CHECK(contains(message, "triangle " + std::to_string(needle) + " (vertices 0, 4, 8"));

    CHECK(findDegenerateTriangles(box) == std::vector<int>{needle});
    CHECK(dropDegenerateTriangles(box) == std::vector<int>{needle});
    CHECK(box.nTriangles() == needle);
    CHECK_FALSE(checkTopology(box).closed());  // dropping a needle opens the mesh
}

TEST_CASE("out-of-range indices and NaN coordinates and empty meshes are refused", "[mesh][bad]") {
    SurfaceMesh box = makeBox({1, 1, 1});
    box.triangles[7][2] = 99;
    CHECK(contains(inputErrorOf([&] { requireUsable(box); }), "triangle 7"));
    CHECK(contains(inputErrorOf([&] { weldVertices(box); }), "vertex 99"));

    SurfaceMesh nan = makeBox({1, 1, 1});
    nan.vertices[3].x() = NAN;
    CHECK(contains(inputErrorOf([&] { requireUsable(nan); }), "vertex 3"));

    SurfaceMesh empty;
    empty.source = "empty.obj";
    CHECK(contains(inputErrorOf([&] { requireUsable(empty); }), "empty.obj: mesh has no triangles"));
}

// ---------------------------------------------------------------------------
// Files

TEST_CASE("missing file is an error naming the path", "[mesh][io][bad]") {
    const TempFile file(".stl");  // never written
    CHECK(inputErrorOf([&] { loadSurfaceMesh(file.path); }) == file.path.string() + ": file not found");
}

TEST_CASE("unsupported or unparsable files are errors listing the formats", "[mesh][io][bad]") {
    const TempFile xyz(".xyz");
    xyz.write("0 0 0\n1 0 0\n0 1 0\n");
    const std::string message = inputErrorOf([&] { loadSurfaceMesh(xyz.path); });
    CHECK(contains(message, xyz.path.string()));
    CHECK(contains(message, "unsupported"));
    CHECK(contains(message, ".stl .obj .ply .off"));

    const TempFile garbage(".stl");
    garbage.write("this is not an STL file\n");
    const std::string garbageMessage = inputErrorOf([&] { loadSurfaceMesh(garbage.path); });
    CHECK(contains(garbageMessage, garbage.path.string()));
    CHECK(contains(garbageMessage, ".stl .obj .ply .off"));

    const TempFile noFaces(".obj");
    noFaces.write("v 0 0 0\nv 1 0 0\nv 0 1 0\n");
    CHECK(contains(inputErrorOf([&] { loadSurfaceMesh(noFaces.path); }), noFaces.path.string()));

    CHECK(contains(inputErrorOf([&] { writeSurfaceMesh(makeBox({1, 1, 1}), xyz.path); }), ".xyz"));
    CHECK(contains(inputErrorOf([&] { loadSurfaceMesh(xyz.path, {.scale = -1.0}); }), "scale"));
}

TEST_CASE("binary STL round trip keeps the mass properties", "[mesh][io]") {
    const SurfaceMesh cylinder = makeCylinder(0.005, 0.02, 48);
    const TempFile file(".stl");
    writeStlBinary(cylinder, file.path);
    CHECK(fs::file_size(file.path) == 84 + 50 * cylinder.triangles.size());

    MeshLoadReport report;
    const SurfaceMesh loaded = loadSurfaceMesh(file.path, {}, &report);
    CHECK(loaded.source == file.path.string());
    CHECK(loaded.nTriangles() == cylinder.nTriangles());
    CHECK(loaded.nVertices() == cylinder.nVertices());  // welded back to shared vertices
    CHECK(report.format == ".stl");
    CHECK(report.collapsedTrianglesRemoved == 0);
    REQUIRE_NOTHROW(requireUsable(loaded));

    // STL stores floats: agreement to single precision.
    const MassProperties a = computeMassProperties(cylinder);
    const MassProperties b = computeMassProperties(loaded);
    CHECK(b.volume == Approx(a.volume).epsilon(1e-6));
    CHECK((b.centreOfMass - a.centreOfMass).norm() <= 1e-9);
    CHECK(relativeDifference(b.inertia, a.inertia) <= 1e-6);
}

TEST_CASE("a thin fine rod reloads from STL and OBJ as it was written (no vertices merged)", "[mesh][io]") {
    // Rim vertices 3 um apart on a part 0.1 m long: a joining tolerance that
    // scales with the part (assimp's, ~1e-4 of the box) merges them; the weld's
    // 1e-9 of the box does not.
    const SurfaceMesh rod = makeCylinder(0.0005, 0.1, 1024);
    for (const char* extension : {".stl", ".obj"}) {
        INFO(extension);
        const TempFile file(extension);
        if (std::string(extension) == ".stl")
            writeStlBinary(rod, file.path);
        else
            writeObj(rod, file.path);
        const SurfaceMesh loaded = loadSurfaceMesh(file.path);
        CHECK(loaded.nVertices() == rod.nVertices());
        CHECK(loaded.nTriangles() == rod.nTriangles());
        CHECK_NOTHROW(requireUsable(loaded));
    }
}

TEST_CASE("OBJ round trip keeps the mesh and scale applies", "[mesh][io]") {
    const SurfaceMesh sphere = makeIcosphere(10.0, 2);  // "millimetres"
    const TempFile file(".obj");
    writeObj(sphere, file.path);

    const SurfaceMesh loaded = loadSurfaceMesh(file.path);
    REQUIRE(loaded.nVertices() == sphere.nVertices());
    REQUIRE(loaded.nTriangles() == sphere.nTriangles());
    // The file holds 17 digits, but assimp (ai_real = float in Debian's build)
    // reads single precision.
    const MassProperties a = computeMassProperties(sphere);
    CHECK(computeMassProperties(loaded).volume == Approx(a.volume).epsilon(1e-6));
    // assimp renumbers vertices: each original one must have a loaded twin.
    for (const Vec3& p : sphere.vertices) {
        double nearest = 1e300;
        for (const Vec3& q : loaded.vertices) nearest = std::min(nearest, (p - q).norm());
        CHECK(nearest <= 1e-6 * 10.0);
    }

    const SurfaceMesh metres = loadSurfaceMesh(file.path, {.scale = 0.001});
    CHECK(computeMassProperties(metres).volume == Approx(a.volume * 1e-9).epsilon(1e-6));
}

TEST_CASE("hand-written ASCII STL and OBJ with quads and PLY and OFF load", "[mesh][io]") {
    // Unit cube written with quads (OBJ, OFF) must be triangulated to 12 triangles.
    const std::string cubeVertices = "0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n";
    const std::array<std::array<int, 4>, 6> quads{{{0, 3, 2, 1},
                                                   {4, 5, 6, 7},
                                                   {0, 1, 5, 4},
                                                   {2, 3, 7, 6},
                                                   {1, 2, 6, 5},
                                                   {0, 4, 7, 3}}};

    SECTION("OBJ") {
        std::string text = "# cube\n";
        std::istringstream vs(cubeVertices);
        for (std::string line; std::getline(vs, line);) text += "v " + line + "\n";
        for (const auto& q : quads)
            text += "f " + std::to_string(q[0] + 1) + " " + std::to_string(q[1] + 1) + " " +
                    std::to_string(q[2] + 1) + " " + std::to_string(q[3] + 1) + "\n";
        const TempFile file(".obj");
        file.write(text);
        const SurfaceMesh cube = loadSurfaceMesh(file.path);
        CHECK(cube.nTriangles() == 12);
        CHECK(cube.nVertices() == 8);
        REQUIRE_NOTHROW(requireUsable(cube));
        CHECK(computeMassProperties(cube).volume == Approx(1.0).epsilon(1e-14));
        CHECK((computeMassProperties(cube).centreOfMass - Vec3(0.5, 0.5, 0.5)).norm() <= 1e-15);
    }
    SECTION("OFF") {
        std::string text = "OFF\n8 6 0\n" + cubeVertices;
        for (const auto& q : quads)
            text += "4 " + std::to_string(q[0]) + " " + std::to_string(q[1]) + " " +
                    std::to_string(q[2]) + " " + std::to_string(q[3]) + "\n";
        const TempFile file(".off");
        file.write(text);
        const SurfaceMesh cube = loadSurfaceMesh(file.path);
        CHECK(cube.nTriangles() == 12);
        REQUIRE_NOTHROW(requireUsable(cube));
        CHECK(computeMassProperties(cube).volume == Approx(1.0).epsilon(1e-14));
    }
    SECTION("PLY (ASCII)") {
        // Tetrahedron (0,0,0), (2,0,0), (0,3,0), (0,0,4): volume 4.
        const TempFile file(".ply");
        file.write("ply\nformat ascii 1.0\ncomment magFoam test\n"
                   "element vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
                   "element face 4\nproperty list uchar int vertex_indices\nend_header\n"
                   "0 0 0\n2 0 0\n0 3 0\n0 0 4\n"
                   "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n");
        const SurfaceMesh tet = loadSurfaceMesh(file.path);
        CHECK(tet.nTriangles() == 4);
        CHECK(tet.nVertices() == 4);
        REQUIRE_NOTHROW(requireUsable(tet));
        CHECK(computeMassProperties(tet).volume == Approx(4.0).epsilon(1e-14));
    }
    SECTION("ASCII STL") {
        // Same tetrahedron, each facet with its own corners (welded on load).
        const Vec3 p[4] = {{0, 0, 0}, {2, 0, 0}, {0, 3, 0}, {0, 0, 4}};
        const int faces[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
        std::string text = "solid tet\n";
        for (const auto& f : faces) {
            text += "facet normal 0 0 0\n outer loop\n";
            for (int k : f)
                text += "  vertex " + std::to_string(p[k].x()) + " " + std::to_string(p[k].y()) +
                        " " + std::to_string(p[k].z()) + "\n";
            text += " endloop\nendfacet\n";
        }
        text += "endsolid tet\n";
        const TempFile file(".stl");
        file.write(text);
        MeshLoadReport report;
        const SurfaceMesh tet = loadSurfaceMesh(file.path, {}, &report);
        CHECK(tet.nVertices() == 4);
        CHECK(report.verticesRead - report.verticesMerged == 4);
        REQUIRE_NOTHROW(requireUsable(tet));
        CHECK(computeMassProperties(tet).volume == Approx(4.0).epsilon(1e-14));
    }
}

TEST_CASE("closest point on a triangle: face, edge and vertex regions", "[mesh]") {
    const mag::Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
    // Unit triangle: the barycentric divisions round at ~1e-16.
    auto near = [&](const mag::Vec3& p, const mag::Vec3& expected) {
        return (mag::closestPointOnTriangle(p, a, b, c) - expected).norm() < 1e-15;
    };
    CHECK(near(mag::Vec3(0.2, 0.3, 5), mag::Vec3(0.2, 0.3, 0)));  // face
    CHECK(near(mag::Vec3(0.5, -2, 1), mag::Vec3(0.5, 0, 0)));     // edge ab
    CHECK(near(mag::Vec3(1, 1, 0), mag::Vec3(0.5, 0.5, 0)));      // edge bc
    CHECK(near(mag::Vec3(-1, -1, 0), a));                          // vertex a
    CHECK(near(mag::Vec3(3, -1, 0), b));                           // vertex b
    CHECK(near(mag::Vec3(-1, 4, 2), c));                           // vertex c
}

// ---------------------------------------------------------------------------
// Malformed mesh files (tests/badMeshes): an InputError naming the file and the
// line or element, never a crash, a hang or a mesh with bad indices.

namespace {

fs::path badMesh(const std::string& name) { return fs::path(MAG_SOURCE_DIR) / "tests/badMeshes" / name; }

} // namespace

TEST_CASE("binary PLY with float, double and big-endian coordinates loads", "[mesh][io]") {
    for (const std::string name : {"goodBinaryFloat.ply", "goodBinaryDouble.ply", "goodBinaryBigEndian.ply"}) {
        INFO(name);
        const SurfaceMesh tet = loadSurfaceMesh(badMesh(name));
        CHECK(tet.nTriangles() == 4);
        CHECK(tet.nVertices() == 4);
        REQUIRE_NOTHROW(requireUsable(tet));
        CHECK(computeMassProperties(tet).volume == Approx(4.0).epsilon(1e-14));
    }
}

TEST_CASE("malformed PLY, OFF, STL and OBJ files are errors naming file and element", "[mesh][io][bad]") {
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"faceIndexMinus1.ply", ":17: face 2: vertex index -1 is out of range; the file has 4 vertices"},
        {"faceIndexMinus5.ply", ": face 1 (at byte 257): vertex index -5 is out of range"},
        {"faceIndexHuge.ply", ":18: face 3: vertex index 2147483647 is out of range"},
        // The header says binary, the data is text: its bytes make no sense as numbers.
        {"binaryHeaderAsciiData.ply", ": face 0 (at byte 244): list 'vertex_indices' counts 51 items, but the rest "
                                      "of the file holds at most 1 (truncated, or not binary data)"},
        {"truncatedBinary.ply", ": face 3 (at byte 283): list 'vertex_indices' counts 3 items, but the rest of the "
                                "file holds at most 1 (truncated"},
        {"endHeder.ply", ":10: PLY header: unknown header line 'end_heder'"},
        {"hugeVertexCount.ply", ":4: PLY header: element 'vertex' counts 2000000000 items, more than the 56 bytes"},
        {"infCoordinate.ply", ":14: vertex 3: coordinate z = inf, expected a finite number"},
        {"moreVerticesThanData.off", ":2: the header counts 12 vertices and 6 faces, more than the 109 bytes"},
        {"moreFacesThanData.off", ":2: the header counts 8 vertices and 9 faces, more than the 109 bytes"},
        {"oneFaceMissing.off", ":17: the file ends at face 6; the header counts 7 faces"},
        {"oneFaceMissing.ply", ":17: face 3: the file ends here; the header counts 4 face items"},
        {"faceIndexOutOfRange.off", ":15: face 4: vertex index 8 is out of range; the file has 8 vertices"},
        {"nanCoordinate.stl", ": mesh 0 vertex 2 at (0, nan, 0): expected finite coordinates"},
        {"faceIndexOutOfRange.obj", ":8: face corner '9': vertex index 9 is out of range; 4 vertices are defined "
                                    "before it"},
        // What assimp's OBJ importer leaked memory on (found by fuzzing): a
        // coordinate of bytes that are no number.
        {"garbledCoordinate.obj", ":2: vertex 1: expected 3 numbers x y z, got '0A0'"},
    };
    for (const auto& [name, expected] : cases) {
        INFO(name);
        const std::string message = inputErrorOf([&] { (void)loadSurfaceMesh(badMesh(name)); });
        CHECK(contains(message, badMesh(name).string()));
        CHECK(contains(message, expected));
    }
}

TEST_CASE("mesh files that are not regular files are refused", "[mesh][io][bad]") {
    const TempFile link(".stl");
    fs::create_symlink("/dev/zero", link.path);
    CHECK(contains(inputErrorOf([&] { (void)loadSurfaceMesh(link.path); }),
                   link.path.string() + ": is a character device, expected a regular mesh file"));
}
