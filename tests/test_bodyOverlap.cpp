// findOverlaps (BodyOverlap.hpp): bodies inside each other are found, with the
// depth of the deepest vertex; bodies apart or touching (flush faces, a vertex on
// a face) are not; a crossing with no vertex inside is found through its edges.
#include "bodyFixture.hpp"

#include "PartShapes.hpp"

#include <magFoam/BodyOverlap.hpp>
#include <magFoam/ShapeFactory.hpp>

#include <catch2/catch.hpp>

using mag::Vec3;
using magtest::axisAngle;
using magtest::boxShape;
using magtest::magnet;

namespace {
std::vector<mag::Body> two(const mag::Body& a, const mag::Body& b) { return {a, b}; }
}

TEST_CASE("overlaps: apart, flush and touching bodies are not reported", "[overlap]") {
    const auto cube = boxShape(Vec3::Constant(0.01));
    const auto a = magnet("a", cube, Vec3::Zero(), Vec3(0, 0, 1));
    CHECK(mag::findOverlaps(two(a, magnet("b", cube, Vec3(0, 0, 0.0105), Vec3(0, 0, 1)))).empty());  // 0.5 mm gap
    CHECK(mag::findOverlaps(two(a, magnet("b", cube, Vec3(0, 0, 0.01), Vec3(0, 0, 1)))).empty());    // faces flush
    CHECK(mag::findOverlaps(two(a, magnet("b", cube, Vec3(0.003, 0.004, 0.01), Vec3(0, 0, 1)))).empty());  // shifted
    // Standing on one edge of the other's top face, 45 degrees: a vertex line on a face.
    const double h = 0.005 + 0.005 * std::sqrt(2.0);
    CHECK(mag::findOverlaps(two(a, magnet("b", cube, Vec3(0, 0, h), Vec3(0, 0, 1), axisAngle(45, Vec3(1, 0, 0)))))
              .empty());
}

TEST_CASE("overlaps: interpenetrating bodies are reported with their depth", "[overlap]") {
    const auto cube = boxShape(Vec3::Constant(0.01));
    const auto a = magnet("a", cube, Vec3::Zero(), Vec3(0, 0, 1));
    // 1 mm into the other: the bottom corners of b are 1 mm deep in a (and a's top
    // corners 1 mm deep in b).
    const auto found = mag::findOverlaps(two(a, magnet("b", cube, Vec3(0.001, -0.002, 0.009), Vec3(0, 0, 1))));
    REQUIRE(found.size() == 1);
    CHECK(found[0].a == 0);
    CHECK(found[0].b == 1);
    CHECK(found[0].depth == Approx(0.001).epsilon(1e-9));
    // One inside the other entirely: a 2 mm cube near the middle of a 1 cm one; its
    // deepest probes, the centroids (0, +-1/3, -+1/3) mm of its triangles on x = 0,
    // are 5 - 1/3 mm from the nearest face.
    const auto small = magnet("s", boxShape(Vec3::Constant(0.002)), Vec3(0.001, 0, 0), Vec3(1, 0, 0));
    const auto inner = mag::findOverlaps(two(a, small));
    REQUIRE(inner.size() == 1);
    CHECK(inner[0].depth == Approx(0.014 / 3).epsilon(1e-9));
    // Only pairs that overlap, in index order, among several.
    const auto far = magnet("far", cube, Vec3(0.1, 0, 0), Vec3(0, 0, 1));
    const auto list = mag::findOverlaps({far, a, small, magnet("c", cube, Vec3(0.1, 0, 0.0095), Vec3(1, 0, 0))});
    // (0, 3): sides aligned, 0.5 mm too low: every corner of each lies on an edge
    // of the other, the face centroids are inside.
    REQUIRE(list.size() == 2);
    CHECK((list[0].a == 0 && list[0].b == 3));
    CHECK(list[0].depth == Approx(0.0005).epsilon(1e-9));
    CHECK((list[1].a == 1 && list[1].b == 2));
}

