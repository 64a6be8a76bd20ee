// magMakeGeometry: writes the meshes of everyday steel parts and magnets (the
// paper's scenes: Fig. 1 binder clips, Fig. 8 paperclips and a bar magnet,
// Fig. 9 junk under a crane magnet) into a case, from system/geometryDict.yaml:
//
//   parts:
//     - {name: paperclip, type: paperclip, length: 0.033, width: 0.008, wire: 0.0009, segments: 12}
//     - {name: nut, type: hexNut, acrossFlats: 0.008, hole: 0.005, thickness: 0.0035}
//     - {name: clip, type: binderClip, width: 0.025}            # 3 shells in one mesh
//     - {name: hook, type: tube, wire: 0.001, cornerRadius: 0.002,
//        path: [[0, 0, 0], [0.02, 0, 0], [0.02, 0.01, 0]]}
//
// Each part is checked (closed, manifold, outward: requireUsable) and written
// as binary STL constant/geometry/<name>.stl, for bodies.yaml:
//   geometry: {file: geometry/paperclip.stl}
// A table lists triangles, volume and bounding-box size per part. Nothing is
// written when any part is invalid. Unknown keys and types are errors citing
// file:line. Names: letters, digits, '_', '-', '.'.
//
// Types and keys (SI metres, angles in degrees; defaults in brackets):
//   paperclip   Gem clip, one bent wire in the xy plane, long side x (1368 triangles)
//               length [0.033] width [0.008] wire [0.0009] (diameter)
//               spacing [0.2 width] (between neighbouring legs, centre to centre, > wire)
//               segments [12] (sides of the wire) bendSegments [16] (per 180-degree bend)
//               caps [round] (round | flat)
//   binderClip  folded sheet (spine at -x, mouth at +x, extruded along y) + 2 wire
//               handles folded back on the jaws, clear of the sheet (912 triangles);
//               every default scales with width:
//               width [0.025] depth [0.7 w] spine [0.4 w] (outer height of the back)
//               thickness [0.02 w] mouthGap [0.02 w] lip [0.06 w] lipAngle [30]
//               foldRadius [0.02 w] (inner) foldSegments [4] (per 90 degrees)
//               handles [true] handleWire [0.04 w] handleLength [0.9 w]
//               handleSpan [0.76 w] handleLoop [0.44 w] handlePivot [0.08 w]
//               handleCorner [0.06 w] handleSegments [8] handleBendSegments [3]
//               split [false]: true writes <name>_sheet, <name>_handle1, <name>_handle2
//               (separate bodies); false one mesh of three shells (one rigid clip)
//   hexNut      acrossFlats [0.008] hole [0.005] (diameter) thickness [0.004]
//               segments [24] (hole sides, a multiple of 6); axis z (192 triangles)
//   washer      outer [0.010] inner [0.0053] (diameters) thickness [0.001]
//               segments [32]; axis z (256 triangles)
//   bentPlate   L/V/U bracket, extruded along y (68 triangles): width [0.02]
//               thickness [0.0015] legA [0.03] legB [0.02] (flat legs, centreline)
//               angle [90] (0 flat .. 180 a U) bendRadius [thickness] (inner; 0: a
//               sharp corner, legs to the corner, angle <= 150) bendSegments [6] (per 90 degrees)
//   rod         radius [0.003] length [0.05] segments [24]; axis x (96 triangles)
//   barMagnet   size [[0.05, 0.01, 0.01]] (12 triangles)
//   ellipsoid   semiAxes [[0.005, 0.0005, 0.0005]] subdivisions [4] (0..6);
//               semi-axes along x, y, z (20 4^subdivisions triangles)
//   craneDisc   radius [0.15] height [0.05] (overall) rimWidth [0.015] rimDepth [0.01]
//               (0: a plain disc) segments [64]; axis z, rim below (512 triangles)
//   tube        a wire along a polyline: path (required, list of [x, y, z])
//               wire (required, diameter) segments [12] caps [round]
//               cornerRadius [0] (> 0: corners become arcs) bendSegments [4] (per 90 degrees)
//
// Parts are centred on their bounding box (tube: as given by its path); bodies
// are placed by their centre of mass in bodies.yaml anyway.
#include "GeometryDict.hpp"

#include <magFoam/ArgList.hpp>
#include <magFoam/Log.hpp>
#include <magFoam/MassProperties.hpp>

using namespace mag;

namespace {

int run(const ArgList& args) {
    const auto dir = args.caseDir();
    spdlog::info("magMakeGeometry: case {}, reading system/geometryDict.yaml", dir.string());
    const std::vector<NamedMesh> parts = makeCaseGeometry(dir);

    spdlog::info("  {:<18} {:<11} {:>9} {:>13} {:>33}", "part", "type", "triangles", "volume [m^3]",
                 "bounding size [m]");
    for (const NamedMesh& p : parts) {
        const Vec3 size = boundingBox(p.mesh).size();
        spdlog::info("  {:<18} {:<11} {:>9} {:>13.6g} {:>10.4g} x {:>9.4g} x {:>9.4g}", p.name, p.type,
                     p.mesh.nTriangles(), signedVolume(p.mesh), size.x(), size.y(), size.z());
    }
    spdlog::info("wrote {} mesh(es) to {}", parts.size(), (dir / "constant/geometry").string());
    return 0;
}

} // namespace

int main(int argc, char** argv) {
    std::string types;
    for (const auto& t : shapeTypes()) types += (types.empty() ? "" : ", ") + t;
    ArgList args("magMakeGeometry",
                 "Writes meshes of paperclips, binder clips, nuts, washers, brackets, rods, ellipsoids and magnets "
                 "(system/geometryDict.yaml) to constant/geometry/<name>.stl.\n"
                 "Part types: " + types + ".\n"
                 "Their keys and defaults: docs/case-reference.md#geometrydict.");
    args.outputs("  constant/geometry/<name>.stl   binary STL per part, metres (bodies.yaml: geometry: {file: ...})\n");
    if (!args.parse(argc, argv)) return args.exitCode();
    return runGuarded(args, run);
}
