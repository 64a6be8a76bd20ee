// Scene part generators: tubes (wires), paperclip, binder clip, nut, washer,
// bent plate, rod, bar magnet, crane disc.
#include "PartShapes.hpp"

#include <magFoam/Error.hpp>
#include <magFoam/MeshPrimitives.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace mag {

namespace {

using Vec2 = Eigen::Vector2d;

// Numbers in messages: 9 significant digits, "%g" style, as in core's mesh
// messages (so 1e-6 m^3 does not print as 0.000000).
std::string number(double x) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.9g", x);
    return buffer;
}

void requirePositive(double value, const std::string& what, const std::string& shape) {
    if (!std::isfinite(value) || value <= 0.0)
        throw InputError(shape + ": " + what + " = " + number(value) +
                         ", expected a finite number > 0");
}

void requireNonNegative(double value, const std::string& what, const std::string& shape) {
    if (!std::isfinite(value) || value < 0.0)
        throw InputError(shape + ": " + what + " = " + number(value) +
                         ", expected a finite number >= 0");
}

void requireRange(int value, int low, int high, const std::string& what,
                  const std::string& shape) {
    if (value < low || value > high)
        throw InputError(shape + ": " + what + " = " + std::to_string(value) + ", expected " +
                         std::to_string(low) + " to " + std::to_string(high));
}

double degrees(double radians) { return radians * 180.0 / pi; }
double radians(double degrees) { return degrees * pi / 180.0; }

// Angle between two unit vectors, accurate for small and large angles.
double angleBetween(const Vec3& a, const Vec3& b) {
    return std::atan2(a.cross(b).norm(), a.dot(b));
}

// Moves the mesh so that its bounding box is centred at the origin; returns the shift.
Vec3 centreBox(SurfaceMesh& mesh) {
    const Vec3 shift = -boundingBox(mesh).centre();
    translate(mesh, shift);
    return shift;
}

// Flips the triangles if the enclosed volume came out negative (used by the
// builders whose winding depends on the turning sense of their profile).
void orientOutward(SurfaceMesh& mesh) {
    double volume = 0.0;
    for (int t = 0; t < mesh.nTriangles(); ++t)
        volume += mesh.corner(t, 0).dot(mesh.corner(t, 1).cross(mesh.corner(t, 2)));
    if (volume < 0.0) flipOrientation(mesh);
}

// A planar quad a-b-c-d (counter-clockwise from outside) as two triangles.
void addQuad(SurfaceMesh& mesh, int a, int b, int c, int d) {
    mesh.triangles.push_back({a, b, c});
    mesh.triangles.push_back({a, c, d});
}

// Points of a circular arc in the xy plane (angles in radians), both ends included.
void appendArc(std::vector<Vec3>& path, const Vec3& centre, double radius, double from, double to,
               int chords) {
    for (int k = 0; k <= chords; ++k) {
        const double phi = from + (to - from) * k / chords;
        path.push_back(centre + radius * Vec3(std::cos(phi), std::sin(phi), 0.0));
    }
}

// Removes consecutive points closer than tol (arcs whose ends meet).
std::vector<Vec3> withoutRepeats(const std::vector<Vec3>& points, double tol) {
    std::vector<Vec3> out;
    for (const Vec3& p : points)
        if (out.empty() || (p - out.back()).norm() > tol) out.push_back(p);
    return out;
}

double polylineLength(const std::vector<Vec3>& points) {
    double length = 0.0;
    for (std::size_t i = 1; i < points.size(); ++i) length += (points[i] - points[i - 1]).norm();
    return length;
}

