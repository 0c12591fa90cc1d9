#pragma once
// Triangle meshes written through assimp, for viewers (never for CAD exchange).

#include <filesystem>
#include <optional>

#include "argil/core/base/status.hpp"
#include "argil/io/mesh/tessellate.hpp"

namespace argil::io {

/// Mesh file formats. STL and PLY are written binary (float32 coordinates),
/// OBJ as text with 9 significant digits (float32-exact), glTF 2 as .glb.
/// STL stores facet normals only; the others store the surface normals.
enum class MeshFormat { stl, obj, ply, glb };

/// The format for ".stl", ".obj", ".ply" or ".glb" (case-insensitive), if any.
std::optional<MeshFormat> mesh_format_for(const std::filesystem::path& path);

/// Writes the mesh atomically: one mesh per face, each in a node named after
/// the face (TriangleMesh::face_names), one material. glb is in metres with +Y
/// up, as glTF 2.0 requires (x, y, z [mm] are written as x, z, -y [m]); the
/// other formats keep millimetres and +Z up. Triangles with no area once
/// stored in float32 are left out. Fails on an empty mesh or when assimp
/// reports an error.
Status write_mesh(const TriangleMesh& mesh, const std::filesystem::path& path, MeshFormat format);

}  // namespace argil::io
