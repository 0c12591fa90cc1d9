// The one translation unit that uses assimp.
#include <assimp/material.h>
#include <assimp/scene.h>
#include <assimp/Exporter.hpp>

#include <algorithm>
#include <cctype>
#include <exception>
#include <string>
#include <string_view>

#include "argil/io/base/atomic_write.hpp"
#include "argil/io/mesh/mesh_export.hpp"

namespace argil::io {
namespace {

const char* assimp_format_id(MeshFormat format) {
  switch (format) {
    case MeshFormat::stl:
      return "stlb";
    case MeshFormat::obj:
      return "objnomtl";  // one file: no .mtl written beside it
    case MeshFormat::ply:
      return "plyb";
    case MeshFormat::glb:
      return "glb2";  // "glb" would be glTF 1.0
  }
  return "";
}

// An aiScene owns its arrays and frees them in its destructor.
void fill_scene(const TriangleMesh& mesh, aiScene& scene) {
  auto* material = new aiMaterial();
  const aiString name("argil surface");
  material->AddProperty(&name, AI_MATKEY_NAME);
  const aiColor3D grey(0.7f, 0.7f, 0.72f);
  material->AddProperty(&grey, 1, AI_MATKEY_COLOR_DIFFUSE);
  scene.mMaterials = new aiMaterial* [1] { material };
  scene.mNumMaterials = 1;

  auto* out = new aiMesh();
  out->mName = aiString("argil");
  out->mMaterialIndex = 0;
  out->mPrimitiveTypes = aiPrimitiveType_TRIANGLE;
  const auto vertex_count = static_cast<unsigned>(mesh.positions.rows());
  out->mNumVertices = vertex_count;
  out->mVertices = new aiVector3D[vertex_count];
  out->mNormals = new aiVector3D[vertex_count];
  for (unsigned v = 0; v < vertex_count; ++v) {
    const auto r = static_cast<Eigen::Index>(v);
    out->mVertices[v] = aiVector3D(static_cast<ai_real>(mesh.positions(r, 0)),
                                   static_cast<ai_real>(mesh.positions(r, 1)),
                                   static_cast<ai_real>(mesh.positions(r, 2)));
    out->mNormals[v] = aiVector3D(static_cast<ai_real>(mesh.normals(r, 0)),
                                  static_cast<ai_real>(mesh.normals(r, 1)),
                                  static_cast<ai_real>(mesh.normals(r, 2)));
  }
  const auto face_count = static_cast<unsigned>(mesh.triangles.rows());
  out->mNumFaces = face_count;
  out->mFaces = new aiFace[face_count];
  for (unsigned f = 0; f < face_count; ++f) {
    aiFace& face = out->mFaces[f];
    face.mNumIndices = 3;
    face.mIndices = new unsigned[3];
    for (int c = 0; c < 3; ++c) {
      face.mIndices[c] = static_cast<unsigned>(mesh.triangles(static_cast<Eigen::Index>(f), c));
    }
  }
  scene.mMeshes = new aiMesh* [1] { out };
  scene.mNumMeshes = 1;
  scene.mRootNode = new aiNode("argil");
  scene.mRootNode->mMeshes = new unsigned[1]{0};
  scene.mRootNode->mNumMeshes = 1;
}

}  // namespace

std::optional<MeshFormat> mesh_format_for(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".stl") return MeshFormat::stl;
  if (ext == ".obj") return MeshFormat::obj;
  if (ext == ".ply") return MeshFormat::ply;
  if (ext == ".glb") return MeshFormat::glb;
  return std::nullopt;
}

Status write_mesh(const TriangleMesh& mesh, const std::filesystem::path& path, MeshFormat format) {
  if (mesh.triangles.rows() == 0) {
    return Status::error(StatusCode::invalid_argument,
                         path.string() + ": the mesh has no triangles (everything trimmed away?)");
  }
  std::string bytes;
  try {
    aiScene scene;
    fill_scene(mesh, scene);
    Assimp::Exporter exporter;
    const aiExportDataBlob* blob = exporter.ExportToBlob(&scene, assimp_format_id(format));
    if (blob == nullptr) {
      return Status::error(StatusCode::io_error,
                           path.string() + ": assimp export failed: " + exporter.GetErrorString());
    }
    bytes.assign(static_cast<const char*>(blob->data), blob->size);
  } catch (const std::exception& e) {
    return Status::error(StatusCode::io_error,
                         path.string() + ": assimp export failed: " + e.what());
  }
  return write_bytes_atomically(path, bytes);
}

}  // namespace argil::io