// A thick open polyline (centreline in the xz plane, as (x, z) pairs) extruded
// along y from -width/2 to width/2: both sides are offset by thickness/2 with
// mitred joints, so every piece is a trapezoid of area thickness * its
// centreline length. The ends are cut square to the end segments.
SurfaceMesh extrudeThickPolyline(const std::vector<Vec2>& centreline, double thickness,
                                 double width, const std::string& name) {
    const int m = static_cast<int>(centreline.size()) - 1;
    if (m < 1) throw InputError(name + ": the cross-section needs at least two points");
    std::vector<Vec2> dir(m), left(m + 1), right(m + 1);
    for (int k = 0; k < m; ++k) {
        const Vec2 d = centreline[k + 1] - centreline[k];
        if (d.norm() <= 1e-12 * thickness)
            throw InputError(name + ": cross-section points " + std::to_string(k) + " and " +
                             std::to_string(k + 1) + " coincide");
        dir[k] = d.normalized();
    }
    // Left normal of each segment; at an inner point the mitre direction is the
    // mean of the two normals, stretched so both offset lines are thickness/2 away.
    auto normal = [&](int k) { return Vec2(-dir[k].y(), dir[k].x()); };
    for (int k = 0; k <= m; ++k) {
        Vec2 offset;
        if (k == 0) {
            offset = normal(0);
        } else if (k == m) {
            offset = normal(m - 1);
        } else {
            const Vec2 mitre = (normal(k - 1) + normal(k)).normalized();
            const double cosHalf = mitre.dot(normal(k));
            if (cosHalf < std::cos(radians(75.0)))
                throw InputError(name + ": the cross-section turns by more than 150 degrees at point " +
                                 std::to_string(k) + "; round the bend instead");
            offset = mitre / cosHalf;
        }
        left[k] = centreline[k] + 0.5 * thickness * offset;
        right[k] = centreline[k] - 0.5 * thickness * offset;
    }
    // Each side of each piece must run forward, else the mitres cross (a bend
    // tighter than half the thickness, or a leg shorter than its mitres).
    for (int k = 0; k < m; ++k)
        if ((left[k + 1] - left[k]).dot(dir[k]) <= 1e-9 * thickness ||
            (right[k + 1] - right[k]).dot(dir[k]) <= 1e-9 * thickness)
            throw InputError(name + ": cross-section segment " + std::to_string(k) + " (length " +
                             number((centreline[k + 1] - centreline[k]).norm()) +
                             ") is too short for the thickness at its bends: use a larger bend "
                             "radius (> thickness/2) or longer legs");

    SurfaceMesh mesh;
    mesh.source = name;
    // Vertex 4k + s: s = 0 left at -y, 1 left at +y, 2 right at -y, 3 right at +y.
    const double h = 0.5 * width;
    for (int k = 0; k <= m; ++k)
        for (const Vec2& p : {left[k], right[k]})
            for (double y : {-h, h}) mesh.vertices.emplace_back(p.x(), y, p.y());
    auto L = [](int k, int s) { return 4 * k + s; };      // s: 0 at -y, 1 at +y
    auto R = [](int k, int s) { return 4 * k + 2 + s; };
    for (int k = 0; k < m; ++k) {
        addQuad(mesh, L(k, 0), L(k + 1, 0), L(k + 1, 1), L(k, 1));  // left wall
        addQuad(mesh, R(k, 0), R(k, 1), R(k + 1, 1), R(k + 1, 0));  // right wall
        addQuad(mesh, L(k, 0), R(k, 0), R(k + 1, 0), L(k + 1, 0));  // face at -y
        addQuad(mesh, L(k, 1), L(k + 1, 1), R(k + 1, 1), R(k, 1));  // face at +y
    }
    addQuad(mesh, L(0, 0), L(0, 1), R(0, 1), R(0, 0));  // start
    addQuad(mesh, L(m, 0), R(m, 0), R(m, 1), L(m, 1));  // end
    orientOutward(mesh);
    return mesh;
}

// A prism of thickness t along z between an inner and an outer closed ring
// (matching points on the same rays, counter-clockwise seen from +z): a solid
// of genus 1 (nut, washer), z from -t/2 to t/2. 8 n triangles.
SurfaceMesh annularPrism(const std::vector<Vec2>& inner, const std::vector<Vec2>& outer,
                         double thickness, const std::string& name) {
    const int n = static_cast<int>(inner.size());
    SurfaceMesh mesh;
    mesh.source = name;
    // Vertex index: inner bottom j, inner top n + j, outer bottom 2n + j, outer top 3n + j.
    const double h = 0.5 * thickness;
    for (const auto* ring : {&inner, &outer})
        for (double z : {-h, h})
            for (const Vec2& p : *ring) mesh.vertices.emplace_back(p.x(), p.y(), z);
    for (int j = 0; j < n; ++j) {
        const int k = (j + 1) % n;
        const int ib = j, ibk = k, it = n + j, itk = n + k;
        const int ob = 2 * n + j, obk = 2 * n + k, ot = 3 * n + j, otk = 3 * n + k;
        addQuad(mesh, it, ot, otk, itk);  // top (+z)
        addQuad(mesh, ib, ibk, obk, ob);  // bottom (-z)
        addQuad(mesh, ob, obk, otk, ot);  // outer wall
        addQuad(mesh, ib, it, itk, ibk);  // hole wall (normal towards the axis)
    }
    return mesh;
}

// A profile (rho, z) revolved about z with n sides. The profile is an open
// polyline from a point on the axis to another point on the axis, counter-
// clockwise in the (rho, z) half plane (material on its left), all inner
// points off the axis: a closed surface of genus 0.
SurfaceMesh revolveProfile(const std::vector<Vec2>& profile, int n, const std::string& name) {
    SurfaceMesh mesh;
    mesh.source = name;
    // First vertex of each profile point (a single vertex on the axis, else a ring).
    std::vector<int> first;
    for (const Vec2& p : profile) {
        first.push_back(mesh.nVertices());
        if (p.x() == 0.0) {
            mesh.vertices.emplace_back(0.0, 0.0, p.y());
            continue;
        }
        for (int j = 0; j < n; ++j) {
            const double phi = 2.0 * pi * j / n;
            mesh.vertices.emplace_back(p.x() * std::cos(phi), p.x() * std::sin(phi), p.y());
        }
    }
    for (std::size_t k = 0; k + 1 < profile.size(); ++k) {
        const bool axisA = profile[k].x() == 0.0, axisB = profile[k + 1].x() == 0.0;
        const int a = first[k], b = first[k + 1];
        for (int j = 0; j < n; ++j) {
            const int i = (j + 1) % n;
            if (axisA)
                mesh.triangles.push_back({a, b + i, b + j});
            else if (axisB)
                mesh.triangles.push_back({a + j, a + i, b});
            else
                addQuad(mesh, a + j, a + i, b + i, b + j);
        }
    }
    orientOutward(mesh);
    return mesh;
}

