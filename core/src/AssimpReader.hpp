// Private: assimp reading a mesh from its file (MeshIO.cpp); from memory is
// parseWithAssimp (MeshFormats.hpp).
#pragma once

#include <magFoam/MeshFormats.hpp>

#include <filesystem>
#include <string>

namespace mag {

ParsedMesh readWithAssimp(const std::filesystem::path& path, const std::string& extension);

} // namespace mag