TEST_CASE("overlaps: two bars crossing like a plus sign, no vertex inside, are found", "[overlap]") {
    const auto bar = boxShape(Vec3(0.03, 0.002, 0.002));
    const auto x = magnet("x", bar, Vec3::Zero(), Vec3(1, 0, 0));
    const auto y = magnet("y", bar, Vec3(0, 0, 0.0005), Vec3(1, 0, 0), axisAngle(90, Vec3(0, 0, 1)));
    const auto found = mag::findOverlaps(two(x, y));
    REQUIRE(found.size() == 1);
    // No vertex of one is inside the other; the centre of y is, 0.5 mm from x's top.
    CHECK(found[0].depth == Approx(0.0005).epsilon(1e-9));
    // Lifted clear of each other: none.
    CHECK(mag::findOverlaps(two(x, magnet("y", bar, Vec3(0, 0, 0.0021), Vec3(1, 0, 0), axisAngle(90, Vec3(0, 0, 1)))))
              .empty());
}

// A ring's (a washer's, a paperclip's) centre of mass lies in empty space,
// where another body may pass without touching it: a rod through a washer's
// hole is not inside it, though the washer's centre is inside the rod. Two
// identical rings at one place still are (a point of the material inside).
// (Fig. 8: a clip resting with another's wire through its centre of mass was
// reported 0.2 mm sunk in, the depth of that point in the wire.)
TEST_CASE("overlaps: a rod through a washer's hole is not inside it, washers or clips at one place are",
          "[overlap]") {
    const auto washer = mag::makeShape(mag::makeWasher(0.010, 0.0053, 0.001, 32), mag::ShapeKind{});
    const auto w = magnet("w", washer, Vec3::Zero(), Vec3(0, 0, 1));
    // Rod of 1 mm radius along the washer's axis: 1.65 mm clear of the hole's rim.
    const auto rod = mag::makeShape(mag::makeRod(0.001, 0.03, 24), mag::ShapeKind{});
    CHECK(mag::findOverlaps(two(w, magnet("r", rod, Vec3::Zero(), Vec3(1, 0, 0), axisAngle(90, Vec3(0, 1, 0)))))
              .empty());
    // Shifted by 2 mm, the rod cuts through the ring's material.
    CHECK(mag::findOverlaps(two(w, magnet("r", rod, Vec3(0.002, 0, 0), Vec3(1, 0, 0), axisAngle(90, Vec3(0, 1, 0)))))
              .size() == 1);
    // Identical washers at one place: every vertex and face centroid lies on the
    // other's surface; the inner point, mid-thickness under the largest
    // triangle (a face of the annulus), is half the thickness deep.
    const auto same = mag::findOverlaps(two(w, magnet("v", washer, Vec3::Zero(), Vec3(0, 0, 1))));
    REQUIRE(same.size() == 1);
    CHECK(same[0].depth == Approx(0.0005).epsilon(1e-9));
    // Identical paperclips (0.9 mm wire) at one place: a point of the wire, at
    // most its radius deep.
    const auto clip = mag::makeShape(mag::makePaperclip(), mag::ShapeKind{});
    const auto clips = mag::findOverlaps(two(magnet("c", clip, Vec3::Zero(), Vec3(1, 0, 0)),
                                             magnet("d", clip, Vec3::Zero(), Vec3(1, 0, 0))));
    REQUIRE(clips.size() == 1);
    CHECK(clips[0].depth > 0.0002);
    CHECK(clips[0].depth <= 0.00045);
}

// surfaceGap of two bars crossed one above the other: their closest points lie
// on an edge of each, mid-edge, 15 mm from every vertex (a paperclip lying
// across another). Exact: the vertical gap.
TEST_CASE("surface gap: bars crossing with a gap, closest points between vertices", "[overlap]") {
    const auto bar = boxShape(Vec3(0.03, 0.002, 0.002));
    const auto x = magnet("x", bar, Vec3::Zero(), Vec3(1, 0, 0));
    for (double gap : {1e-6, 1e-4, 3e-3}) {
        const auto y = magnet("y", bar, Vec3(0, 0, 0.002 + gap), Vec3(1, 0, 0), axisAngle(90, Vec3(0, 0, 1)));
        CHECK(mag::surfaceGap(x, y) == Approx(gap).epsilon(1e-9));
        CHECK(mag::surfaceGap(y, x) == Approx(gap).epsilon(1e-9));
    }
    // Apart by more than the cap: the cap.
    const auto far = magnet("y", bar, Vec3(0, 0, 0.1), Vec3(1, 0, 0), axisAngle(90, Vec3(0, 0, 1)));
    CHECK(mag::surfaceGap(x, far, 0.01) == 0.01);
}
