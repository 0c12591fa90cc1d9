#pragma once
// CAD exchange: STEP and IGES through OpenCASCADE. Import turns every face into a
// FaceRecord; export writes each record as a B-spline face with its trims.
// OpenCASCADE's console output is silenced and none of its exceptions escape.

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "argil/core/base/status.hpp"
#include "argil/io/model/model.hpp"

namespace argil::io {

enum class CadFormat { step, iges };

/// The format for ".step"/".stp" or ".iges"/".igs" (case-insensitive), if any.
std::optional<CadFormat> cad_format_for(const std::filesystem::path& path);

/// How read_cad() protects the caller from OpenCASCADE.
struct CadReadOptions {
  /// Read in a child process, so that a crash, hang or memory blow-up inside
  /// OpenCASCADE on a malformed file becomes an error status (docs/robustness.md).
  /// false: read in this process (faster by one fork; for debugging).
  bool isolate = true;
  /// The child is stopped after this long [s].
  double time_limit_s = 600.0;
  /// Address-space limit of the child [MB]; 0: none. Not applied in
  /// AddressSanitizer builds (its shadow memory alone exceeds any such limit).
  std::size_t memory_limit_mb = 8192;
};

/// Reads every face of a STEP or IGES file, in OpenCASCADE's TopExp_Explorer
/// order, into millimetres.
/// - B-spline faces keep their surface and parametrisation; periodic surfaces
///   become clamped (same geometry, same parameters).
/// - Other surfaces (planes, cylinders, cones, tori, revolutions, ...) are
///   converted exactly to rational B-splines over the face's parameter range by
///   BRepBuilderAPI_NurbsConvert, which also re-expresses the trim curves in the
///   new parametrisation (circles in u become rational quadratics, so u is no
///   longer the angle). Offset surfaces are approximated by that conversion.
/// - Trim loops come from the edges' parameter-space curves in wire order; the
///   outer loop is counter-clockwise. A face bounded by exactly its domain
///   boundary is recorded untrimmed.
/// Errors name the file and, where known, the entity: missing, empty, truncated
/// or malformed files, files without faces, unsupported entities, and (isolated
/// reads) OpenCASCADE crashing, running out of memory or over the time limit.
Result<Model> read_cad(const std::filesystem::path& path, CadFormat format,
                       const CadReadOptions& options = {});

/// How write_cad() builds the faces it writes.
struct CadWriteOptions {
  /// eps [mm], the length under which the caller treats two points as one (a
  /// session's contact tolerance); 0: none given. The export tolerance is
  /// export_tolerance(model, tolerance_mm).
  double tolerance_mm = 0.0;
  /// Read the written file back with OpenCASCADE's own reader before it
  /// replaces the target, and refuse it unless every face comes back as one
  /// BRepCheck-valid face. false: skip that read (a faster export whose faces
  /// passed BRepCheck as built, but are not known to survive the file).
  bool read_back = true;
  /// Receives one line when a model with a B-rep could not be written whole
  /// (its shared edges torn apart by faces sculpted independently, say) and its
  /// faces were written one by one instead; may be null.
  std::vector<std::string>* warnings = nullptr;
};

/// Export tolerances relative to the model size (the diagonal of model_box()).
inline constexpr double kExportRelativeTolerance = 1e-7;
/// The smallest export tolerance [mm]: OpenCASCADE's Precision::Confusion(),
/// below which its algorithms treat lengths as zero.
inline constexpr double kMinExportTolerance = 1e-7;

/// The tolerance write_cad() builds edges at [mm]: the accuracy the 3D edge
/// curves are approximated to, the largest 3D image a trim curve may have and
/// still be a degenerated edge, and the least tolerance of any edge or vertex:
/// min(eps, kExportRelativeTolerance * model size), or the relative term alone
/// when eps <= 0, and never below kMinExportTolerance.
double export_tolerance(const Model& model, double eps_mm);

/// Writes all faces as B-spline faces in millimetres (declared in the file):
/// STEP as B_SPLINE_SURFACE_WITH_KNOTS (rational: the complex entity) in
/// ADVANCED_FACE, IGES as entity 128 inside 144. Numbers carry 17 significant
/// digits, so knots, weights and control points read back bit-exactly (values
/// below 1e-99 in magnitude are written as 0).
/// Each face keeps its (u, v) trims; its edges, vertices and tolerances are
/// built from the surface as it is (docs/io.md, "Export"). Every face must pass
/// BRepCheck_Analyzer as built and, with `options.read_back`, again as
/// OpenCASCADE reads it from the written file. Otherwise nothing is written
/// and the error (invalid_surface) names every failing face, its index, source
/// entity and name, with what BRepCheck_Analyzer reported per loop, curve or
/// edge. The write is atomic: the target is complete or untouched.
Status write_cad(const Model& model, const std::filesystem::path& path, CadFormat format,
                 const CadWriteOptions& options = {});

}  // namespace argil::io
