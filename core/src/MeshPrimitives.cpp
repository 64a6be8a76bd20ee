// Primitive meshes: box, icosphere, ellipsoid, cylinder.
#include <magFoam/MeshPrimitives.hpp>

#include <magFoam/Error.hpp>

#include "MeshNumerics.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <unordered_map>

namespace mag {

namespace {

const auto number = meshDetail::formatNumber;

void requirePositive(double value, const std::string& what, const std::string& primitive) {
    if (!std::isfinite(value) || value <= 0.0)
        throw InputError(primitive + ": " + what + " = " + number(value) +
                         ", expected a finite number > 0");
}

void requireRange(int value, int low, int high, const std::string& what,
                  const std::string& primitive) {
    if (value < low || value > high)
        throw InputError(primitive + ": " + what + " = " + std::to_string(value) + ", expected " +
                         std::to_string(low) + " to " + std::to_string(high));
}

// Unit icosphere (radius 1, outward counter-clockwise triangles).
SurfaceMesh unitIcosphere(int subdivisions) {
    SurfaceMesh mesh;
    const double g = (1.0 + std::sqrt(5.0)) / 2.0;  // golden ratio
    mesh.vertices = {{-1, g, 0},  {1, g, 0},  {-1, -g, 0}, {1, -g, 0}, {0, -1, g},  {0, 1, g},
                     {0, -1, -g}, {0, 1, -g}, {g, 0, -1},  {g, 0, 1},  {-g, 0, -1}, {-g, 0, 1}};
    for (Vec3& p : mesh.vertices) p.normalize();
    mesh.triangles = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                      {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                      {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                      {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};

    // Each level splits every triangle into four; the new vertex of an edge is
    // shared by both neighbours (looked up by the edge's vertex pair) and pushed
    // out onto the sphere.
    for (int level = 0; level < subdivisions; ++level) {
        std::unordered_map<std::uint64_t, int> midpoints;
        midpoints.reserve(mesh.triangles.size() * 2);
        auto midpoint = [&](int a, int b) {
            const auto key = (static_cast<std::uint64_t>(std::min(a, b)) << 32) |
                             static_cast<std::uint32_t>(std::max(a, b));
            const auto [it, inserted] = midpoints.try_emplace(key, mesh.nVertices());
            if (inserted) mesh.vertices.push_back((mesh.vertices[a] + mesh.vertices[b]).normalized());
            return it->second;
        };
        std::vector<std::array<int, 3>> finer;
        finer.reserve(4 * mesh.triangles.size());
        for (const auto& [a, b, c] : mesh.triangles) {
            const int ab = midpoint(a, b);
            const int bc = midpoint(b, c);
            const int ca = midpoint(c, a);
            finer.push_back({a, ab, ca});
            finer.push_back({b, bc, ab});
            finer.push_back({c, ca, bc});
            finer.push_back({ab, bc, ca});
        }
        mesh.triangles = std::move(finer);
    }
    return mesh;
}

} // namespace

SurfaceMesh makeBox(const Vec3& size) {
    const std::string name = "box(size = [" + number(size.x()) + ", " + number(size.y()) + ", " +
                             number(size.z()) + "])";
    requirePositive(size.x(), "size x", name);
    requirePositive(size.y(), "size y", name);
    requirePositive(size.z(), "size z", name);

    SurfaceMesh mesh;
    mesh.source = name;
    // Vertex i has bit 0 -> +x, bit 1 -> +y, bit 2 -> +z.
    for (int i = 0; i < 8; ++i)
        mesh.vertices.push_back(0.5 * Vec3((i & 1) ? size.x() : -size.x(),
                                           (i & 2) ? size.y() : -size.y(),
                                           (i & 4) ? size.z() : -size.z()));
    mesh.triangles = {{0, 4, 6}, {0, 6, 2},   // -x
                      {1, 3, 7}, {1, 7, 5},   // +x
                      {0, 1, 5}, {0, 5, 4},   // -y
                      {2, 6, 7}, {2, 7, 3},   // +y
                      {0, 2, 3}, {0, 3, 1},   // -z
                      {4, 5, 7}, {4, 7, 6}};  // +z
    return mesh;
}

SurfaceMesh makeIcosphere(double radius, int subdivisions) {
    const std::string name = "icosphere(radius = " + number(radius) +
                             ", subdivisions = " + std::to_string(subdivisions) + ")";
    requirePositive(radius, "radius", name);
    requireRange(subdivisions, 0, 8, "subdivisions", name);
    SurfaceMesh mesh = unitIcosphere(subdivisions);
    for (Vec3& p : mesh.vertices) p *= radius;
    mesh.source = name;
    return mesh;
}

SurfaceMesh makeEllipsoid(const Vec3& semiAxes, int subdivisions) {
    const std::string name = "ellipsoid(semiAxes = [" + number(semiAxes.x()) + ", " +
                             number(semiAxes.y()) + ", " + number(semiAxes.z()) +
                             "], subdivisions = " + std::to_string(subdivisions) + ")";
    requirePositive(semiAxes.x(), "semi-axis x", name);
    requirePositive(semiAxes.y(), "semi-axis y", name);
    requirePositive(semiAxes.z(), "semi-axis z", name);
    requireRange(subdivisions, 0, 8, "subdivisions", name);
    SurfaceMesh mesh = unitIcosphere(subdivisions);
    for (Vec3& p : mesh.vertices) p = p.cwiseProduct(semiAxes);
    mesh.source = name;
    return mesh;
}

SurfaceMesh makeCylinder(double radius, double height, int segments) {
    const std::string name = "cylinder(radius = " + number(radius) + ", height = " +
                             number(height) + ", segments = " + std::to_string(segments) + ")";
    requirePositive(radius, "radius", name);
    requirePositive(height, "height", name);
    requireRange(segments, 3, 1 << 20, "segments", name);

    SurfaceMesh mesh;
    mesh.source = name;
    const double h = 0.5 * height;
    // Vertices: bottom ring 0..n-1, top ring n..2n-1, bottom centre 2n, top centre 2n+1.
    const int n = segments;
    for (double z : {-h, h})
        for (int i = 0; i < n; ++i) {
            const double phi = 2.0 * pi * i / n;
            mesh.vertices.emplace_back(radius * std::cos(phi), radius * std::sin(phi), z);
        }
    mesh.vertices.emplace_back(0.0, 0.0, -h);
    mesh.vertices.emplace_back(0.0, 0.0, h);
    const int bottomCentre = 2 * n;
    const int topCentre = 2 * n + 1;
    for (int i = 0; i < n; ++i) {
        const int j = (i + 1) % n;
        // Side quad split in two, counter-clockwise seen from outside.
        mesh.triangles.push_back({i, j, n + j});
        mesh.triangles.push_back({i, n + j, n + i});
        // Caps: counter-clockwise seen from +z on top, from -z at the bottom.
        mesh.triangles.push_back({topCentre, n + i, n + j});
        mesh.triangles.push_back({bottomCentre, j, i});
    }
    return mesh;
}

} // namespace mag