std::string capName(TubeCap caps) { return caps == TubeCap::round ? "round" : "flat"; }

} // namespace

// ---------------------------------------------------------------------------
// Wires
// ---------------------------------------------------------------------------

SurfaceMesh makeTube(const std::vector<Vec3>& path, double radius, int segments, TubeCap caps) {
    const std::string name = "tube(" + std::to_string(path.size()) + " points, radius = " +
                             number(radius) + ", segments = " + std::to_string(segments) +
                             ", caps = " + capName(caps) + ")";
    requirePositive(radius, "radius", name);
    requireRange(segments, 3, 1 << 16, "segments", name);
    if (path.size() < 2) throw InputError(name + ": the path needs at least two points");
    for (std::size_t i = 0; i < path.size(); ++i)
        if (!path[i].allFinite())
            throw InputError(name + ": path point " + std::to_string(i) + " is not finite");

    // Unit tangents and lengths of the path segments.
    const int m = static_cast<int>(path.size()) - 1;
    const double total = polylineLength(path);
    std::vector<Vec3> t(m);
    std::vector<double> length(m);
    for (int i = 0; i < m; ++i) {
        length[i] = (path[i + 1] - path[i]).norm();
        if (length[i] <= 1e-12 * total)
            throw InputError(name + ": path points " + std::to_string(i) + " and " +
                             std::to_string(i + 1) + " coincide at " + formatPoint(path[i]));
        t[i] = (path[i + 1] - path[i]) / length[i];
    }

    // tan(turn/2) at each point (0 at the ends); the ring at an inner point is
    // mitred, reaching r tan(turn/2) along the wire on either side.
    std::vector<double> tanHalf(m + 1, 0.0);
    for (int i = 1; i < m; ++i) {
        const double turn = angleBetween(t[i - 1], t[i]);
        if (turn > radians(150.0))
            throw InputError(name + ": the path turns by " + number(degrees(turn)) +
                             " degrees at point " + std::to_string(i) + " " + formatPoint(path[i]) +
                             ", at most 150 allowed: sample sharp bends as arcs");
        tanHalf[i] = std::tan(0.5 * turn);
    }
    for (int i = 0; i < m; ++i)
        if (length[i] <= radius * (tanHalf[i] + tanHalf[i + 1]) * (1.0 + 1e-9))
            throw InputError(name + ": path segment " + std::to_string(i) + " (length " +
                             number(length[i]) + ") is too short for the mitres of its bends: "
                             "bend radii must exceed the wire radius " + number(radius));

    // Parallel-transport frames (u, v, t) per segment. The first u is the
    // normal of the first bend (so planar paths give rings symmetric about
    // their plane), or any direction normal to a straight path.
    std::vector<Vec3> u(m), v(m);
    u[0] = Vec3::Zero();
    for (int i = 1; i < m && u[0].norm() == 0.0; ++i) {
        const Vec3 c = t[0].cross(t[i]);
        if (c.norm() > 1e-6) u[0] = c.normalized();
    }
    if (u[0].norm() == 0.0) {
        Eigen::Index axis;
        t[0].cwiseAbs().minCoeff(&axis);
        u[0] = t[0].cross(Vec3::Unit(axis)).normalized();
    }
    v[0] = t[0].cross(u[0]);
    for (int i = 1; i < m; ++i) {
        Vec3 next = Quat::FromTwoVectors(t[i - 1], t[i]) * u[i - 1];
        u[i] = (next - next.dot(t[i]) * t[i]).normalized();
        v[i] = t[i].cross(u[i]);
    }

    // Rings of n points, counter-clockwise about the local tangent, in order
    // along the wire; a pole vertex closes each end.
    const int n = segments;
    std::vector<std::vector<Vec3>> rings;
    auto ring = [&](const Vec3& centre, const Vec3& du, const Vec3& dv, double r) {
        std::vector<Vec3> points(n);
        for (int j = 0; j < n; ++j) {
            const double phi = 2.0 * pi * j / n;
            points[j] = centre + r * (std::cos(phi) * du + std::sin(phi) * dv);
        }
        return points;
    };
    // Hemispherical caps: latitude rings every 90/K degrees.
    const int K = caps == TubeCap::round ? std::max(2, (segments + 2) / 4) : 1;
    const Vec3 startPole = path[0] - (caps == TubeCap::round ? radius : 0.0) * t[0];
    const Vec3 endPole = path[m] + (caps == TubeCap::round ? radius : 0.0) * t[m - 1];
    for (int k = K - 1; k >= 1; --k) {
        const double alpha = 0.5 * pi * k / K;
        rings.push_back(ring(path[0] - radius * std::sin(alpha) * t[0], u[0], v[0],
                             radius * std::cos(alpha)));
    }
    for (int i = 0; i <= m; ++i) {
        if (i == 0 || i == m) {
            const int s = i == 0 ? 0 : m - 1;
            rings.push_back(ring(path[i], u[s], v[s], radius));
            continue;
        }
        // Inner point: the incoming segment's circle cut by the mitre plane
        // (normal t_a + t_b); the same points lie on the outgoing segment's circle.
        const Vec3 mitre = (t[i - 1] + t[i]).normalized();
        std::vector<Vec3> points = ring(path[i], u[i - 1], v[i - 1], radius);
        for (Vec3& p : points) {
            const double s = -(p - path[i]).dot(mitre) / t[i - 1].dot(mitre);
            p += s * t[i - 1];
        }
        rings.push_back(std::move(points));
    }
    for (int k = 1; k <= K - 1; ++k) {
        const double alpha = 0.5 * pi * k / K;
        rings.push_back(ring(path[m] + radius * std::sin(alpha) * t[m - 1], u[m - 1], v[m - 1],
                             radius * std::cos(alpha)));
    }

    SurfaceMesh mesh;
    mesh.source = name;
    mesh.vertices.push_back(startPole);
    for (const auto& r : rings) mesh.vertices.insert(mesh.vertices.end(), r.begin(), r.end());
    mesh.vertices.push_back(endPole);
    const int nRings = static_cast<int>(rings.size());
    const int last = mesh.nVertices() - 1;
    auto at = [&](int r, int j) { return 1 + r * n + (j % n); };
    for (int j = 0; j < n; ++j) {
        mesh.triangles.push_back({0, at(0, j + 1), at(0, j)});
        for (int r = 0; r + 1 < nRings; ++r) addQuad(mesh, at(r, j), at(r, j + 1), at(r + 1, j + 1), at(r + 1, j));
        mesh.triangles.push_back({last, at(nRings - 1, j), at(nRings - 1, j + 1)});
    }
    return mesh;
}

