// Scene part generators (PartShapes) and the magMakeGeometry front end (GeometryDict).
// References are independent of the code under test: closed-form volumes of the
// polygonal solids and of the smooth ones they converge to (observed order 2),
// the paperclip's analytic wire length, brute-force distances between path
// segments, edge-triangle crossings and winding numbers for (self-)intersection.
#include <catch2/catch.hpp>

#include "GeometryDict.hpp"
#include "PartShapes.hpp"

#include <magFoam/Error.hpp>
#include <magFoam/MassProperties.hpp>
#include <magFoam/MeshIO.hpp>
#include <magFoam/MeshPrimitives.hpp>
#include <magFoam/MeshTopology.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

using namespace mag;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

namespace {

// Regular n-gon inscribed in a circle of radius 1: area / (pi r^2).
double polygonFactor(int n) { return n / (2.0 * pi) * std::sin(2.0 * pi / n); }

double observedOrder(double error1, double error2) { return std::log2(error1 / error2); }

double relative(double value, double reference) { return std::abs(value - reference) / std::abs(reference); }

// The mesh passes every check and has the expected shells and genus.
void checkUsable(const SurfaceMesh& mesh, int shells = 1, int eulerCharacteristic = 2) {
    INFO(mesh.source);
    const TopologyReport report = checkTopology(mesh);
    for (const auto& line : describeProblems(mesh, report)) INFO(line);
    CHECK(report.usable());
    CHECK_NOTHROW(requireUsable(mesh));
    CHECK(report.shells == shells);
    CHECK(report.eulerCharacteristic == eulerCharacteristic);
    for (double v : report.shellVolumes) CHECK(v > 0.0);
}

// Does segment p-q cross (or touch) triangle t? Moller-Trumbore with a small
// tolerance on the inclusive side, so near misses count as hits.
bool segmentHitsTriangle(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c) {
    const double eps = 1e-9;
    const Vec3 d = q - p, e1 = b - a, e2 = c - a;
    const Vec3 h = d.cross(e2);
    const double det = e1.dot(h);
    if (std::abs(det) <= 1e-30) return false;  // parallel: no transversal crossing
    const Vec3 s = p - a;
    const double u = s.dot(h) / det;
    if (u < -eps || u > 1 + eps) return false;
    const Vec3 qv = s.cross(e1);
    const double v = d.dot(qv) / det;
    if (v < -eps || u + v > 1 + eps) return false;
    const double t = e2.dot(qv) / det;
    return t >= -eps && t <= 1 + eps;
}

// Edges of `a` that cross triangles of `b`; with sameMesh, pairs sharing a
// vertex are skipped (they meet by construction).
int edgeTriangleCrossings(const SurfaceMesh& a, const SurfaceMesh& b, bool sameMesh) {
    int crossings = 0;
    for (const MeshEdge& edge : buildEdgeTable(a).edges) {
        const Vec3& p = a.vertices[edge.vertices[0]];
        const Vec3& q = a.vertices[edge.vertices[1]];
        for (const auto& tri : b.triangles) {
            if (sameMesh && std::count_if(tri.begin(), tri.end(), [&](int v) {
                    return v == edge.vertices[0] || v == edge.vertices[1];
                }))
                continue;
            if (segmentHitsTriangle(p, q, b.vertices[tri[0]], b.vertices[tri[1]], b.vertices[tri[2]]))
                ++crossings;
        }
    }
    return crossings;
}

// Two closed meshes are disjoint: no edge of one crosses the other, and no
// vertex of one lies inside the other (one inside the other without crossings;
// core's windingNumber).
bool disjoint(const SurfaceMesh& a, const SurfaceMesh& b) {
    if (edgeTriangleCrossings(a, b, false) > 0 || edgeTriangleCrossings(b, a, false) > 0) return false;
    return std::abs(windingNumber(b, a.vertices[0])) < 0.5 && std::abs(windingNumber(a, b.vertices[0])) < 0.5;
}

// Distance between segments p1-q1 and p2-q2 (Ericson, Real-Time Collision
// Detection, 5.1.9), for non-degenerate segments.
double segmentDistance(const Vec3& p1, const Vec3& q1, const Vec3& p2, const Vec3& q2) {
    const Vec3 d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
    const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
    const double c = d1.dot(r), b = d1.dot(d2), denom = a * e - b * b;
    double s = denom > 1e-30 * a * e ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
    double t = (b * s + f) / e;
    if (t < 0.0) {
        t = 0.0;
        s = std::clamp(-c / a, 0.0, 1.0);
    } else if (t > 1.0) {
        t = 1.0;
        s = std::clamp((b - c) / a, 0.0, 1.0);
    }
    return ((p1 + s * d1) - (p2 + t * d2)).norm();
}

// Smallest distance between path segments that are at least `gap` apart
// along the path (measured between their nearest ends).
double closestDistantSegments(const std::vector<Vec3>& path, double gap) {
    std::vector<double> arc{0.0};
    for (std::size_t i = 1; i < path.size(); ++i) arc.push_back(arc.back() + (path[i] - path[i - 1]).norm());
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i + 1 < path.size(); ++i)
        for (std::size_t j = i + 1; j + 1 < path.size(); ++j)
            if (arc[j] - arc[i + 1] >= gap)
                best = std::min(best, segmentDistance(path[i], path[i + 1], path[j], path[j + 1]));
    return best;
}

