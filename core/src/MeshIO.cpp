// Mesh files: assimp for reading, own code for writing binary STL and OBJ.
#include <magFoam/MeshIO.hpp>

#include <magFoam/Error.hpp>

#include "MeshNumerics.hpp"

#include <assimp/Importer.hpp>
#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>

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

// "supported: .stl .obj .ply .off (assimp also reads: *.3mf;*.dae;...)"
std::string supportedFormats(const Assimp::Importer& importer) {
    std::string all;
    importer.GetExtensionList(all);
    return "supported: " + joined(meshFileExtensions()) + " (assimp also reads: " + all + ")";
}

} // namespace

std::vector<std::string> meshFileExtensions() { return {".stl", ".obj", ".ply", ".off"}; }

SurfaceMesh loadSurfaceMesh(const fs::path& path, const MeshLoadOptions& options,
                            MeshLoadReport* report) {
    const std::string name = path.string();
    std::error_code ec;
    if (!fs::exists(path, ec)) throw InputError(name + ": file not found");
    if (fs::is_directory(path, ec))
        throw InputError(name + ": is a directory, expected a mesh file (" +
                         joined(meshFileExtensions()) + ")");
    if (!std::isfinite(options.scale) || options.scale <= 0.0)
        throw InputError(name + ": scale " + meshDetail::formatNumber(options.scale) +
                         " is not allowed, expected a finite number > 0");

    MeshLoadReport local;
    MeshLoadReport& info = report ? *report : local;
    info = MeshLoadReport{};
    info.format = lowerExtension(path);

    // Triangulate polygons; join identical vertices where the format allows it
    // (our weld below does the rest).
    Assimp::Importer importer;
    importer.SetPropertyBool(AI_CONFIG_IMPORT_NO_SKELETON_MESHES, true);
    const aiScene* scene =
        importer.ReadFile(name, aiProcess_Triangulate | aiProcess_JoinIdenticalVertices);
    if (!scene) {
        const std::string reason = importer.GetErrorString();
        if (!importer.IsExtensionSupported(info.format))
            throw InputError(name + ": unsupported mesh format '" + info.format + "' (assimp: " +
                             reason + "); " + supportedFormats(importer));
        throw InputError(name + ": cannot read the mesh (assimp: " + reason +
                         "); supported: " + joined(meshFileExtensions()));
    }

    // Gather the triangles of every mesh the node tree places, with the node
    // transforms applied (identity for STL, OBJ, PLY, OFF; scene formats such as
    // glTF or COLLADA position their parts this way).
    SurfaceMesh mesh;
    mesh.source = name;
    auto gather = [&](auto&& self, const aiNode* node, const aiMatrix4x4& parent) -> void {
        const aiMatrix4x4 placement = parent * node->mTransformation;
        // A mirroring placement turns the normals inward; reverse those triangles.
        const bool mirrored = placement.Determinant() < 0.0f;
        for (unsigned i = 0; i < node->mNumMeshes; ++i) {
            const aiMesh* part = scene->mMeshes[node->mMeshes[i]];
            const int offset = mesh.nVertices();
            for (unsigned v = 0; v < part->mNumVertices; ++v) {
                const aiVector3D p = placement * part->mVertices[v];
                mesh.vertices.emplace_back(p.x, p.y, p.z);
            }
            for (unsigned f = 0; f < part->mNumFaces; ++f) {
                const aiFace& face = part->mFaces[f];
                if (face.mNumIndices != 3) {
                    ++info.pointsAndLinesIgnored;
                    continue;
                }
                const int a = offset + static_cast<int>(face.mIndices[0]);
                const int b = offset + static_cast<int>(face.mIndices[1]);
                const int c = offset + static_cast<int>(face.mIndices[2]);
                mesh.triangles.push_back(mirrored ? std::array<int, 3>{a, c, b}
                                                  : std::array<int, 3>{a, b, c});
            }
        }
        for (unsigned i = 0; i < node->mNumChildren; ++i) self(self, node->mChildren[i], placement);
    };
    if (scene->mRootNode) gather(gather, scene->mRootNode, aiMatrix4x4());
    info.verticesRead = mesh.nVertices();
    info.trianglesRead = mesh.nTriangles();
    if (mesh.triangles.empty())
        throw InputError(name + ": the file holds no triangles" +
                         (info.pointsAndLinesIgnored
                              ? " (only " + std::to_string(info.pointsAndLinesIgnored) +
                                    " points or lines)"
                              : std::string()) +
                         ", expected a closed triangle surface");

    if (options.scale != 1.0) scale(mesh, options.scale);
    info.verticesMerged = weldVertices(mesh, options.weldTolerance);
    info.collapsedTrianglesRemoved = static_cast<int>(dropCollapsedTriangles(mesh).size());
    info.unusedVerticesRemoved = removeUnusedVertices(mesh);
    if (mesh.triangles.empty())
        throw InputError(name + ": every triangle collapsed to a line or point when vertices closer "
                                "than the weld tolerance were merged; expected a solid");
    return mesh;
}

SurfaceMesh loadMesh(const fs::path& path, double scale) {
    MeshLoadOptions options;
    options.scale = scale;
    return loadSurfaceMesh(path, options);
}

// ---------------------------------------------------------------------------
// Writers

namespace {

std::ofstream openForWriting(const fs::path& path, std::ios::openmode mode) {
    std::ofstream out(path, mode);
    if (!out) throw InputError(path.string() + ": cannot open the file for writing");
    return out;
}

void finishWriting(std::ofstream& out, const fs::path& path) {
    out.flush();
    if (!out) throw InputError(path.string() + ": writing the file failed");
}

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
    std::ofstream out = openForWriting(path, std::ios::binary | std::ios::trunc);
    out.write(buffer.data(), static_cast<std::streamsize>(buffer.size()));
    finishWriting(out, path);
}

void writeObj(const SurfaceMesh& mesh, const fs::path& path) {
    requireValidIndices(mesh);
    std::ofstream out = openForWriting(path, std::ios::trunc);
    out << "# magFoam surface mesh: " << mesh.source << "\n";
    char line[128];
    for (const Vec3& p : mesh.vertices) {
        // 17 digits: the doubles read back bit for bit.
        std::snprintf(line, sizeof line, "v %.17g %.17g %.17g\n", p.x(), p.y(), p.z());
        out << line;
    }
    for (const auto& tri : mesh.triangles)  // OBJ counts from 1
        out << "f " << tri[0] + 1 << ' ' << tri[1] + 1 << ' ' << tri[2] + 1 << '\n';
    finishWriting(out, path);
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