std::vector<Vec3> roundCorners(const std::vector<Vec3>& polyline, double radius, int segmentsPer90) {
    const std::string name = "roundCorners(radius = " + number(radius) + ")";
    requirePositive(radius, "radius", name);
    requireRange(segmentsPer90, 1, 1 << 12, "segmentsPer90", name);
    const int count = static_cast<int>(polyline.size());
    if (count < 3) return polyline;
    const double tol = 1e-9 * polylineLength(polyline);

    // Tangent length radius * tan(turn/2) of every inner corner.
    std::vector<double> tangent(count, 0.0), turn(count, 0.0);
    for (int i = 1; i + 1 < count; ++i) {
        const Vec3 a = polyline[i] - polyline[i - 1], b = polyline[i + 1] - polyline[i];
        if (a.norm() <= tol || b.norm() <= tol)
            throw InputError(name + ": repeated point " + formatPoint(polyline[i]));
        turn[i] = angleBetween(a.normalized(), b.normalized());
        if (turn[i] > radians(179.0))
            throw InputError(name + ": the polyline reverses at " + formatPoint(polyline[i]));
        tangent[i] = radius * std::tan(0.5 * turn[i]);
    }
    for (int i = 0; i + 1 < count; ++i) {
        const double l = (polyline[i + 1] - polyline[i]).norm();
        if (tangent[i] + tangent[i + 1] > l + tol)
            throw InputError(name + ": segment from " + formatPoint(polyline[i]) + " to " +
                             formatPoint(polyline[i + 1]) + " (length " + number(l) +
                             ") is too short for corner radius " + number(radius));
    }

    std::vector<Vec3> out{polyline.front()};
    for (int i = 1; i + 1 < count; ++i) {
        if (turn[i] < 1e-9) {
            out.push_back(polyline[i]);
            continue;
        }
        const Vec3 d1 = (polyline[i] - polyline[i - 1]).normalized();
        const Vec3 d2 = (polyline[i + 1] - polyline[i]).normalized();
        const Vec3 centre = polyline[i] + radius / std::cos(0.5 * turn[i]) * (d2 - d1).normalized();
        const Vec3 start = polyline[i] - tangent[i] * d1;
        const Vec3 axis = d1.cross(d2).normalized();
        const int chords = std::max(1, static_cast<int>(std::ceil(segmentsPer90 * turn[i] / (0.5 * pi) - 1e-9)));
        for (int k = 0; k <= chords; ++k)
            out.push_back(centre + Eigen::AngleAxisd(turn[i] * k / chords, axis) * (start - centre));
    }
    out.push_back(polyline.back());
    return withoutRepeats(out, tol);
}