double pathLength(const std::vector<Vec3>& path) {
    double length = 0.0;
    for (std::size_t i = 1; i < path.size(); ++i) length += (path[i] - path[i - 1]).norm();
    return length;
}

// A case folder under the temp directory, removed on destruction.
struct TempCase {
    fs::path dir;
    TempCase() {
        static std::atomic<int> counter{0};
        std::random_device rd;
        dir = fs::temp_directory_path() /
              ("magFoam_test_shapes_" + std::to_string(rd()) + "_" + std::to_string(counter++));
        fs::create_directories(dir / "system");
    }
    TempCase(const TempCase&) = delete;
    TempCase& operator=(const TempCase&) = delete;
    ~TempCase() {
        std::error_code ec;
        fs::remove_all(dir, ec);
    }
    void geometryDict(const std::string& text) const { std::ofstream(dir / "system/geometryDict.yaml") << text; }
};

} // namespace

// ---------------------------------------------------------------------------
// Every generator: usable, expected topology, no self-intersection

TEST_CASE("default shapes are usable, of the right genus, without self-intersections", "[shapes]") {
    struct Case {
        SurfaceMesh mesh;
        int triangles;
        int euler;
    };
    const std::vector<Case> cases = {
        {makePaperclip(), 1368, 2},   {makeHexNut(), 192, 0},    {makeWasher(), 256, 0},
        {makeBentPlate(), 68, 2},     {makeRod(), 96, 2},        {makeBarMagnet(), 12, 2},
        {makeCraneDisc(), 512, 2},    {makeCraneDisc(0.1, 0.04, 0, 0, 32), 128, 2},
        {makeBentPlate(0.01, 0.001, 0.02, 0.01, 120.0, 0.0, 1), 20, 2},
        {makeBentPlate(0.01, 0.001, 0.02, 0.02, 180.0, 0.002, 4), 84, 2},
        {makeTube({{0, 0, 0}, {0.01, 0, 0}, {0.01, 0.01, 0.005}, {0, 0.02, 0.01}}, 0.001, 8, TubeCap::flat), 64, 2},
    };
    for (const Case& c : cases) {
        INFO(c.mesh.source);
        checkUsable(c.mesh, 1, c.euler);
        CHECK(c.mesh.nTriangles() == c.triangles);
        CHECK(edgeTriangleCrossings(c.mesh, c.mesh, true) == 0);
    }
}

