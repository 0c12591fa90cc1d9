// The one translation unit that uses assimp.
#include <assimp/material.h>
#include <assimp/scene.h>
#include <assimp/Exporter.hpp>

#include <algorithm>
#include <cctype>
#include <exception>
#include <string>
#include <string_view>
#include <vector>

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

// glTF 2.0 says metres with +Y up; argil holds millimetres with +Z up. The
// other formats carry no unit or axis convention and are written as held.
struct Frame {
  double scale = 1.0;
  bool y_up = false;
  aiVector3D apply(const Eigen::Vector3d& p, double s) const {
    const Eigen::Vector3d q = y_up ? Eigen::Vector3d(p.x(), p.z(), -p.y()) : p;
    return {static_cast<ai_real>(s * q.x()), static_cast<ai_real>(s * q.y()),
            static_cast<ai_real>(s * q.z())};
  }
};

Frame frame_for(MeshFormat format) {
  if (format == MeshFormat::glb) return {1e-3, true};
  return {};
}

/// True when the triangle has no area once stored: float32 rounding (or a
/// surface's collapsed edge) put two corners on one point, or all three on a
/// line. Viewers and validators reject such triangles.
bool degenerate(const aiVector3D& a, const aiVector3D& b, const aiVector3D& c) {
  const aiVector3D n = (b - a) ^ (c - a);
  return n.x == 0 && n.y == 0 && n.z == 0;
}

/// One assimp mesh: the triangles of one face, its vertices renumbered.
/// `local` (one slot per vertex of `mesh`, all -1) is scratch space shared by
/// the faces, left all -1 again.
aiMesh* face_mesh(const TriangleMesh& mesh, const std::vector<Eigen::Index>& triangles,
                  const std::string& name, const Frame& frame, std::vector<int>& local) {
  std::vector<Eigen::Index> vertices;
  std::vector<Eigen::Index> kept;
  for (Eigen::Index t : triangles) {
    const auto corner = [&](int c) {
      return frame.apply(mesh.positions.row(mesh.triangles(t, c)).transpose(), frame.scale);
    };
    if (degenerate(corner(0), corner(1), corner(2))) continue;
    kept.push_back(t);
    for (int c = 0; c < 3; ++c) {
      int& slot = local[static_cast<std::size_t>(mesh.triangles(t, c))];
      if (slot < 0) {
        slot = static_cast<int>(vertices.size());
        vertices.push_back(mesh.triangles(t, c));
      }
    }
  }
  if (kept.empty()) return nullptr;  // nothing was numbered
  auto* out = new aiMesh();
  out->mName = aiString(name);
  out->mMaterialIndex = 0;
  out->mPrimitiveTypes = aiPrimitiveType_TRIANGLE;
  out->mNumVertices = static_cast<unsigned>(vertices.size());
  out->mVertices = new aiVector3D[vertices.size()];
  out->mNormals = new aiVector3D[vertices.size()];
  out->mTextureCoords[0] = new aiVector3D[vertices.size()];
  out->mNumUVComponents[0] = 2;
  for (std::size_t v = 0; v < vertices.size(); ++v) {
    out->mVertices[v] = frame.apply(mesh.positions.row(vertices[v]).transpose(), frame.scale);
    out->mNormals[v] = frame.apply(mesh.normals.row(vertices[v]).transpose(), 1.0);
    // The face's own (u, v): a viewer reads the surface parameters of a picked
    // point, and assimp's glTF export, which joins vertices closer than 1e-4
    // of the mesh's size, keeps apart those at different parameters (where a
    // face collapses to a point, its vertices coincide but their (u, v) do not).
    out->mTextureCoords[0][v] = aiVector3D(static_cast<ai_real>(mesh.uv(vertices[v], 0)),
                                           static_cast<ai_real>(mesh.uv(vertices[v], 1)), 0);
  }
  out->mNumFaces = static_cast<unsigned>(kept.size());
  out->mFaces = new aiFace[kept.size()];
  for (std::size_t f = 0; f < kept.size(); ++f) {
    aiFace& face = out->mFaces[f];
    face.mNumIndices = 3;
    face.mIndices = new unsigned[3];
    for (int c = 0; c < 3; ++c)
      face.mIndices[c] =
          static_cast<unsigned>(local[static_cast<std::size_t>(mesh.triangles(kept[f], c))]);
  }
  for (Eigen::Index v : vertices) local[static_cast<std::size_t>(v)] = -1;
  return out;
}

// An aiScene owns its arrays and frees them in its destructor. The face
// meshes are handed to it once all are made.
void fill_scene(const TriangleMesh& mesh, MeshFormat format, aiScene& scene) {
  auto* material = new aiMaterial();
  const aiString material_name("argil surface");
  material->AddProperty(&material_name, AI_MATKEY_NAME);
  const aiColor3D grey(0.7f, 0.7f, 0.72f);
  material->AddProperty(&grey, 1, AI_MATKEY_COLOR_DIFFUSE);
  scene.mMaterials = new aiMaterial* [1] { material };
  scene.mNumMaterials = 1;

  // Triangles by face, in order (tessellate() concatenates face after face).
  std::vector<std::vector<Eigen::Index>> by_face;
  for (Eigen::Index t = 0; t < mesh.triangles.rows(); ++t) {
    const auto face =
        static_cast<std::size_t>(mesh.vertex_face[static_cast<std::size_t>(mesh.triangles(t, 0))]);
    if (face >= by_face.size()) by_face.resize(face + 1);
    by_face[face].push_back(t);
  }
  const Frame frame = frame_for(format);
  std::vector<int> local(static_cast<std::size_t>(mesh.positions.rows()), -1);
  std::vector<aiMesh*> meshes;
  for (std::size_t f = 0; f < by_face.size(); ++f) {
    const std::string name =
        f < mesh.face_names.size() ? mesh.face_names[f] : "face " + std::to_string(f);
    if (aiMesh* m = face_mesh(mesh, by_face[f], name, frame, local)) meshes.push_back(m);
  }
  scene.mRootNode = new aiNode("argil");
  if (meshes.empty()) return;
  scene.mNumMeshes = static_cast<unsigned>(meshes.size());
  scene.mMeshes = new aiMesh*[meshes.size()];
  std::copy(meshes.begin(), meshes.end(), scene.mMeshes);
  // One node per face, named like its mesh, so a viewer can tell faces apart.
  scene.mRootNode->mNumChildren = scene.mNumMeshes;
  scene.mRootNode->mChildren = new aiNode*[meshes.size()];
  for (unsigned k = 0; k < scene.mNumMeshes; ++k) {
    auto* node = new aiNode(scene.mMeshes[k]->mName.C_Str());
    node->mParent = scene.mRootNode;
    node->mNumMeshes = 1;
    node->mMeshes = new unsigned[1]{k};
    scene.mRootNode->mChildren[k] = node;
  }
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
    fill_scene(mesh, format, scene);
    if (scene.mNumMeshes == 0) {
      return Status::error(StatusCode::invalid_argument,
                           path.string() + ": every triangle of the mesh has zero area");
    }
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
