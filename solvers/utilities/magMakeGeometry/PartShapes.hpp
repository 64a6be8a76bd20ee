// Everyday steel parts and magnets as closed triangle meshes, for the paper's
// scenes (Fig. 1 binder clips on a neodymium magnet, Fig. 8 paperclips on a bar
// magnet, Fig. 9 metal junk under a crane magnet). Scene parts, not framework:
// they live in the static library magPartShapes beside magMakeGeometry (their
// dictionary front end, GeometryDict.hpp); general primitives (box, sphere,
// cylinder) stay in core's MeshPrimitives.hpp.
//
// Every generator returns a closed, manifold, consistently outward oriented
// mesh without degenerate triangles (requireUsable passes), in SI metres,
// with its bounding box centred at the origin unless said otherwise. Bad
// sizes are InputErrors that name the shape and the expected range.
//
//   shape         built as                                   triangles (defaults)
//   makeTube      wire swept along a polyline, mitred joints  2n per path segment + caps
//   makePaperclip Gem clip: one wire, 3 semicircular bends    1368 (33 x 8 mm, 0.9 mm wire)
//   makeBinderClip folded sheet prism + 2 wire handles        156 sheet + 2 x 352 handles
//   makeHexNut    hexagonal prism with a round hole (genus 1) 8 * segments
//   makeWasher    annulus of thickness t (genus 1)            8 * segments
//   makeBentPlate extruded thick polyline (L / V / U bracket) 8 per centreline segment + 4
//   makeRod       round rod along x (makeCylinder)            4 * segments
//   makeBarMagnet box (makeBox)                               12
//   makeCraneDisc disc along z, optional rim below            8 * segments (4 without rim)
//
// Frames: long parts lie along x (paperclip, rod, bar magnet); flat parts lie
// in the xy plane (paperclip, nut, washer, crane disc, axis z); extruded parts
// (bent plate, binder clip) are extruded along y with their cross-section in
// the xz plane. Angles are in degrees, as in the dictionaries.
//
// Accuracy: curved surfaces are polygonal (vertices on the true surface), so
// volumes approach the closed forms at second order in the number of segments
// (from below; from above for a nut, whose inscribed hole is too small); straight tubes with flat caps, nuts, washers and bent plates
// have exactly the volume of the polygonal cross-section times the length.
#pragma once

#include <magFoam/ConvexPieces.hpp>
#include <magFoam/SurfaceMesh.hpp>

#include <string>
#include <vector>