TEST_CASE("binder clip: sheet and handles are usable and disjoint", "[shapes][binderClip]") {
    const std::vector<SurfaceMesh> parts = makeBinderClip();
    REQUIRE(parts.size() == 3);
    CHECK(parts[0].nTriangles() == 156);
    CHECK(parts[1].nTriangles() == 352);
    CHECK(parts[2].nTriangles() == 352);
    for (const SurfaceMesh& p : parts) {
        checkUsable(p);
        CHECK(edgeTriangleCrossings(p, p, true) == 0);
    }
    CHECK(disjoint(parts[0], parts[1]));
    CHECK(disjoint(parts[0], parts[2]));
    CHECK(disjoint(parts[1], parts[2]));

    // Merged: one mesh of three shells, volume the sum of the parts'.
    const SurfaceMesh merged = mergeParts(parts);
    checkUsable(merged, 3, 6);
    CHECK(relative(signedVolume(merged), signedVolume(parts[0]) + signedVolume(parts[1]) + signedVolume(parts[2])) < 1e-12);

    // The sheet is a 0.5 mm shell: volume = thickness * width * centreline
    // length. Centreline: lip, jaw tip, back fold, back fold, jaw tip, lip
    // (documented layout); each fold of turn a is an arc of radius
    // foldRadius + t/2 in k = ceil(4 a / 90 deg) chords replacing 2 rc tan(a/2).
    const BinderClipOptions o = binderClipOptions(0.025);
    const double t = o.thickness, la = o.lipAngle * pi / 180.0;
    const Vec3 tip(o.depth, 0, 0.5 * (o.mouthGap + t)), back(0.5 * t, 0, 0.5 * (o.spine - t));
    const Vec3 lip = tip + o.lip * Vec3(std::cos(la), 0, std::sin(la));
    const Vec3 flip(1, 1, -1);
    const std::vector<Vec3> corners = {lip, tip, back, back.cwiseProduct(flip), tip.cwiseProduct(flip), lip.cwiseProduct(flip)};
    double centreline = pathLength(corners);
    const double rc = o.foldRadius + 0.5 * t;
    for (std::size_t i = 1; i + 1 < corners.size(); ++i) {
        const Vec3 d1 = (corners[i] - corners[i - 1]).normalized(), d2 = (corners[i + 1] - corners[i]).normalized();
        const double turn = std::acos(d1.dot(d2));
        const int k = static_cast<int>(std::ceil(4.0 * turn / (0.5 * pi) - 1e-9));
        centreline += 2.0 * k * rc * std::sin(0.5 * turn / k) - 2.0 * rc * std::tan(0.5 * turn);
    }
    CHECK(relative(signedVolume(parts[0]), t * o.width * centreline) < 1e-12);
    CHECK(boundingBox(parts[0]).size().y() == Approx(o.width).epsilon(1e-12));

    // Scaled clips keep their proportions; no handles gives the sheet only.
    BinderClipOptions small = binderClipOptions(0.015);
    CHECK(small.thickness == Approx(0.0003));
    const std::vector<SurfaceMesh> smallParts = makeBinderClip(small);
    for (const SurfaceMesh& p : smallParts) checkUsable(p);
    CHECK(disjoint(smallParts[0], smallParts[1]));
    small.handles = false;
    CHECK(makeBinderClip(small).size() == 1);
}

// ---------------------------------------------------------------------------
// Volumes against closed forms

TEST_CASE("washer volume is the polygonal annulus and converges with order 2", "[shapes][convergence]") {
    const double R = 0.005, r = 0.00265, t = 0.001;
    const double exact = pi * (R * R - r * r) * t;
    std::vector<double> errors;
    for (int n : {16, 32, 64, 128}) {
        const double V = signedVolume(makeWasher(2 * R, 2 * r, t, n));
        CHECK(relative(V, polygonFactor(n) * exact) < 1e-12);
        errors.push_back(exact - V);
    }
    for (std::size_t k = 0; k + 1 < errors.size(); ++k) CHECK(observedOrder(errors[k], errors[k + 1]) == Approx(2.0).margin(0.02));
    CHECK(relative(signedVolume(makeWasher(2 * R, 2 * r, t, 32)), exact) < 0.007);
}

