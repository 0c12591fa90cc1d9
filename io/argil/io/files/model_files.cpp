#include "argil/io/files/model_files.hpp"

#include <cctype>

#include "argil/io/cad/cad_exchange.hpp"
#include "argil/io/json/json_format.hpp"
#include "argil/io/mesh/mesh_export.hpp"

namespace argil::io {
namespace {

bool is_json(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".json";
}

Status unknown_extension(const std::filesystem::path& path, const char* what) {
  return Status::error(StatusCode::unsupported,
                       path.string() + ": cannot " + what +
                           " this file type (supported: " + supported_extensions() + ")");
}

}  // namespace

const char* supported_extensions() {
  return "read .step .stp .iges .igs .json; write those and .stl .obj .ply .glb";
}

Result<Model> read_model(const std::filesystem::path& path) {
  if (const auto cad = cad_format_for(path)) return read_cad(path, *cad);
  if (is_json(path)) return read_json(path);
  return unknown_extension(path, "read");
}

Status write_model(const Model& model, const std::filesystem::path& path,
                   const WriteOptions& options) {
  if (const auto cad = cad_format_for(path)) return write_cad(model, path, *cad, options.cad);
  if (is_json(path)) return write_json(model, path);
  if (const auto mesh_format = mesh_format_for(path)) {
    Result<TriangleMesh> mesh = tessellate(model, options.tessellation);
    if (!mesh.ok()) {
      return Status::error(mesh.status().code, path.string() + ": " + mesh.status().message);
    }
    if (options.cad.warnings != nullptr) {
      for (const std::string& w : mesh.value().warnings)
        options.cad.warnings->push_back(path.string() + ": " + w);
    }
    return write_mesh(mesh.value(), path, *mesh_format);
  }
  return unknown_extension(path, "write");
}

}  // namespace argil::io