std::vector<Vec3> paperclipPath(double length, double width, double wireDiameter, int bendSegments,
                                double spacing) {
    const std::string name = "paperclip(length = " + number(length) + ", width = " + number(width) +
                             ", wire = " + number(wireDiameter) + ")";
    requirePositive(length, "length", name);
    requirePositive(width, "width", name);
    requirePositive(wireDiameter, "wire diameter", name);
    requireRange(bendSegments, 2, 1 << 12, "bendSegments", name);
    if (!std::isfinite(spacing)) throw InputError(name + ": spacing is not finite");
    const double s = spacing > 0.0 ? spacing : 0.2 * width;
    const double d = wireDiameter;

    // Centreline sizes: outer loop w0 wide (centre to centre), legs s apart.
    const double w0 = width - d, h = 0.5 * w0, L0 = length - d;
    if (!(s > d))
        throw InputError(name + ": spacing " + number(s) +
                         " between neighbouring legs must exceed the wire diameter");
    if (!(w0 - 2.0 * s > d))
        throw InputError(name + ": width " + number(width) + " leaves no inner loop: need width > " +
                         number(2.0 * d + 2.0 * s) + " (2 wire + 2 spacing)");
    if (!(L0 >= 2.0 * h + 2.5 * s))
        throw InputError(name + ": length " + number(length) + " too short for the width: need >= " +
                         number(width + 2.5 * s));

    const double xOuterLeft = -0.5 * L0 + h;          // centre of the outer-left bend
    const double xInnerLeft = xOuterLeft + s;          // centre of the inner-left bend
    const double rightRadius = h - 0.5 * s;            // right bend joins -h + s to +h
    const double xRight = 0.5 * L0 - rightRadius;      // its centre
    const double innerRadius = h - s;                  // inner-left bend joins h - s to -h + s

    std::vector<Vec3> path;
    path.emplace_back(xRight - s, h - s, 0.0);  // free end of the inner leg
    appendArc(path, Vec3(xInnerLeft, 0.0, 0.0), innerRadius, 0.5 * pi, 1.5 * pi, bendSegments);
    appendArc(path, Vec3(xRight, 0.5 * s, 0.0), rightRadius, -0.5 * pi, 0.5 * pi, bendSegments);
    appendArc(path, Vec3(xOuterLeft, 0.0, 0.0), h, 0.5 * pi, 1.5 * pi, bendSegments);
    path.emplace_back(xRight, -h, 0.0);          // free end of the outer leg
    return path;
}

SurfaceMesh makePaperclip(double length, double width, double wireDiameter, int segments,
                          int bendSegments, double spacing, TubeCap caps) {
    SurfaceMesh mesh = makeTube(paperclipPath(length, width, wireDiameter, bendSegments, spacing),
                                0.5 * wireDiameter, segments, caps);
    mesh.source = "paperclip(length = " + number(length) + ", width = " + number(width) +
                  ", wire = " + number(wireDiameter) + ", segments = " + std::to_string(segments) + ")";
    return mesh;
}

// ---------------------------------------------------------------------------
// Binder clip
// ---------------------------------------------------------------------------

BinderClipOptions binderClipOptions(double width) {
    const std::string name = "binderClip(width = " + number(width) + ")";
    requirePositive(width, "width", name);
    BinderClipOptions o;
    const double f = width / o.width;
    for (double* x : {&o.width, &o.depth, &o.spine, &o.thickness, &o.mouthGap, &o.lip, &o.foldRadius,
                      &o.handleWire, &o.handleLength, &o.handleSpan, &o.handleLoop, &o.handlePivot,
                      &o.handleCorner})
        *x *= f;
    o.width = width;
    return o;
}

std::vector<SurfaceMesh> makeBinderClip(double width) { return makeBinderClip(binderClipOptions(width)); }