TEST_CASE("hex nut volume is hexagon minus polygonal hole", "[shapes][convergence]") {
    const double F = 0.008, d = 0.005, t = 0.0035;
    const double hexagon = std::sqrt(3.0) / 2.0 * F * F * t;  // across flats F: side F / sqrt(3)
    const double round = hexagon - pi * 0.25 * d * d * t;
    std::vector<double> errors;
    for (int n : {12, 24, 48, 96}) {
        const SurfaceMesh nut = makeHexNut(F, d, t, n);
        const double V = signedVolume(nut);
        CHECK(relative(V, hexagon - polygonFactor(n) * pi * 0.25 * d * d * t) < 1e-12);
        errors.push_back(V - round);
        // Flats across x, corners on y.
        const Vec3 size = boundingBox(nut).size();
        CHECK(size.x() == Approx(F).epsilon(1e-12));
        CHECK(size.y() == Approx(2.0 * F / std::sqrt(3.0)).epsilon(1e-12));
    }
    for (std::size_t k = 0; k + 1 < errors.size(); ++k) CHECK(observedOrder(errors[k], errors[k + 1]) == Approx(2.0).margin(0.02));
}

TEST_CASE("straight tube: exact prism with flat caps, pi r^2 L + 4/3 pi r^3 with round caps", "[shapes][tube][convergence]") {
    const double r = 0.0005, L = 0.02;
    // Along an oblique axis, so the frame choice is exercised.
    const Vec3 axis = Vec3(1, 2, 2).normalized();
    const std::vector<Vec3> path = {Vec3(0.001, 0, 0), Vec3(0.001, 0, 0) + L * axis};
    std::vector<double> errors;
    const double exact = pi * r * r * L + 4.0 / 3.0 * pi * r * r * r;
    for (int n : {8, 16, 32, 64}) {
        const SurfaceMesh flat = makeTube(path, r, n, TubeCap::flat);
        checkUsable(flat);
        CHECK(flat.nTriangles() == 4 * n);
        CHECK(relative(signedVolume(flat), polygonFactor(n) * pi * r * r * L) < 1e-12);
        const SurfaceMesh round = makeTube(path, r, n);
        checkUsable(round);
        errors.push_back(exact - signedVolume(round));
    }
    for (std::size_t k = 0; k + 1 < errors.size(); ++k) CHECK(observedOrder(errors[k], errors[k + 1]) == Approx(2.0).margin(0.1));
    CHECK(errors.back() > 0.0);
    CHECK(errors.back() / exact < 0.003);
}

TEST_CASE("bent tube: mitred joints keep the volume exactly area times path length", "[shapes][tube]") {
    // A non-planar zig-zag: parallel transport and mitres in 3D.
    const std::vector<Vec3> path = {{0, 0, 0}, {0.01, 0, 0}, {0.015, 0.008, 0.002}, {0.012, 0.016, 0.009},
                                    {0.004, 0.018, 0.012}, {0.0, 0.012, 0.02}};
    const double r = 0.0008;
    for (int n : {5, 12, 24}) {
        const SurfaceMesh tube = makeTube(path, r, n, TubeCap::flat);
        checkUsable(tube);
        CHECK(edgeTriangleCrossings(tube, tube, true) == 0);
        CHECK(relative(signedVolume(tube), polygonFactor(n) * pi * r * r * pathLength(path)) < 1e-12);
    }
    // A half circle of radius R in 24 chords: exact for the polyline, and within
    // the chord error of Pappus' pi r^2 * pi R.
    const double R = 0.01;
    std::vector<Vec3> arc;
    for (int k = 0; k <= 24; ++k) arc.emplace_back(R * std::cos(pi * k / 24), R * std::sin(pi * k / 24), 0.0);
    const SurfaceMesh bent = makeTube(arc, r, 64, TubeCap::flat);
    checkUsable(bent);
    CHECK(edgeTriangleCrossings(bent, bent, true) == 0);
    CHECK(relative(signedVolume(bent), polygonFactor(64) * pi * r * r * pathLength(arc)) < 1e-12);
    CHECK(relative(signedVolume(bent), pi * r * r * pi * R) < 0.003);
}

