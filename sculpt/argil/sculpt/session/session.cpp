#include "argil/sculpt/session/session.hpp"

#include <cstring>

#include "argil/io/files/model_files.hpp"
#include "argil/sculpt/detail/fnv_hash.hpp"

namespace argil::sculpt {
namespace {

std::string model_path(std::size_t k) { return "models[" + std::to_string(k) + "]"; }

/// Reads a model file; errors name the scene field that points at it.
Result<io::Model> read_for(const std::filesystem::path& file, const std::string& field) {
  Result<io::Model> read = io::read_model(file);
  if (!read.ok()) return Status::error(read.status().code, field + ": " + read.status().message);
  return read;
}

void hash_bytes(std::uint64_t& h, const void* data, std::size_t size) {
  h = fnv1a64(std::string_view(static_cast<const char*>(data), size), h);
}

/// The tool's shape; a B-spline tool is read from its file. `field` names the
/// scene's tool in errors ("tools[1]").
Result<ToolShape> read_tool_shape(const ToolOptions& tool, const std::string& field) {
  switch (tool.type) {
    case ToolType::sphere:
      return ToolShape{SphereToolShape{tool.radius}};
    case ToolType::point:
      return ToolShape{SphereToolShape{0.0}};
    case ToolType::bspline:
      break;
  }
  Result<io::Model> read = read_for(tool.file, field + ".file");
  if (!read.ok()) return read.status();
  const auto& faces = read.value().faces;
  if (tool.face >= static_cast<int>(faces.size())) {
    return Status::error(StatusCode::invalid_argument,
                         field + ".face: face " + std::to_string(tool.face) +
                             " is out of range: " + tool.file.string() + " has " +
                             std::to_string(faces.size()) + " faces");
  }
  return ToolShape{SurfaceToolShape{faces[static_cast<std::size_t>(tool.face)].surface}};
}

/// Model m of the scene: its whole file, and the faces it names (all when
/// none), as read.
Result<LoadedModel> load_model(const Scene& scene, std::size_t m) {
  const ModelOptions& spec = scene.models[m];
  Result<io::Model> read = read_for(spec.file, model_path(m) + ".file");
  if (!read.ok()) return read.status();
  LoadedModel loaded;
  loaded.spec = spec;
  loaded.file_model = std::move(read).value();
  const io::Model& file = loaded.file_model;
  loaded.initial.source_unit = file.source_unit;
  loaded.initial.metadata = file.metadata;
  loaded.initial.metadata["sculpt_scene"] = scene.source.string();
  loaded.initial.metadata["sculpt_model"] = spec.name;
  std::vector<int> wanted = spec.faces;
  if (wanted.empty()) {
    for (std::size_t f = 0; f < file.faces.size(); ++f) wanted.push_back(static_cast<int>(f));
  }
  for (std::size_t k = 0; k < wanted.size(); ++k) {
    const int f = wanted[k];
    if (f >= static_cast<int>(file.faces.size())) {
      return Status::error(StatusCode::invalid_argument,
                           model_path(m) + ".faces[" + std::to_string(k) + "]: face " +
                               std::to_string(f) + " is out of range: " + spec.file.string() +
                               " has " + std::to_string(file.faces.size()) + " faces");
    }
    Result<TrimRegion> trims = TrimRegion::create(file.faces[static_cast<std::size_t>(f)].loops);
    if (!trims.ok()) {
      return Status::error(trims.status().code, model_path(m) + " face " + std::to_string(f) +
                                                    ": " + trims.status().message);
    }
    loaded.initial.faces.push_back(file.faces[static_cast<std::size_t>(f)]);
    loaded.file_faces.push_back(f);
    loaded.trims.push_back(std::move(trims).value());
  }
  if (loaded.initial.faces.empty()) {
    return Status::error(StatusCode::invalid_argument,
                         model_path(m) + ".file: " + spec.file.string() + " has no faces");
  }
  return loaded;
}

}  // namespace

Result<Session> Session::create(const Scene& scene, const std::string& tool_name,
                                const std::vector<std::vector<Eigen::Vector3d>>& tool_paths,
                                const std::vector<std::string>& later_tools) {
  Session s;
  s.scene_ = scene;
  s.shapes_.resize(scene.tools.size());
  s.initial_tool_ = s.tool_index_ = scene.tool_index(tool_name);
  if (s.tool_index_ < 0) {
    return Status::error(StatusCode::invalid_argument,
                         "tool \"" + tool_name + "\" is not in the scene's tools");
  }
  // Refined for every tool the script holds: the widest reach, the finest
  // positive resolution (a point tool derives none).
  Result<ToolShape> widest = s.shape_of(s.tool_index_);
  if (!widest.ok()) return widest.status();
  double resolution = refinement_resolution(scene, widest.value());
  for (const std::string& name : later_tools) {
    const int index = scene.tool_index(name);
    if (index < 0) {
      return Status::error(StatusCode::invalid_argument,
                           "tool \"" + name + "\" is not in the scene's tools");
    }
    Result<ToolShape> shape = s.shape_of(index);
    if (!shape.ok()) return shape.status();
    if (tool_bound_radius(shape.value()) > tool_bound_radius(widest.value())) widest = shape;
    const double r = refinement_resolution(scene, shape.value());
    if (r > 0.0 && (resolution <= 0.0 || r < resolution)) resolution = r;
  }
  for (std::size_t m = 0; m < scene.models.size(); ++m) {
    Result<LoadedModel> loaded = load_model(scene, m);
    if (!loaded.ok()) return loaded.status();
    s.models_.push_back(std::move(loaded).value());
  }
  Result<std::vector<FaceRefinement>> refined =
      refine_faces(s.models_, widest.value(), resolution, tool_paths);
  if (!refined.ok()) return refined.status();
  s.refinements_ = std::move(refined).value();
  const Status built = s.rebuild_world();
  if (!built.ok()) return built;
  return s;
}

const ToolShape* Session::tool_shape(int index) const {
  if (index < 0 || index >= static_cast<int>(shapes_.size())) return nullptr;
  const std::optional<ToolShape>& shape = shapes_[static_cast<std::size_t>(index)];
  return shape ? &*shape : nullptr;
}

Result<ToolShape> Session::shape_of(int index) {
  std::optional<ToolShape>& shape = shapes_[static_cast<std::size_t>(index)];
  if (!shape) {
    Result<ToolShape> read = read_tool_shape(scene_.tools[static_cast<std::size_t>(index)],
                                             "tools[" + std::to_string(index) + "]");
    if (!read.ok()) return read.status();
    shape = std::move(read).value();
  }
  return *shape;
}

Status Session::hold_tool(int index) {
  Result<ToolShape> shape = shape_of(index);
  if (!shape.ok()) return shape.status();
  const Status set = world_->set_tool(shape.value());
  if (!set.ok()) {
    return Status::error(set.code, "tools[" + std::to_string(index) + "]: " + set.message);
  }
  tool_index_ = index;
  return Status::success();
}

Status Session::switch_tool(const std::string& name) {
  if (engaged_) {
    return Status::error(StatusCode::invalid_argument, "tool: a stroke is in progress");
  }
  const int index = scene_.tool_index(name);
  if (index < 0) {
    return Status::error(StatusCode::invalid_argument,
                         "tool: \"" + name + "\" is not in the scene's tools");
  }
  if (index == tool_index_) return Status::success();
  const Status held = hold_tool(index);
  if (!held.ok()) return held;
  tool_changes_.push_back({history_.size(), index});
  return Status::success();
}

void Session::forget_tool_changes_from(std::size_t at) {
  while (!tool_changes_.empty() && tool_changes_.back().at >= at) tool_changes_.pop_back();
}

Status Session::rebuild_world() {
  WorldOptions options;
  options.tolerance = scene_.tolerance;
  options.coupling = scene_.coupling;
  Result<ToolShape> shape = shape_of(initial_tool_);
  if (!shape.ok()) return shape.status();
  Result<HapticWorld> world = HapticWorld::create(shape.value(), options);
  if (!world.ok()) {
    return Status::error(world.status().code, "tools[" + std::to_string(initial_tool_) +
                                                  "] or coupling: " + world.status().message);
  }
  tool_index_ = initial_tool_;
  world_.emplace(std::move(world).value());
  body_owner_.clear();
  for (std::size_t m = 0; m < models_.size(); ++m) {
    LoadedModel& loaded = models_[m];
    loaded.bodies.clear();
    for (std::size_t f = 0; f < loaded.initial.faces.size(); ++f) {
      const BSplineSurface& surface = loaded.initial.faces[f].surface;
      const Result<int> body =
          loaded.spec.deformable
              ? world_->add_deformable(surface, loaded.spec.material, loaded.spec.boundary,
                                       loaded.spec.friction)
              : world_->add_rigid(surface, loaded.spec.friction);
      const Status trimmed =
          body.ok() ? world_->set_trim(body.value(), loaded.trims[f]) : body.status();
      if (!trimmed.ok()) {
        return Status::error(trimmed.code, model_path(m) + " face " +
                                               std::to_string(loaded.file_faces[f]) + ": " +
                                               trimmed.message);
      }
      loaded.bodies.push_back(body.value());
      body_owner_.emplace_back(static_cast<int>(m), static_cast<int>(f));
    }
    if (loaded.spec.deformable) {
      std::vector<int> body_of(loaded.file_model.faces.size(), -1);
      for (std::size_t f = 0; f < loaded.file_faces.size(); ++f)
        body_of[static_cast<std::size_t>(loaded.file_faces[f])] = loaded.bodies[f];
      for (const io::Edge& edge : loaded.file_model.topology.edges) {
        if (edge.degenerate || edge.uses.size() != 2) continue;
        const int a = body_of[edge.uses[0].face], b = body_of[edge.uses[1].face];
        if (a < 0 || b < 0) continue;
        const Result<int> j = world_->join(a, edge.uses[0].pcurve, b, edge.uses[1].pcurve);
        if (!j.ok()) return j.status();
      }
    }
  }
  return Status::success();
}

Result<TickReport> Session::advance(const DeviceSample& sample) {
  const TickResult r = world_->step(sample, time_step());
  if (!r.status.ok()) {
    return Status::error(r.status.code,
                         "tick " + std::to_string(sample.tick) + ": " + r.status.message);
  }
  TickReport report;
  report.tick = sample.tick;
  report.time = sample.t;
  report.force = r.force;
  report.clamped = r.clamped;
  report.proxy = r.proxy.X_WT.p;
  report.max_depth = r.max_depth;
  report.tool = tool_index_;
  for (std::size_t b = 0; b < r.body_contacts.size() && b < body_owner_.size(); ++b) {
    const auto [model, face] = body_owner_[b];
    for (const Contact& c : r.body_contacts[b]) {
      ContactRecord record;
      record.model = model;
      record.face =
          models_[static_cast<std::size_t>(model)].file_faces[static_cast<std::size_t>(face)];
      record.uv = c.uv_a;
      record.point = c.point;
      record.normal = c.normal;
      record.depth = c.depth;
      report.contacts.push_back(record);
    }
  }
  return report;
}

Result<TickReport> Session::step(const DeviceSample& sample) {
  if (sample.engaged && !engaged_) {
    stroke_start_ = history_.size();
    redo_.clear();  // a new stroke forks the history
  }
  Result<TickReport> report = advance(sample);
  if (!report.ok()) return report;
  history_.push_back(sample);
  if (!sample.engaged && engaged_) {
    strokes_.push_back({stroke_start_, history_.size()});
    report.value().stroke_finished = true;
  }
  engaged_ = sample.engaged;
  return report;
}

Status Session::undo() {
  if (engaged_) return Status::error(StatusCode::invalid_argument, "undo: a stroke is in progress");
  if (strokes_.empty()) return Status::error(StatusCode::invalid_argument, "undo: nothing to undo");
  const int held = tool_index_;
  const StrokeSpan stroke = strokes_.back();
  strokes_.pop_back();
  // What a redo needs to make the stroke again from the end of the stroke
  // before it: the samples in between and the stroke, and the tool changes.
  RedoEntry entry;
  entry.from = strokes_.empty() ? 0 : strokes_.back().end;
  entry.stroke_offset = stroke.start - entry.from;
  entry.samples.assign(history_.begin() + static_cast<std::ptrdiff_t>(entry.from),
                       history_.begin() + static_cast<std::ptrdiff_t>(stroke.end));
  for (const ToolChange& c : tool_changes_) {
    if (c.at >= entry.from && c.at <= stroke.start)
      entry.changes.push_back({c.at - entry.from, c.tool});
  }
  redo_.push_back(std::move(entry));
  history_.resize(stroke.start);
  forget_tool_changes_from(stroke.start + 1);
  engaged_ = false;
  // Exact restore: a fresh world replays the inputs that led to the stroke's start.
  if (const Status replayed = replay_history(); !replayed.ok()) return replayed;
  // The tool in hand stays: an undo takes back a stroke, not a tool change.
  return keep_holding(held);
}

Status Session::redo() {
  if (engaged_) return Status::error(StatusCode::invalid_argument, "redo: a stroke is in progress");
  if (redo_.empty()) return Status::error(StatusCode::invalid_argument, "redo: nothing to redo");
  const int held = tool_index_;
  RedoEntry entry = std::move(redo_.back());
  redo_.pop_back();
  // Back to the end of the stroke before it (its redo, if it was undone too,
  // came first: redo_ is a stack), dropping what came since, then the
  // original samples and tool changes up to and through the stroke: exactly
  // the state the stroke finished with.
  forget_tool_changes_from(entry.from);
  if (history_.size() != entry.from) {
    history_.resize(entry.from);
    if (const Status replayed = replay_history(); !replayed.ok()) return replayed;
  } else if (const int before = tool_at(entry.from); before != tool_index_) {
    // Only tool changes at its end were dropped: the world is right, the hand is not.
    if (const Status h = hold_tool(before); !h.ok()) return h;
  }
  std::size_t change = 0;
  for (std::size_t i = 0; i < entry.samples.size(); ++i) {
    for (; change < entry.changes.size() && entry.changes[change].at == i; ++change) {
      if (const Status h = hold_tool(entry.changes[change].tool); !h.ok()) return h;
      tool_changes_.push_back({history_.size(), entry.changes[change].tool});
    }
    const Result<TickReport> r = advance(entry.samples[i]);
    if (!r.ok()) return r.status();
    history_.push_back(entry.samples[i]);
  }
  strokes_.push_back({entry.from + entry.stroke_offset, history_.size()});
  engaged_ = false;
  return keep_holding(held);
}

Status Session::keep_holding(int tool) {
  if (tool == tool_index_) return Status::success();
  if (const Status h = hold_tool(tool); !h.ok()) return h;
  tool_changes_.push_back({history_.size(), tool});
  return Status::success();
}

Status Session::replay_history() {
  const Status built = rebuild_world();
  if (!built.ok()) return built;
  std::size_t change = 0;
  const auto hold_changes_at = [&](std::size_t at) {
    for (; change < tool_changes_.size() && tool_changes_[change].at == at; ++change) {
      const Status held = hold_tool(tool_changes_[change].tool);
      if (!held.ok()) return held;
    }
    return Status::success();
  };
  for (std::size_t i = 0; i < history_.size(); ++i) {
    if (const Status held = hold_changes_at(i); !held.ok()) return held;
    const Result<TickReport> r = advance(history_[i]);
    if (!r.ok()) return r.status();
  }
  return hold_changes_at(history_.size());
}

int Session::tool_at(std::size_t at) const {
  int tool = initial_tool_;
  for (const ToolChange& c : tool_changes_)
    if (c.at <= at) tool = c.tool;
  return tool;
}

io::Model Session::current_faces(int index) const {
  const LoadedModel& loaded = models_[static_cast<std::size_t>(index)];
  io::Model model = loaded.initial;
  for (std::size_t f = 0; f < model.faces.size(); ++f) {
    model.faces[f].surface = world_->surface(loaded.bodies[f]);
  }
  return model;
}

io::Model Session::current_file_model(int index) const {
  const LoadedModel& loaded = models_[static_cast<std::size_t>(index)];
  // A copy of the whole io::Model, so fields beyond the faces come along.
  io::Model model = loaded.file_model;
  model.metadata = loaded.initial.metadata;
  for (std::size_t f = 0; f < loaded.file_faces.size(); ++f) {
    model.faces[static_cast<std::size_t>(loaded.file_faces[f])].surface =
        world_->surface(loaded.bodies[f]);
  }
  return model;
}

std::uint64_t Session::state_hash() const {
  std::uint64_t h = fnv1a64("argil.session");
  for (int b = 0; b < world_->body_count(); ++b) {
    const ControlNet& points = world_->surface(b).control_points;
    hash_bytes(h, points.data(), static_cast<std::size_t>(points.size()) * sizeof(double));
    if (const DeformableBody* body = world_->deformable(b)) {
      hash_bytes(h, body->rest_control_points().data(),
                 static_cast<std::size_t>(body->rest_control_points().size()) * sizeof(double));
      hash_bytes(h, body->velocities().data(),
                 static_cast<std::size_t>(body->velocities().size()) * sizeof(double));
    }
  }
  const ProxyState& proxy = world_->proxy();
  hash_bytes(h, &tool_index_, sizeof tool_index_);
  hash_bytes(h, proxy.X_WT.p.data(), 3 * sizeof(double));
  hash_bytes(h, proxy.v_WT.data(), 3 * sizeof(double));
  return h;
}

}  // namespace argil::sculpt