namespace mag {

// ---------------------------------------------------------------------------
// Wires
// ---------------------------------------------------------------------------

// End of a tube: a hemisphere (latitude rings, then a pole vertex) or a flat disc.
enum class TubeCap { round, flat };

// A wire of the given radius swept along a polyline (the centreline, at least
// two points): a tube of 'segments' (>= 3) sides with parallel-transport
// (rotation-minimising) frames, so the wire does not twist. At an inner point
// the ring lies in the bisecting (mitre) plane of the two segments, so every
// straight piece is an exact prism: with flat caps the volume is exactly
// (segments/2) sin(2 pi/segments) r^2 * path length. Round caps add
// (hemispherical) ~ 2/3 pi r^3 each.
// Smooth curves are given as finely sampled polylines (see roundCorners).
// InputError when: fewer than two points, repeated points, a turn of more than
// 150 degrees at one point, or a segment too short for the mitres at its ends
// (bend radius below the wire radius: the tube would fold into itself).
// The tube is not moved (it follows the path); self-intersections between
// distant parts of the path are not detected (keep them > 2 r apart).
SurfaceMesh makeTube(const std::vector<Vec3>& path, double radius, int segments,
                     TubeCap caps = TubeCap::round);

// Replaces every inner corner of a polyline by a circular arc of the given
// radius tangent to both segments, sampled with segmentsPer90 chords per 90
// degrees of turn (at least one chord per corner). End points stay. InputError
// when the arcs of two neighbouring corners would overlap (segment too short).
std::vector<Vec3> roundCorners(const std::vector<Vec3>& polyline, double radius,
                               int segmentsPer90);

// Centreline of the classic Gem paperclip in the xy plane, bounding box of the
// wire (centreline +- wireDiameter/2) centred at the origin, long side along x:
//   start: free end of the inner leg (inside the loop of the right bend), going -x
//   inner-left bend, radius (w0 - 2 s)/2        (w0 = width - wireDiameter,
//   middle leg along the bottom, going +x                s = spacing)
//   right bend, radius (w0 - s)/2, up to the top
//   top leg, going -x
//   outer-left bend, radius w0/2 (encloses the inner-left bend, clearance >= s)
//   bottom leg, going +x, ending under the right bend: the other free end.
// Neighbouring legs are 'spacing' apart (centre to centre); the loops never
// come closer than 'spacing' (> wireDiameter) to each other. Each semicircular
// bend is sampled with bendSegments chords. spacing <= 0 selects 0.2 * width.
// InputError unless wireDiameter < spacing, width - wireDiameter - 2 spacing >
// wireDiameter (the inner loop is open) and the clip is long enough for its
// straight legs (length - width >= 2.5 spacing).
std::vector<Vec3> paperclipPath(double length = 0.033, double width = 0.008,
                                double wireDiameter = 0.0009, int bendSegments = 16,
                                double spacing = 0.0);

// Gem paperclip: makeTube along paperclipPath with 'segments' sides and the
// given caps. Outer size length x width x wireDiameter (33 x 8 x 0.9 mm by
// default; the mitred rings at the bends' apexes stick out by r (1/cos(90/bendSegments
// degrees) - 1), 2 micrometres at the defaults). 0.60 g of steel at the defaults.
SurfaceMesh makePaperclip(double length = 0.033, double width = 0.008,
                          double wireDiameter = 0.0009, int segments = 12,
                          int bendSegments = 16, double spacing = 0.0,
                          TubeCap caps = TubeCap::round);

// ---------------------------------------------------------------------------
// Binder clip (Fig. 1)
// ---------------------------------------------------------------------------

// Sizes of a binder clip. The sheet is a thick polyline in the xz plane,
// extruded along y by 'width': spine (back, at -x) with two rounded folds, two
// jaws converging towards the mouth (+x) where they almost touch ('mouthGap'
// between their inner faces), then two short lips flared outward. The handles
// are wire loops lying folded back on the outer faces of the jaws; their pivot
// ends sit at the mouth end of the jaws.
struct BinderClipOptions {
    double width = 0.025;          // along the spine (y), m
    double depth = 0.0175;         // spine back face to the jaw tips (x), m
    double spine = 0.010;          // outer height of the spine (z), m
    double thickness = 0.0005;     // sheet thickness, m
    double mouthGap = 0.0005;      // between the jaws' inner faces at the tips, m
    double lip = 0.0015;           // length of each flared lip, m (0: none)
    double lipAngle = 30.0;        // lip direction above the x axis, degrees
    double foldRadius = 0.0005;    // inner radius of the sheet folds, m
    int foldSegments = 4;          // chords per 90 degrees of fold
    bool handles = true;           // false: the sheet only
    double handleWire = 0.001;     // handle wire diameter, m
    double handleLength = 0.0225;  // from the pivot line to the far end of the loop, m
    double handleSpan = 0.019;     // centreline distance between the pivot corners, m
    double handleLoop = 0.011;     // centreline width of the finger loop, m
    double handlePivot = 0.002;     // length of each pivot end, m
    double handleCorner = 0.0015;  // centreline radius of the handle corners, m
    int handleSegments = 8;        // sides of the handle wire
    int handleBendSegments = 3;    // chords per 90 degrees of handle corner
};

// Realistic proportions scaled to a clip of the given width (the defaults above
// are binderClipOptions(0.025): a 25 mm clip of 0.5 mm steel with 1 mm handles).
BinderClipOptions binderClipOptions(double width);

// The parts of a binder clip: [0] the sheet, [1] the handle on the +z jaw,
// [2] the handle on the -z jaw (only the sheet when options.handles is false).
// In a real clip the handle pivots go through the sheet's hinges; here the
// handles lie a small clearance (0.2 * thickness) outside the jaws and the
// pivots stop outside the sheet, so the parts never intersect. They may be
// written as separate bodies or merged (mergeParts) into one mesh with three
// shells, a valid closed surface for a single rigid clip.
std::vector<SurfaceMesh> makeBinderClip(const BinderClipOptions& options);
std::vector<SurfaceMesh> makeBinderClip(double width = 0.025);

// All parts appended into one mesh (one shell per part); source names the first.
SurfaceMesh mergeParts(const std::vector<SurfaceMesh>& parts, const std::string& source = "");

// ---------------------------------------------------------------------------
// Junk: nuts, washers, brackets, rods
// ---------------------------------------------------------------------------

// Hexagonal nut, axis z, flats facing +-x: a hexagonal prism (across flats,
// thickness) with a round hole of the given diameter, i.e. a closed surface of
// genus 1. The hole is a regular polygon of 'segments' sides (a multiple of 6,
// >= 6) inscribed in the circle; each hole vertex is joined radially to the
// hexagon. Volume exactly (sqrt(3)/2) F^2 t - (n/2) sin(2 pi/n) r^2 t.
// 8 * segments triangles.
SurfaceMesh makeHexNut(double acrossFlats = 0.008, double holeDiameter = 0.005,
                       double thickness = 0.004, int segments = 24);

// Flat washer, axis z: outer and inner diameters, thickness; both circles are
// regular 'segments'-gons (>= 3). Volume exactly (n/2) sin(2 pi/n) (R^2 - r^2) t
// -> pi (R^2 - r^2) t at second order in n. 8 * segments triangles.
SurfaceMesh makeWasher(double outerDiameter = 0.010, double innerDiameter = 0.0053,
                       double thickness = 0.001, int segments = 32);

// Bent plate (L, V or U bracket): a plate of the given thickness and width
// (along y) whose centreline in the xz plane runs legA along +x, bends up by
// bendAngle degrees (0 flat, 90 an L, 180 a U) and runs legB. With
// innerBendRadius > 0 the bend is an arc of centreline radius innerBendRadius +
// thickness/2 between the two flat legs (sampled with bendSegments chords per
// 90 degrees); with 0 the legs meet at a sharp, mitred corner (bendAngle <= 150;
// legs measured to the corner on the centreline). Bounding box centred.
// Volume exactly thickness * width * centreline polyline length.
SurfaceMesh makeBentPlate(double width = 0.02, double thickness = 0.0015, double legA = 0.03,
                          double legB = 0.02, double bendAngle = 90.0,
                          double innerBendRadius = 0.0015, int bendSegments = 6);

// Round rod along x (makeCylinder turned): 4 * segments triangles.
SurfaceMesh makeRod(double radius = 0.003, double length = 0.05, int segments = 24);

// Bar magnet: a box with edge lengths size (x the long side), 12 triangles.
SurfaceMesh makeBarMagnet(const Vec3& size = Vec3(0.05, 0.01, 0.01));

// Crane (lifting) magnet, axis z: a disc of the given radius and overall height;
// with rimWidth > 0 and rimDepth > 0 an outer rim of that radial width
// protrudes rimDepth below the recessed bottom face inside it (the pole ring of
// a lifting magnet). Profile revolved with 'segments' (>= 3) sides.
// Volume exactly (n/2) sin(2 pi/n) (R^2 h - (R - w)^2 d).
SurfaceMesh makeCraneDisc(double radius = 0.15, double height = 0.05, double rimWidth = 0.015,
                          double rimDepth = 0.01, int segments = 64);

// ---------------------------------------------------------------------------
// Convex pieces (collision only; docs/rigid-bodies.md#convex-pieces)
// ---------------------------------------------------------------------------

// Point sets (ConvexPieces.hpp) whose convex hulls tile a part exactly (no
// gaps, no overlaps): what rigid-body engines collide instead of a concave mesh.
// From the vertex layout of the builders above (moves and rotations of the
// mesh keep it): a tube (makeTube, makePaperclip, binder clip handles) is a
// chain of mitred prisms, one per pair of neighbouring rings, and its caps'
// frusta; an extruded thick polyline (makeBentPlate, the binder clip sheet)
// one trapezoid prism per centreline segment; an annulus (makeHexNut,
// makeWasher) one prism per sector. InputError when the mesh does not have
// the layout (another builder's mesh).
ConvexPieces tubePieces(const SurfaceMesh& tube, int segments);
ConvexPieces platePieces(const SurfaceMesh& plate);
ConvexPieces annulusPieces(const SurfaceMesh& annulus);
// A crane disc with a rim (makeCraneDisc's arguments): the inner cylinder
// above the recess and one trapezoid prism per sector of the outer ring
// (full height). Empty without a rim (the disc is convex).
ConvexPieces craneDiscPieces(double radius, double height, double rimWidth, double rimDepth, int segments);

} // namespace mag