TEST_CASE("bent plate volume is thickness x width x centreline length", "[shapes]") {
    const double W = 0.02, t = 0.0015, a = 0.03, b = 0.02;
    // Sharp bend: centreline = the two legs.
    for (double angle : {0.0, 45.0, 90.0, 135.0}) {
        const SurfaceMesh sharp = makeBentPlate(W, t, a, b, angle, 0.0, 1);
        checkUsable(sharp);
        CHECK(relative(signedVolume(sharp), t * W * (a + b)) < 1e-12);
    }
    // Rounded bend of centreline radius rc between the legs, k chords.
    for (double angle : {30.0, 90.0, 180.0}) {
        const double ri = 0.002, rc = ri + 0.5 * t, theta = angle * pi / 180.0;
        const int k = static_cast<int>(std::ceil(6 * angle / 90.0 - 1e-9));
        const double centreline = a + b + k * 2.0 * rc * std::sin(0.5 * theta / k);
        const SurfaceMesh plate = makeBentPlate(W, t, a, b, angle, ri, 6);
        checkUsable(plate);
        CHECK(plate.nTriangles() == 8 * (k + 2) + 4);
        CHECK(edgeTriangleCrossings(plate, plate, true) == 0);
        CHECK(relative(signedVolume(plate), t * W * centreline) < 1e-12);
    }
    // A U: the legs are 2 ri apart (inner faces), the outer width 2 ri + 2 t.
    const SurfaceMesh u = makeBentPlate(W, t, a, b, 180.0, 0.002, 6);
    CHECK(boundingBox(u).size().z() == Approx(2 * 0.002 + 2 * t).epsilon(1e-12));
}

TEST_CASE("rod and crane disc volumes", "[shapes]") {
    const double r = 0.003, L = 0.05;
    const SurfaceMesh rod = makeRod(r, L, 24);
    CHECK(relative(signedVolume(rod), polygonFactor(24) * pi * r * r * L) < 1e-12);
    CHECK(boundingBox(rod).size().x() == Approx(L).epsilon(1e-12));  // along x

    const double R = 0.15, H = 0.05, w = 0.015, d = 0.01;
    const SurfaceMesh disc = makeCraneDisc(R, H, w, d, 64);
    CHECK(relative(signedVolume(disc), polygonFactor(64) * pi * (R * R * H - (R - w) * (R - w) * d)) < 1e-12);
    CHECK(boundingBox(disc).size().z() == Approx(H).epsilon(1e-12));
    CHECK(signedVolume(makeBarMagnet(Vec3(0.05, 0.01, 0.02))) == Approx(1e-5).epsilon(1e-12));
}

// ---------------------------------------------------------------------------
// Paperclip

TEST_CASE("paperclip: size, wire length and volume", "[shapes][paperclip]") {
    const double length = 0.033, width = 0.008, wire = 0.0009, r = 0.5 * wire, s = 0.2 * width;
    const int bend = 16;
    const std::vector<Vec3> path = paperclipPath(length, width, wire, bend);

    // Analytic centreline (the documented layout): four legs and three
    // semicircles of radii (w0 - 2s)/2, (w0 - s)/2, w0/2.
    const double w0 = width - wire, h = 0.5 * w0, L0 = length - wire;
    const double xOL = -0.5 * L0 + h, xIL = xOL + s, Rr = h - 0.5 * s, xR = 0.5 * L0 - Rr;
    const double legs = (xR - s - xIL) + (xR - xIL) + (xR - xOL) + (xR - xOL);
    const double radii = (h - s) + Rr + h;
    const double analytic = legs + pi * radii;
    const double chords = legs + radii * 2.0 * bend * std::sin(0.5 * pi / bend);
    CHECK(relative(pathLength(path), chords) < 1e-12);
    CHECK(relative(pathLength(path), analytic) < 0.002);

    // Flat caps: exactly polygon area x wire length; round caps add two polygonal
    // hemispheres. With many sides the volume approaches pi r^2 L + 4/3 pi r^3.
    const SurfaceMesh flat = makePaperclip(length, width, wire, 12, bend, 0.0, TubeCap::flat);
    CHECK(relative(signedVolume(flat), polygonFactor(12) * pi * r * r * pathLength(path)) < 1e-12);
    const double smooth = pi * r * r * analytic + 4.0 / 3.0 * pi * r * r * r;
    CHECK(relative(signedVolume(makePaperclip(length, width, wire, 64, 64)), smooth) < 0.002);
    CHECK(relative(signedVolume(makePaperclip()), smooth) < 0.05);  // 12 sides: polygon factor 0.955

    // Outer size length x width x wire (rings have vertices on the wire's
    // circle; mitred rings at the ends of the bends stick out by r (1/cos - 1)).
    const Vec3 size = boundingBox(makePaperclip(length, width, wire, 12, bend)).size();
    CHECK(size.x() == Approx(length).epsilon(1e-3));
    CHECK(size.y() == Approx(width).epsilon(1e-9));
    CHECK(size.z() == Approx(wire).epsilon(1e-9));
    CHECK(boundingBox(makePaperclip()).centre().norm() < 1e-9);
}

