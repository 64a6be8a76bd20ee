#include "magFoam/VtkWriter.hpp"

#include "magFoam/OutputFile.hpp"

#include <sstream>

namespace mag::vtk {

namespace {

// Each file is formatted in memory and written whole (writeFileAtomically):
// ParaView never finds half a file, and a failed write names the file.
std::ostringstream openFile() {
    std::ostringstream out;
    out.precision(10);
    return out;
}

void writeArrays(std::ostream& out, const std::vector<PointField>& fields) {
    for (const auto& f : fields) {
        out << "<DataArray type=\"Float64\" Name=\"" << f.name << "\" NumberOfComponents=\"" << f.components
            << "\" format=\"ascii\">\n";
        for (std::size_t i = 0; i < f.values.size(); ++i) out << f.values[i] << ((i + 1) % 9 ? ' ' : '\n');
        out << "\n</DataArray>\n";
    }
}

void writePoints(std::ostream& out, const std::vector<Vec3>& points) {
    out << "<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
    for (const auto& p : points) out << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
    out << "</DataArray></Points>\n";
}

} // namespace

void writeImageData(const std::filesystem::path& file, const Vec3& origin, const Vec3& spacing,
                    const std::array<int, 3>& dims, const std::vector<PointField>& fields) {
    auto out = openFile();
    const std::string extent = "0 " + std::to_string(dims[0] - 1) + " 0 " + std::to_string(dims[1] - 1) + " 0 " +
                               std::to_string(dims[2] - 1);
    out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"ImageData\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
        << "<ImageData WholeExtent=\"" << extent << "\" Origin=\"" << origin.x() << ' ' << origin.y() << ' '
        << origin.z() << "\" Spacing=\"" << spacing.x() << ' ' << spacing.y() << ' ' << spacing.z() << "\">\n"
        << "<Piece Extent=\"" << extent << "\">\n<PointData>\n";
    writeArrays(out, fields);
    out << "</PointData>\n</Piece>\n</ImageData>\n</VTKFile>\n";
    writeFileAtomically(file, out.str());
}

void writePolyLine(const std::filesystem::path& file, const std::vector<Vec3>& points,
                   const std::vector<PointField>& fields) {
    auto out = openFile();
    const std::size_t n = points.size();
    out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
        << "<PolyData>\n<Piece NumberOfPoints=\"" << n << "\" NumberOfLines=\"1\">\n<PointData>\n";
    writeArrays(out, fields);
    out << "</PointData>\n";
    writePoints(out, points);
    out << "<Lines><DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
    for (std::size_t i = 0; i < n; ++i) out << i << ' ';
    out << "\n</DataArray><DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">" << n
        << "</DataArray></Lines>\n</Piece>\n</PolyData>\n</VTKFile>\n";
    writeFileAtomically(file, out.str());
}

void writeVertices(const std::filesystem::path& file, const std::vector<Vec3>& points,
                   const std::vector<PointField>& fields) {
    auto out = openFile();
    const std::size_t n = points.size();
    out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
        << "<PolyData>\n<Piece NumberOfPoints=\"" << n << "\" NumberOfVerts=\"" << n << "\">\n<PointData>\n";
    writeArrays(out, fields);
    out << "</PointData>\n";
    writePoints(out, points);
    out << "<Verts><DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
    for (std::size_t i = 0; i < n; ++i) out << i << ((i + 1) % 20 ? ' ' : '\n');
    out << "\n</DataArray><DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
    for (std::size_t i = 1; i <= n; ++i) out << i << ((i % 20) ? ' ' : '\n');
    out << "\n</DataArray></Verts>\n</Piece>\n</PolyData>\n</VTKFile>\n";
    writeFileAtomically(file, out.str());
}

void writeSurface(const std::filesystem::path& file, const std::vector<Vec3>& points,
                  const std::vector<std::array<int, 3>>& triangles, const std::vector<PointField>& pointFields,
                  const std::vector<PointField>& cellFields, const std::vector<std::string>& names) {
    auto out = openFile();
    out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
        << "<PolyData>\n";
    if (!names.empty()) {
        // VTK's ASCII form of a string array: each string's bytes as integers, then 0.
        out << "<FieldData>\n<DataArray type=\"String\" Name=\"bodyNames\" NumberOfTuples=\"" << names.size()
            << "\" format=\"ascii\">\n";
        for (const std::string& n : names) {
            for (unsigned char c : n) out << int(c) << ' ';
            out << "0\n";
        }
        out << "</DataArray>\n</FieldData>\n";
    }
    out << "<Piece NumberOfPoints=\"" << points.size() << "\" NumberOfPolys=\"" << triangles.size()
        << "\">\n<PointData>\n";
    writeArrays(out, pointFields);
    out << "</PointData>\n<CellData>\n";
    writeArrays(out, cellFields);
    out << "</CellData>\n";
    writePoints(out, points);
    out << "<Polys><DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
    for (const auto& t : triangles) out << t[0] << ' ' << t[1] << ' ' << t[2] << '\n';
    out << "</DataArray><DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
    for (std::size_t i = 1; i <= triangles.size(); ++i) out << 3 * i << ((i % 20) ? ' ' : '\n');
    out << "\n</DataArray></Polys>\n</Piece>\n</PolyData>\n</VTKFile>\n";
    writeFileAtomically(file, out.str());
}

} // namespace mag::vtk