std::vector<SurfaceMesh> makeBinderClip(const BinderClipOptions& o) {
    const std::string name = "binderClip(width = " + number(o.width) + ")";
    requirePositive(o.width, "width", name);
    requirePositive(o.depth, "depth", name);
    requirePositive(o.spine, "spine", name);
    requirePositive(o.thickness, "thickness", name);
    requirePositive(o.mouthGap, "mouthGap", name);
    requireNonNegative(o.lip, "lip", name);
    requireNonNegative(o.foldRadius, "foldRadius", name);
    requireRange(o.foldSegments, 1, 64, "foldSegments", name);
    if (!std::isfinite(o.lipAngle) || o.lipAngle < 0.0 || o.lipAngle > 80.0)
        throw InputError(name + ": lipAngle = " + number(o.lipAngle) + ", expected 0 to 80 degrees");
    const double t = o.thickness;
    if (!(o.spine > o.mouthGap + 2.0 * t))
        throw InputError(name + ": spine " + number(o.spine) +
                         " must exceed mouthGap + 2 thickness: the jaws must close towards the mouth");

    // Sheet centreline (x, z): lip, jaw tip, back fold, back fold, jaw tip, lip;
    // back face at x = 0, jaw tips at x = depth.
    const Vec3 tipTop(o.depth, 0.0, 0.5 * (o.mouthGap + t));
    const Vec3 backTop(0.5 * t, 0.0, 0.5 * (o.spine - t));
    const Vec3 lipDir(std::cos(radians(o.lipAngle)), 0.0, std::sin(radians(o.lipAngle)));
    const Vec3 flipZ(1.0, 1.0, -1.0);
    std::vector<Vec3> corners;
    if (o.lip > 0.0) corners.push_back(tipTop + o.lip * lipDir);
    corners.insert(corners.end(), {tipTop, backTop, backTop.cwiseProduct(flipZ), tipTop.cwiseProduct(flipZ)});
    if (o.lip > 0.0) corners.push_back((tipTop + o.lip * lipDir).cwiseProduct(flipZ));
    // The folds bend the sheet about their centreline radius (inner radius + t/2).
    const double foldCentre = o.foldRadius + 0.5 * t;
    std::vector<Vec3> rounded = o.foldRadius > 0.0 ? roundCorners(corners, foldCentre, o.foldSegments) : corners;
    std::vector<Vec2> section;
    for (const Vec3& p : rounded) section.emplace_back(p.x(), p.z());

    std::vector<SurfaceMesh> parts;
    try {
        parts.push_back(extrudeThickPolyline(section, t, o.width, name + " sheet"));
    } catch (const InputError& e) {
        throw InputError(name + ": sheet: " + e.what());
    }
    parts.back().source = name + " sheet";

    if (o.handles) {
        requirePositive(o.handleWire, "handleWire", name);
        requirePositive(o.handleLength, "handleLength", name);
        requirePositive(o.handleSpan, "handleSpan", name);
        requirePositive(o.handleLoop, "handleLoop", name);
        requirePositive(o.handlePivot, "handlePivot", name);
        requirePositive(o.handleCorner, "handleCorner", name);
        requireRange(o.handleSegments, 3, 256, "handleSegments", name);
        requireRange(o.handleBendSegments, 1, 64, "handleBendSegments", name);
        const double rw = 0.5 * o.handleWire;
        if (!(o.handleSpan + o.handleWire < o.width * 1.5))
            throw InputError(name + ": handleSpan " + number(o.handleSpan) + " is far wider than the clip");
        if (!(o.handleSpan - 2.0 * o.handlePivot > 4.0 * rw))
            throw InputError(name + ": handle pivots overlap: need handleSpan - 2 handlePivot > 2 handleWire");

        // Jaw line from the tip towards the back (u) and its outward normal (n).
        const Vec3 eu = (backTop - tipTop).normalized();
        const Vec3 en(eu.z(), 0.0, -eu.x());
        // The lip fold lifts the outer face up to tangentLength from the tip;
        // the wire stays clear of it and a clearance above the jaw's face.
        const double clearance = 0.2 * t;
        double tangentLength = 0.0;
        if (o.lip > 0.0 && o.foldRadius > 0.0)
            tangentLength = foldCentre * std::tan(0.5 * angleBetween(-lipDir, eu));
        else if (o.lip > 0.0)
            tangentLength = 0.5 * t * std::tan(0.5 * angleBetween(-lipDir, eu));
        const Vec3 pivot = tipTop + (tangentLength + rw + clearance) * eu + (0.5 * t + rw + clearance) * en;

        // Handle in its plane (u along the jaw, y across): two pivot ends
        // pointing at each other, legs converging to the finger loop.
        const double a = 0.5 * o.handleSpan, b = 0.5 * o.handleLoop, L = o.handleLength;
        const std::vector<Vec2> plan = {{0, -a + o.handlePivot}, {0, -a}, {L, -b}, {L, b}, {0, a}, {0, a - o.handlePivot}};
        std::vector<Vec3> path;
        for (const Vec2& q : plan) path.push_back(pivot + q.x() * eu + q.y() * Vec3::UnitY());
        try {
            path = roundCorners(path, o.handleCorner, o.handleBendSegments);
            parts.push_back(makeTube(path, rw, o.handleSegments));
            parts.back().source = name + " handle 1";
            for (Vec3& p : path) p = p.cwiseProduct(flipZ);
            parts.push_back(makeTube(path, rw, o.handleSegments));
            parts.back().source = name + " handle 2";
        } catch (const InputError& e) {
            throw InputError(name + ": handle: " + e.what());
        }
    }

    // One shift for all parts: the bounding box of the whole clip at the origin.
    BoundingBox box = boundingBox(parts[0]);
    for (const SurfaceMesh& p : parts) {
        const BoundingBox b = boundingBox(p);
        box.lower = box.lower.cwiseMin(b.lower);
        box.upper = box.upper.cwiseMax(b.upper);
    }
    for (SurfaceMesh& p : parts) translate(p, -box.centre());
    return parts;
}

SurfaceMesh mergeParts(const std::vector<SurfaceMesh>& parts, const std::string& source) {
    SurfaceMesh mesh;
    for (const SurfaceMesh& p : parts) append(mesh, p);
    mesh.source = !source.empty() ? source : parts.empty() ? std::string("empty") : parts.front().source;
    return mesh;
}

// ---------------------------------------------------------------------------
// Junk
// ---------------------------------------------------------------------------

SurfaceMesh makeHexNut(double acrossFlats, double holeDiameter, double thickness, int segments) {
    const std::string name = "hexNut(acrossFlats = " + number(acrossFlats) + ", hole = " +
                             number(holeDiameter) + ", thickness = " + number(thickness) +
                             ", segments = " + std::to_string(segments) + ")";
    requirePositive(acrossFlats, "acrossFlats", name);
    requirePositive(holeDiameter, "hole diameter", name);
    requirePositive(thickness, "thickness", name);
    requireRange(segments, 6, 1 << 16, "segments", name);
    if (segments % 6 != 0)
        throw InputError(name + ": segments = " + std::to_string(segments) + ", expected a multiple of 6");
    if (!(holeDiameter < 0.98 * acrossFlats))
        throw InputError(name + ": hole diameter must be smaller than across flats (at most 98 %)");

    // Rays every 360/n degrees starting at a hexagon corner (30 degrees; flats
    // face 0, 60, ... degrees), so each corner has a ray and every quad lies in
    // one sector of the hexagon.
    const double apothem = 0.5 * acrossFlats, r = 0.5 * holeDiameter;
    std::vector<Vec2> inner, outer;
    for (int j = 0; j < segments; ++j) {
        const double phi = pi / 6.0 + 2.0 * pi * j / segments;
        const double flat = pi / 3.0 * std::floor(phi / (pi / 3.0) + 0.5);  // nearest flat normal
        const Vec2 ray(std::cos(phi), std::sin(phi));
        inner.push_back(r * ray);
        outer.push_back(apothem / std::cos(phi - flat) * ray);
    }
    return annularPrism(inner, outer, thickness, name);
}