TEST_CASE("paperclip: the wire never comes near itself", "[shapes][paperclip]") {
    // Segments farther apart along the wire than pi r (the arc over which a bend
    // of radius >= r can bring two points within 2 r) must stay 2 r apart; the
    // layout promises the leg spacing.
    struct Size {
        double length, width, wire, spacing;
    };
    for (const Size& c : {Size{0.033, 0.008, 0.0009, 0.0}, Size{0.05, 0.01, 0.0012, 0.0},
                          Size{0.028, 0.007, 0.0008, 0.0012}, Size{0.033, 0.008, 0.0009, 0.00095}}) {
        const double r = 0.5 * c.wire, s = c.spacing > 0 ? c.spacing : 0.2 * c.width;
        const std::vector<Vec3> path = paperclipPath(c.length, c.width, c.wire, 16, c.spacing);
        const double closest = closestDistantSegments(path, pi * r);
        INFO("length " << c.length << " width " << c.width << " wire " << c.wire << " closest " << closest);
        CHECK(closest >= 2.0 * r);
        // Different loops (farther apart along the wire than half the widest
        // bend) keep the leg spacing, less the sag of the chords.
        CHECK(closestDistantSegments(path, 0.5 * pi * (c.width - c.wire)) >= 0.98 * s);
        const SurfaceMesh clip = makePaperclip(c.length, c.width, c.wire, 8, 16, c.spacing);
        checkUsable(clip);
        CHECK(edgeTriangleCrossings(clip, clip, true) == 0);
    }
}

// ---------------------------------------------------------------------------
// Helpers and bad input

TEST_CASE("roundCorners puts tangent arcs of the given radius on the corners", "[shapes]") {
    const std::vector<Vec3> square = {{0, 0, 0}, {0.01, 0, 0}, {0.01, 0.01, 0}, {0, 0.01, 0}};
    const std::vector<Vec3> rounded = roundCorners(square, 0.002, 3);
    CHECK(rounded.size() == 2 + 2 * 4);
    CHECK(rounded.front() == square.front());
    CHECK(rounded.back() == square.back());
    // First arc: centre (0.008, 0.002), from (0.008, 0) to (0.01, 0.002).
    for (int k = 1; k <= 4; ++k) CHECK((rounded[k] - Vec3(0.008, 0.002, 0)).norm() == Approx(0.002).epsilon(1e-12));
    CHECK((rounded[1] - Vec3(0.008, 0, 0)).norm() < 1e-15);
    CHECK((rounded[4] - Vec3(0.01, 0.002, 0)).norm() < 1e-15);
    CHECK_THROWS_WITH(roundCorners(square, 0.006, 3), Contains("too short"));
}

