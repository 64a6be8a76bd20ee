// VTK XML writers (ASCII; ParaView opens them directly): image data (.vti)
// for sampled fields and poly data (.vtp) for lines, scattered points and
// surfaces.
#pragma once

#include "magFoam/Types.hpp"

#include <array>
#include <filesystem>
#include <string>
#include <vector>

namespace mag::vtk {

// A named point field: 1 (scalar) or 3 (vector) components per point.
struct PointField {
    std::string name;
    int components = 1;
    std::vector<double> values;  // components * nPoints, point-major
};

// Regular grid: dims points along x, y, z (x fastest), spacing in metres.
void writeImageData(const std::filesystem::path& file, const Vec3& origin, const Vec3& spacing,
                    const std::array<int, 3>& dims, const std::vector<PointField>& fields);

// Points joined as one polyline (lines) or triangles (surfaces), with point
// fields and optional cell fields.
void writePolyLine(const std::filesystem::path& file, const std::vector<Vec3>& points,
                   const std::vector<PointField>& fields);
// Unconnected points (one vertex cell each): scattered samples.
void writeVertices(const std::filesystem::path& file, const std::vector<Vec3>& points,
                   const std::vector<PointField>& fields);
// `names`: a string array "bodyNames" in the data set's field data (ParaView's
// Information tab; cell field "body" indexes it).
void writeSurface(const std::filesystem::path& file, const std::vector<Vec3>& points,
                  const std::vector<std::array<int, 3>>& triangles, const std::vector<PointField>& pointFields,
                  const std::vector<PointField>& cellFields, const std::vector<std::string>& names = {});

} // namespace mag::vtk