SurfaceMesh makeWasher(double outerDiameter, double innerDiameter, double thickness, int segments) {
    const std::string name = "washer(outer = " + number(outerDiameter) + ", inner = " +
                             number(innerDiameter) + ", thickness = " + number(thickness) +
                             ", segments = " + std::to_string(segments) + ")";
    requirePositive(outerDiameter, "outer diameter", name);
    requirePositive(innerDiameter, "inner diameter", name);
    requirePositive(thickness, "thickness", name);
    requireRange(segments, 3, 1 << 16, "segments", name);
    if (!(innerDiameter < 0.999 * outerDiameter))
        throw InputError(name + ": the inner diameter must be smaller than the outer one");
    std::vector<Vec2> inner, outer;
    for (int j = 0; j < segments; ++j) {
        const double phi = 2.0 * pi * j / segments;
        const Vec2 ray(std::cos(phi), std::sin(phi));
        inner.push_back(0.5 * innerDiameter * ray);
        outer.push_back(0.5 * outerDiameter * ray);
    }
    return annularPrism(inner, outer, thickness, name);
}

SurfaceMesh makeBentPlate(double width, double thickness, double legA, double legB, double bendAngle,
                          double innerBendRadius, int bendSegments) {
    const std::string name = "bentPlate(width = " + number(width) + ", thickness = " + number(thickness) +
                             ", legs = " + number(legA) + ", " + number(legB) + ", angle = " +
                             number(bendAngle) + ")";
    requirePositive(width, "width", name);
    requirePositive(thickness, "thickness", name);
    requirePositive(legA, "legA", name);
    requirePositive(legB, "legB", name);
    requireNonNegative(innerBendRadius, "innerBendRadius", name);
    requireRange(bendSegments, 1, 1 << 12, "bendSegments", name);
    if (!std::isfinite(bendAngle) || bendAngle < 0.0 || bendAngle > 180.0 ||
        (innerBendRadius == 0.0 && bendAngle > 150.0))
        throw InputError(name + ": bend angle = " + number(bendAngle) + ", expected 0 to " +
                         (innerBendRadius > 0.0 ? "180 degrees" : "150 degrees for a sharp bend (give a bend radius for more)"));

    // Leg A along +x to the origin, the bend turning up (towards +z) about a
    // centre at (0, rc), leg B onwards in the direction (cos, sin) of the angle.
    const double theta = radians(bendAngle);
    const Vec2 dirB(std::cos(theta), std::sin(theta));
    std::vector<Vec2> section = {{-legA, 0.0}, {0.0, 0.0}};
    if (innerBendRadius > 0.0 && bendAngle > 0.0) {
        const double rc = innerBendRadius + 0.5 * thickness;
        const int chords = std::max(1, static_cast<int>(std::ceil(bendSegments * bendAngle / 90.0 - 1e-9)));
        for (int k = 1; k <= chords; ++k) {
            const double phi = theta * k / chords;
            section.emplace_back(rc * std::sin(phi), rc * (1.0 - std::cos(phi)));
        }
    }
    section.push_back(section.back() + legB * dirB);
    SurfaceMesh mesh = extrudeThickPolyline(section, thickness, width, name);
    centreBox(mesh);
    return mesh;
}

SurfaceMesh makeRod(double radius, double length, int segments) {
    SurfaceMesh mesh = makeCylinder(radius, length, segments);
    rotate(mesh, Quat(Eigen::AngleAxisd(0.5 * pi, Vec3::UnitY())));  // z axis -> x axis
    mesh.source = "rod(radius = " + number(radius) + ", length = " + number(length) +
                  ", segments = " + std::to_string(segments) + ")";
    return mesh;
}

SurfaceMesh makeBarMagnet(const Vec3& size) {
    SurfaceMesh mesh = makeBox(size);
    mesh.source = "barMagnet(size = [" + number(size.x()) + ", " + number(size.y()) + ", " +
                  number(size.z()) + "])";
    return mesh;
}

