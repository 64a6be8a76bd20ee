// Mesh files: reading (own readers for PLY and OFF, assimp for the rest, see
// MeshFormats.hpp), welding the result, and writing binary STL and OBJ.
#include <magFoam/MeshIO.hpp>

#include <magFoam/Error.hpp>
#include <magFoam/InputFile.hpp>
#include <magFoam/MeshFormats.hpp>
#include <magFoam/OutputFile.hpp>

#include "AssimpReader.hpp"
#include "MeshNumerics.hpp"

#include <algorithm>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <sstream>

namespace mag {

namespace fs = std::filesystem;

namespace {

std::string lowerExtension(const fs::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext;
}

std::string joined(const std::vector<std::string>& items) {
    std::string text;
    for (const auto& item : items) text += (text.empty() ? "" : " ") + item;
    return text;
}

bool ownReader(const std::string& extension) {
    return extension == ".ply" || extension == ".off" || extension == ".obj";
}

} // namespace

std::vector<std::string> meshFileExtensions() { return {".stl", ".obj", ".ply", ".off"}; }

ParsedMesh parseMeshBytes(std::string_view bytes, const std::string& name, const std::string& extension) {
    if (extension == ".ply") return parsePly(bytes, name);
    if (extension == ".off") return parseOff(bytes, name);
    if (extension == ".obj") return parseObj(bytes, name);
    return parseWithAssimp(bytes, name, extension);
}

SurfaceMesh prepareSurfaceMesh(ParsedMesh parsed, const MeshLoadOptions& options, MeshLoadReport* report) {
    MeshLoadReport local;
    MeshLoadReport& info = report ? *report : local;
    const std::string format = info.format;
    info = MeshLoadReport{};
    info.format = format;
    SurfaceMesh& mesh = parsed.mesh;
    const std::string& name = mesh.source;
    if (!std::isfinite(options.scale) || options.scale <= 0.0)
        throw InputError(name + ": scale " + meshDetail::formatNumber(options.scale) +
                         " is not allowed, expected a finite number > 0");
    info.pointsAndLinesIgnored = parsed.pointsAndLinesIgnored;
    info.verticesRead = mesh.nVertices();
    info.trianglesRead = mesh.nTriangles();
    if (mesh.triangles.empty())
        throw InputError(name + ": the file holds no triangles" +
                         (info.pointsAndLinesIgnored
                              ? " (only " + std::to_string(info.pointsAndLinesIgnored) +
                                    " points or lines)"
                              : std::string()) +
                         ", expected a closed triangle surface");

    if (options.scale != 1.0) {
        scale(mesh, options.scale);
        for (int v = 0; v < mesh.nVertices(); ++v)
            if (!mesh.vertices[v].allFinite() || mesh.vertices[v].cwiseAbs().maxCoeff() > meshCoordinateLimit)
                throw InputError(name + ": scale " + meshDetail::formatNumber(options.scale) + " takes " +
                                 describeVertex(mesh, v) + " beyond 1e30");
    }
    info.verticesMerged = weldVertices(mesh, options.weldTolerance);
    info.collapsedTrianglesRemoved = static_cast<int>(dropCollapsedTriangles(mesh).size());
    info.unusedVerticesRemoved = removeUnusedVertices(mesh);
    if (mesh.triangles.empty())
        throw InputError(name + ": every triangle collapsed to a line or point when vertices closer "
                                "than the weld tolerance were merged; expected a solid");
    return std::move(mesh);
}

SurfaceMesh loadSurfaceMesh(const fs::path& path, const MeshLoadOptions& options,
                            MeshLoadReport* report) {
    const std::string name = path.string();
    std::error_code ec;
    if (fs::is_directory(path, ec))
        throw InputError(name + ": is a directory, expected a mesh file (" +
                         joined(meshFileExtensions()) + ")");
    if (!std::isfinite(options.scale) || options.scale <= 0.0)
        throw InputError(name + ": scale " + meshDetail::formatNumber(options.scale) +
                         " is not allowed, expected a finite number > 0");
    const std::string extension = lowerExtension(path);
    MeshLoadReport local;
    MeshLoadReport& info = report ? *report : local;
    info.format = extension;
    if (ownReader(extension))
        return prepareSurfaceMesh(parseMeshBytes(readInputFile(path, meshFileLimit, "mesh file"), name, extension),
                                  options, &info);
    checkInputFile(path, meshFileLimit, "mesh file");
    return prepareSurfaceMesh(readWithAssimp(path, extension), options, &info);
}

SurfaceMesh loadMesh(const fs::path& path, double scale) {
    MeshLoadOptions options;
    options.scale = scale;
    return loadSurfaceMesh(path, options);
}

// ---------------------------------------------------------------------------
// Writers

namespace {

// STL is little-endian whatever the host is.
void putLittleEndian(std::string& buffer, std::uint32_t value, int bytes) {
    for (int i = 0; i < bytes; ++i) buffer.push_back(static_cast<char>((value >> (8 * i)) & 0xFFu));
}

void putFloat(std::string& buffer, double value) {
    putLittleEndian(buffer, std::bit_cast<std::uint32_t>(static_cast<float>(value)), 4);
}

} // namespace

void writeStlBinary(const SurfaceMesh& mesh, const fs::path& path) {
    requireValidIndices(mesh);
    // 80-byte header; it must not start with "solid" or readers take it for ASCII.
    std::string buffer = "magFoam binary STL: " + mesh.source;
    buffer.resize(80, ' ');
    putLittleEndian(buffer, static_cast<std::uint32_t>(mesh.triangles.size()), 4);
    buffer.reserve(buffer.size() + 50 * mesh.triangles.size());
    for (int t = 0; t < mesh.nTriangles(); ++t) {
        const Vec3 n = mesh.normal(t);
        for (int i = 0; i < 3; ++i) putFloat(buffer, n[i]);
        for (int k = 0; k < 3; ++k)
            for (int i = 0; i < 3; ++i) putFloat(buffer, mesh.corner(t, k)[i]);
        putLittleEndian(buffer, 0, 2);  // attribute byte count
    }
    writeFileAtomically(path, buffer);
}

void writeObj(const SurfaceMesh& mesh, const fs::path& path) {
    requireValidIndices(mesh);
    std::ostringstream out;
    out << "# magFoam surface mesh: " << mesh.source << "\n";
    char line[128];
    for (const Vec3& p : mesh.vertices) {
        // 17 digits: the doubles read back bit for bit.
        std::snprintf(line, sizeof line, "v %.17g %.17g %.17g\n", p.x(), p.y(), p.z());
        out << line;
    }
    for (const auto& tri : mesh.triangles)  // OBJ counts from 1
        out << "f " << tri[0] + 1 << ' ' << tri[1] + 1 << ' ' << tri[2] + 1 << '\n';
    writeFileAtomically(path, out.str());
}

void writeSurfaceMesh(const SurfaceMesh& mesh, const fs::path& path) {
    const std::string ext = lowerExtension(path);
    if (ext == ".stl")
        writeStlBinary(mesh, path);
    else if (ext == ".obj")
        writeObj(mesh, path);
    else
        throw InputError(path.string() + ": cannot write format '" + ext +
                         "', expected .stl (binary) or .obj");
}

} // namespace mag
