// Formats read through assimp (STL, OBJ, 3MF, glTF, ...): the scene it returns
// is validated (mesh and index counts, finite coordinates) before it becomes a
// SurfaceMesh, so a malformed file that assimp half-accepts is an error, not a
// crash further on.
#include "AssimpReader.hpp"

#include <magFoam/Error.hpp>
#include <magFoam/MeshIO.hpp>

#include "MeshNumerics.hpp"

#include <assimp/Importer.hpp>
#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <cmath>
#include <limits>

namespace mag {

namespace {

std::string joined(const std::vector<std::string>& items) {
    std::string text;
    for (const auto& item : items) text += (text.empty() ? "" : " ") + item;
    return text;
}

// Triangulate polygons; assimp's own validation of what its importer built.
// Vertices are joined by our weld (weldVertices, a tolerance of 1e-9 of the
// mesh's size), not by aiProcess_JoinIdenticalVertices: assimp's tolerance
// scales with the bounding box and is far coarser, so it merged distinct
// vertices of thin parts (the rim of a fine 1 mm rod 0.1 m long) and the
// mesh came back open.
constexpr unsigned importFlags = aiProcess_Triangulate | aiProcess_ValidateDataStructure;

void configure(Assimp::Importer& importer) { importer.SetPropertyBool(AI_CONFIG_IMPORT_NO_SKELETON_MESHES, true); }

[[noreturn]] void noScene(const Assimp::Importer& importer, const std::string& name, const std::string& extension) {
    const std::string reason = importer.GetErrorString();
    if (!importer.IsExtensionSupported(extension)) {
        std::string all;
        importer.GetExtensionList(all);
        throw InputError(name + ": unsupported mesh format '" + extension + "' (assimp: " + reason +
                         "); supported: " + joined(meshFileExtensions()) + " (assimp also reads: " + all + ")");
    }
    throw InputError(name + ": cannot read the mesh (assimp: " + reason +
                     "); supported: " + joined(meshFileExtensions()));
}

// Gathers the triangles of every mesh the node tree places, with the node
// transforms applied (identity for STL and OBJ; scene formats such as glTF or
// COLLADA position their parts this way).
ParsedMesh fromScene(const aiScene& scene, const std::string& name) {
    ParsedMesh out;
    SurfaceMesh& mesh = out.mesh;
    mesh.source = name;
    constexpr std::size_t most = std::numeric_limits<int>::max();
    int depth = 0;
    auto gather = [&](auto&& self, const aiNode* node, const aiMatrix4x4& parent) -> void {
        if (++depth > 1000) throw InputError(name + ": the scene's node tree is more than 1000 levels deep");
        const aiMatrix4x4 placement = parent * node->mTransformation;
        // A mirroring placement turns the normals inward; reverse those triangles.
        const bool mirrored = placement.Determinant() < 0.0f;
        for (unsigned i = 0; i < node->mNumMeshes; ++i) {
            const unsigned m = node->mMeshes ? node->mMeshes[i] : scene.mNumMeshes;
            if (m >= scene.mNumMeshes || !scene.mMeshes || !scene.mMeshes[m])
                throw InputError(name + ": node '" + node->mName.C_Str() + "' refers to mesh " + std::to_string(m) +
                                 " of " + std::to_string(scene.mNumMeshes));
            const aiMesh& part = *scene.mMeshes[m];
            if (part.mNumVertices > 0 && !part.mVertices)
                throw InputError(name + ": mesh " + std::to_string(m) + " has vertices but no coordinates");
            if (mesh.vertices.size() + part.mNumVertices > most || mesh.triangles.size() + part.mNumFaces > most)
                throw InputError(name + ": more than 2147483647 vertices or triangles");
            const int offset = mesh.nVertices();
            for (unsigned v = 0; v < part.mNumVertices; ++v) {
                const aiVector3D& raw = part.mVertices[v];
                const aiVector3D p = placement * raw;
                const Vec3 q(p.x, p.y, p.z);
                if (!q.allFinite() || q.cwiseAbs().maxCoeff() > meshCoordinateLimit)
                    throw InputError(name + ": mesh " + std::to_string(m) + " vertex " + std::to_string(v) + " at " +
                                     formatPoint(Vec3(raw.x, raw.y, raw.z)) +
                                     ": expected finite coordinates of magnitude at most 1e30");
                mesh.vertices.push_back(q);
            }
            for (unsigned f = 0; f < part.mNumFaces; ++f) {
                const aiFace& face = part.mFaces[f];
                if (face.mNumIndices != 3 || !face.mIndices) {
                    ++out.pointsAndLinesIgnored;
                    continue;
                }
                int corner[3];
                for (int k = 0; k < 3; ++k) {
                    if (face.mIndices[k] >= part.mNumVertices)
                        throw InputError(name + ": mesh " + std::to_string(m) + " face " + std::to_string(f) +
                                         ": vertex index " + std::to_string(face.mIndices[k]) +
                                         " is out of range; the mesh has " + std::to_string(part.mNumVertices) +
                                         " vertices");
                    corner[k] = offset + static_cast<int>(face.mIndices[k]);
                }
                mesh.triangles.push_back(mirrored ? std::array<int, 3>{corner[0], corner[2], corner[1]}
                                                  : std::array<int, 3>{corner[0], corner[1], corner[2]});
            }
        }
        for (unsigned i = 0; i < node->mNumChildren; ++i)
            if (node->mChildren && node->mChildren[i]) self(self, node->mChildren[i], placement);
        --depth;
    };
    if (scene.mRootNode) gather(gather, scene.mRootNode, aiMatrix4x4());
    return out;
}

} // namespace

ParsedMesh parseWithAssimp(std::string_view bytes, const std::string& name, const std::string& extension) {
    Assimp::Importer importer;
    configure(importer);
    const std::string hint = extension.empty() || extension[0] != '.' ? extension : extension.substr(1);
    const aiScene* scene = importer.ReadFileFromMemory(bytes.data(), bytes.size(), importFlags, hint.c_str());
    if (!scene) noScene(importer, name, extension);
    return fromScene(*scene, name);
}

ParsedMesh readWithAssimp(const std::filesystem::path& path, const std::string& extension) {
    // From the file, not from memory: formats such as glTF or OBJ read
    // companion files (buffers, materials) next to it.
    Assimp::Importer importer;
    configure(importer);
    const aiScene* scene = importer.ReadFile(path.string(), importFlags);
    if (!scene) noScene(importer, path.string(), extension);
    return fromScene(*scene, path.string());
}

} // namespace mag