SurfaceMesh makeCraneDisc(double radius, double height, double rimWidth, double rimDepth, int segments) {
    const std::string name = "craneDisc(radius = " + number(radius) + ", height = " + number(height) +
                             ", rim = " + number(rimWidth) + " x " + number(rimDepth) +
                             ", segments = " + std::to_string(segments) + ")";
    requirePositive(radius, "radius", name);
    requirePositive(height, "height", name);
    requireNonNegative(rimWidth, "rimWidth", name);
    requireNonNegative(rimDepth, "rimDepth", name);
    requireRange(segments, 3, 1 << 16, "segments", name);
    const bool rim = rimWidth > 0.0 && rimDepth > 0.0;
    if (rim && !(rimWidth < radius))
        throw InputError(name + ": rimWidth must be smaller than the radius");
    if (rim && !(rimDepth < height))
        throw InputError(name + ": rimDepth must be smaller than the height");

    // Profile (rho, z), counter-clockwise: bottom (recessed inside the rim), rim, side, top.
    const double top = 0.5 * height, bottom = -0.5 * height;
    std::vector<Vec2> profile;
    if (rim) {
        profile = {{0, bottom + rimDepth}, {radius - rimWidth, bottom + rimDepth},
                   {radius - rimWidth, bottom}, {radius, bottom}, {radius, top}, {0, top}};
    } else {
        profile = {{0, bottom}, {radius, bottom}, {radius, top}, {0, top}};
    }
    return revolveProfile(profile, segments, name);
}

// ---------------------------------------------------------------------------
// Convex pieces
// ---------------------------------------------------------------------------

ConvexPieces tubePieces(const SurfaceMesh& tube, int n) {
    // [start pole, rings of n, end pole] (makeTube).
    const int rings = n >= 3 ? (tube.nVertices() - 2) / n : 0;
    if (n < 3 || rings < 2 || tube.nVertices() != 2 + rings * n || tube.nTriangles() != 2 * n * rings)
        throw InputError(tube.source + ": not a tube of " + std::to_string(n) + " sides");
    auto ring = [&](int r) {
        const auto first = tube.vertices.begin() + 1 + r * n;
        return std::vector<Vec3>(first, first + n);
    };
    // A flat cap's pole lies in its end ring: no piece of its own.
    auto flatCap = [&](const Vec3& pole, const std::vector<Vec3>& end) {
        const Vec3 normal = (end[1] - end[0]).cross(end[2] - end[0]).normalized();
        return std::abs(normal.dot(pole - end[0])) <= 1e-9 * (end[1] - end[0]).norm();
    };
    ConvexPieces pieces;
    for (int r = -1; r < rings; ++r) {
        if ((r < 0 && flatCap(tube.vertices.front(), ring(0))) ||
            (r == rings - 1 && flatCap(tube.vertices.back(), ring(rings - 1))))
            continue;
        std::vector<Vec3> piece = r < 0 ? std::vector<Vec3>{tube.vertices.front()} : ring(r);
        if (r + 1 < rings) {
            const std::vector<Vec3> next = ring(r + 1);
            piece.insert(piece.end(), next.begin(), next.end());
        } else {
            piece.push_back(tube.vertices.back());
        }
        pieces.push_back(std::move(piece));
    }
    return pieces;
}

ConvexPieces platePieces(const SurfaceMesh& plate) {
    // Four vertices per centreline point (extrudeThickPolyline).
    const int points = plate.nVertices() / 4;
    if (points < 2 || plate.nVertices() != 4 * points || plate.nTriangles() != 8 * (points - 1) + 4)
        throw InputError(plate.source + ": not an extruded plate");
    ConvexPieces pieces;
    for (int k = 0; k + 1 < points; ++k)
        pieces.emplace_back(plate.vertices.begin() + 4 * k, plate.vertices.begin() + 4 * k + 8);
    return pieces;
}

ConvexPieces annulusPieces(const SurfaceMesh& annulus) {
    // Inner bottom j, inner top n + j, outer bottom 2n + j, outer top 3n + j (annularPrism).
    const int n = annulus.nVertices() / 4;
    if (n < 3 || annulus.nVertices() != 4 * n || annulus.nTriangles() != 8 * n)
        throw InputError(annulus.source + ": not an annulus");
    ConvexPieces pieces;
    for (int j = 0; j < n; ++j) {
        const int k = (j + 1) % n;
        std::vector<Vec3> piece;
        for (int layer = 0; layer < 4; ++layer)
            piece.insert(piece.end(), {annulus.vertices[layer * n + j], annulus.vertices[layer * n + k]});
        pieces.push_back(std::move(piece));
    }
    return pieces;
}

ConvexPieces craneDiscPieces(double radius, double height, double rimWidth, double rimDepth, int n) {
    if (!(rimWidth > 0.0 && rimDepth > 0.0)) return {};
    // The points of makeCraneDisc's rings (revolveProfile's angles).
    const double top = 0.5 * height, bottom = -0.5 * height, inner = radius - rimWidth;
    auto at = [&](double rho, int j, double z) {
        const double phi = 2.0 * pi * (j % n) / n;
        return Vec3(rho * std::cos(phi), rho * std::sin(phi), z);
    };
    ConvexPieces pieces(1);
    for (int j = 0; j < n; ++j) pieces[0].insert(pieces[0].end(), {at(inner, j, bottom + rimDepth), at(inner, j, top)});
    for (int j = 0; j < n; ++j) {
        std::vector<Vec3> sector;
        for (int k : {j, j + 1})
            for (double rho : {inner, radius})
                for (double z : {bottom, top}) sector.push_back(at(rho, k, z));
        pieces.push_back(std::move(sector));
    }
    return pieces;
}

} // namespace mag