TEST_CASE("generators reject bad sizes with the shape's name", "[shapes][bad]") {
    CHECK_THROWS_WITH(makePaperclip(0.033, 0.008, 0.0009, 12, 16, 0.0008), Contains("paperclip") && Contains("spacing"));
    CHECK_THROWS_WITH(makePaperclip(0.01, 0.008), Contains("too short"));
    CHECK_THROWS_WITH(makePaperclip(0.033, 0.004, 0.0009, 12, 16, 0.0012), Contains("no inner loop"));
    CHECK_THROWS_WITH(makeTube({{0, 0, 0}, {0.001, 0, 0}, {0.001, 0.001, 0}}, 0.001, 8), Contains("too short for the mitres"));
    CHECK_THROWS_WITH(makeTube({{0, 0, 0}, {0, 0, 0}}, 0.001, 8), Contains("coincide"));
    CHECK_THROWS_WITH(makeTube({{0, 0, 0}, {0.01, 0, 0}, {0, 0.0001, 0}}, 0.0001, 8), Contains("turns by"));
    CHECK_THROWS_WITH(makeTube({{0, 0, 0}}, 0.001, 8), Contains("two points"));
    CHECK_THROWS_WITH(makeHexNut(0.008, 0.005, 0.004, 20), Contains("multiple of 6"));
    CHECK_THROWS_WITH(makeHexNut(0.008, 0.009, 0.004, 24), Contains("smaller"));
    CHECK_THROWS_WITH(makeWasher(0.005, 0.006, 0.001, 24), Contains("smaller"));
    CHECK_THROWS_WITH(makeBentPlate(0.02, 0.0015, 0.03, 0.02, 170.0, 0.0), Contains("0 to 150"));
    CHECK_THROWS_WITH(makeBentPlate(0.02, 0.01, 0.003, 0.02, 135.0, 0.0), Contains("too short"));
    CHECK_THROWS_WITH(makeCraneDisc(0.1, 0.05, 0.2, 0.01), Contains("rimWidth"));
    BinderClipOptions o = binderClipOptions(0.025);
    o.mouthGap = 0.02;
    CHECK_THROWS_WITH(makeBinderClip(o), Contains("spine"));
    CHECK_THROWS_AS(makeRod(-1.0, 0.05, 24), InputError);
}

TEST_CASE("the intersection helpers detect overlap", "[shapes][oracle]") {
    // Guards the oracles above: they must see intersections where there are some.
    SurfaceMesh a = makeBox({0.01, 0.01, 0.01}), b = makeBox({0.01, 0.01, 0.01}), c = makeBox({0.002, 0.002, 0.002});
    translate(b, Vec3(0.005, 0.003, 0.002));
    CHECK_FALSE(disjoint(a, b));
    CHECK_FALSE(disjoint(a, c));  // c inside a: no crossings, but a vertex inside
    translate(b, Vec3(0.02, 0, 0));
    CHECK(disjoint(a, b));
    SurfaceMesh twice = a;
    append(twice, b);
    translate(b, Vec3(-0.021, 0, 0));
    append(twice, b);  // the third box overlaps the first
    CHECK(edgeTriangleCrossings(twice, twice, true) > 0);
    CHECK(closestDistantSegments({{0, 0, 0}, {0.01, 0, 0}, {0.01, 0.001, 0}, {0, 0.001, 0}}, 0.0005) ==
          Approx(0.001).epsilon(1e-12));
}

// ---------------------------------------------------------------------------
// magMakeGeometry

TEST_CASE("makeCaseGeometry writes usable STL files for every part", "[shapes][app]") {
    TempCase c;
    c.geometryDict(R"(parts:
  - {name: paperclip, type: paperclip, length: 0.033, width: 0.008, wire: 0.0009, segments: 12}
  - {name: nut, type: hexNut, acrossFlats: 0.008, hole: 0.005, thickness: 0.0035}
  - {name: clip, type: binderClip, width: 0.02, split: true}
  - {name: clipOne, type: binderClip}
  - {name: washer, type: washer}
  - {name: plate, type: bentPlate, angle: 60}
  - {name: rod, type: rod}
  - {name: bar, type: barMagnet, size: [0.06, 0.015, 0.01]}
  - {name: crane, type: craneDisc, rimWidth: 0}
  - {name: hook, type: tube, wire: 0.001, cornerRadius: 0.003, caps: flat,
     path: [[0, 0, 0], [0.02, 0, 0], [0.02, 0.01, 0.002], [0.005, 0.012, 0.004]]}
)");
    const std::vector<NamedMesh> written = makeCaseGeometry(c.dir);
    const std::vector<std::string> names = {"paperclip", "nut", "clip_sheet", "clip_handle1", "clip_handle2", "clipOne",
                                            "washer", "plate", "rod", "bar", "crane", "hook"};
    REQUIRE(written.size() == names.size());
    for (std::size_t i = 0; i < names.size(); ++i) {
        CHECK(written[i].name == names[i]);
        const fs::path file = c.dir / "constant/geometry" / (names[i] + ".stl");
        REQUIRE(fs::exists(file));
        const SurfaceMesh loaded = loadMesh(file);
        INFO(file.string());
        CHECK_NOTHROW(requireUsable(loaded));
        CHECK(loaded.nTriangles() == written[i].mesh.nTriangles());
        // Single precision in the file: volumes agree to ~1e-6.
        CHECK(relative(signedVolume(loaded), signedVolume(written[i].mesh)) < 1e-5);
    }
    CHECK(checkTopology(written[5].mesh).shells == 3);  // clipOne: sheet + 2 handles
    CHECK(written[0].mesh.nTriangles() == makePaperclip().nTriangles());
    CHECK(relative(signedVolume(written[1].mesh), signedVolume(makeHexNut(0.008, 0.005, 0.0035, 24))) < 1e-12);
    CHECK(boundingBox(written[9].mesh).size().x() == Approx(0.06));
}

TEST_CASE("geometryDict errors cite file and line and write nothing", "[shapes][app][bad]") {
    TempCase c;
    c.geometryDict("parts:\n  - {name: a, type: washer}\n  - {name: b, type: washer, thicknes: 0.001}\n");
    CHECK_THROWS_WITH(makeCaseGeometry(c.dir), Contains("geometryDict.yaml:3:") && Contains("unknown key 'thicknes'") &&
                                                   Contains("did you mean 'thickness'"));
    CHECK_FALSE(fs::exists(c.dir / "constant/geometry/a.stl"));

    c.geometryDict("parts:\n  - {name: a, type: paperklip}\n");
    CHECK_THROWS_WITH(makeCaseGeometry(c.dir), Contains("geometryDict.yaml:2:") && Contains("unknown shape type 'paperklip'") &&
                                                   Contains("paperclip") && Contains("binderClip") && Contains("hexNut"));

    c.geometryDict("parts:\n  - {name: a, type: washer}\n  - {name: a, type: rod}\n");
    CHECK_THROWS_WITH(makeCaseGeometry(c.dir), Contains("geometryDict.yaml:3:") && Contains("exists already"));

    c.geometryDict("parts:\n  - {name: a, type: paperclip,\n     wire: 0.003}\n");
    CHECK_THROWS_WITH(makeCaseGeometry(c.dir), Contains("geometryDict.yaml:2:") && Contains("spacing"));

    c.geometryDict("parts:\n  - {name: ../a, type: rod}\n");
    CHECK_THROWS_WITH(makeCaseGeometry(c.dir), Contains("not a file name"));

    c.geometryDict("parts:\n  - {name: t, type: tube, wire: 0.001, path: [[0, 0, 0], [1, 2]]}\n");
    CHECK_THROWS_WITH(makeCaseGeometry(c.dir), Contains("geometryDict.yaml:2:") && Contains("point 1"));

    c.geometryDict("part:\n  - {name: a, type: rod}\n");
    CHECK_THROWS_WITH(makeCaseGeometry(c.dir), Contains("parts") && Contains("required"));

    fs::remove(c.dir / "system/geometryDict.yaml");
    CHECK_THROWS_WITH(makeCaseGeometry(c.dir), Contains("geometryDict.yaml: not found"));
    CHECK_FALSE(fs::exists(c.dir / "constant/geometry"));
    CHECK_THROWS_WITH(makeCaseGeometry(c.dir / "missing"), Contains("case folder not found"));
}
