// The ISO 14649 interpreter. See interpreter.hpp, and docs/interpreter.md for the decisions.

#include "ncpost/stepnc/interpreter.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <unordered_map>
#include <unordered_set>
#include <utility>

#include "features/generator.hpp"
#include "features/report.hpp"
#include "ncpost/stepnc/curves.hpp"
#include "ncpost/stepnc/geometry.hpp"
#include "ncpost/stepnc/machine.hpp"
#include "ncpost/stepnc/program_info.hpp"
#include "units.hpp"

namespace ncpost::stepnc {
namespace {

using detail::Frame;
using detail::Machine;
using detail::Segment;
using detail::Vec3;
using p21::Instance;
using p21::Value;

// ISO 14649 states feed rates in m/s (speed_measure); the canonical program uses mm/min.
constexpr double kFeedToMmPerMin = 60000.0;

// A three-axis pose (generated paths carry no tool axis).
canon::Pose flat_pose(Vec3 p) {
  return {p.x, p.y, p.z, std::nullopt, std::nullopt};
}

class Interpreter {
 public:
  Interpreter(const p21::Model& model, const AttributeReader& attributes, canon::Sink& sink,
              const InterpretOptions& options)
      : m_(model),
        a_(attributes),
        machine_(sink),
        options_(options),
        geometry_(model, attributes, diagnostics_),
        curves_(geometry_, options.arc_tolerance) {}

  InterpretResult run();

 private:
  // ---- helpers ----
  void emit(const canon::Call& c) { machine_.emit(c); }
  std::string name(const Instance& i) {
    const auto v = geometry_.get(i, "its_id");
    return v && v->kind() == p21::ValueKind::String ? m_.as_string(*v) : std::string();
  }
  canon::Entity entity(const Instance& i) { return {i.id, std::string(m_.type_name(i)), name(i)}; }
  const Instance* ref(const Instance& owner, std::string_view attribute, std::string_view type,
                      bool optional = false) {
    const auto v = geometry_.get(owner, attribute);
    if (optional && (!v || v->is_omitted())) return nullptr;
    return geometry_.instance(v, type, &owner, attribute);
  }
  // True once an error has been reported and the options say to stop there.
  bool stopped() {
    if (options_.cancel != nullptr && options_.cancel->load(std::memory_order_relaxed))
      stopped_ = true;
    if (!options_.stop_at_first_error) return stopped_;
    for (; errors_checked_ < diagnostics_.size(); ++errors_checked_)
      if (diagnostics_[errors_checked_].severity == diag::Severity::Error) stopped_ = true;
    return stopped_;
  }
  // The schema does not make `attribute` of the instance's entity OPTIONAL.
  bool required(const Instance& at, std::string_view attribute) const {
    const express::Entity* entity = geometry_.attributes().entity(at);
    if (entity == nullptr) return false;
    const auto index = entity->attribute_index(attribute);
    return index && !entity->attributes[*index].optional;
  }
  void note(const Instance& at, std::string message) {
    geometry_.error(diag::Code::StepncNote, at, std::move(message));
  }
  void not_implemented(const Instance& at, const std::string& what) {
    geometry_.error(diag::Code::StepncNotImplemented, at,
                    detail::describe(m_, at) + ": " + what + " is not implemented");
  }

  // ---- program ----
  void executable(const Instance& e, unsigned depth);
  void elements(const Instance& owner, std::string_view attribute, unsigned depth);
  void workingstep(const Instance& ws);
  void rapid_movement(const Instance& rm);
  void nc_function(const Instance& f);
  void set_up(const Instance& setup);

  // ---- machine state ----
  bool tool(const Instance& tool_instance);
  void technology(const Instance* tech);
  void machine_functions(const Instance* functions);
  void toolpaths(const Instance* list, const Frame& frame, bool rapid);
  void generated(const Instance& ws, const Instance& operation, const Instance* feature,
                 const Instance& tool_instance, const Frame& frame);
  void set_security_plane(const Instance& owner);

  // ---- what ncpost assumes (docs/interoperability.md) ----
  [[nodiscard]] bool tolerant() const { return a_.mode() == Mode::Tolerant; }
  // An INTEROP-002 note for each instance of the tool read through the variants table.
  void note_variants(const Instance& tool_instance);
  // The tool's diameter and teeth, read without reporting (the feature readers report).
  const Instance* referenced(const Instance& owner, std::string_view attribute,
                             std::string_view type);
  units::ToolSize tool_size(const Instance* tool_instance);
  // Each assumption noted since the last call (INTEROP notes) as a COMMENT here, so that the
  // posted program carries it at the workingstep it concerns, in every profile's comment syntax.
  void comment_assumptions();

  const p21::Model& m_;
  const AttributeReader& a_;
  Machine machine_;
  const InterpretOptions& options_;
  std::vector<diag::Diagnostic> diagnostics_;
  detail::GeometryReader geometry_;
  detail::CurveReader curves_;

  Frame workpiece_;                       // machine ← workpiece (setup ∘ workpiece setup)
  std::vector<Frame> workpiece_origins_;  // workpiece setups of the current setup
  std::vector<const Instance*> workpiece_setups_;
  std::unordered_set<std::uint64_t> on_path_;
  std::unordered_set<std::uint64_t> variants_noted_;
  // (technology, tool) ids → the feed and spindle speed read (units.hpp).
  struct UnitsKey {
    std::uint64_t technology, tool;
    bool operator==(const UnitsKey&) const = default;
  };
  struct UnitsKeyHash {
    std::size_t operator()(const UnitsKey& k) const noexcept {
      return std::hash<std::uint64_t>()(k.technology * 0x9E3779B97F4A7C15ull ^ k.tool);
    }
  };
  std::unordered_map<UnitsKey, std::pair<std::optional<double>, std::optional<double>>,
                     UnitsKeyHash>
      units_read_;
  const Instance* tool_ = nullptr;  // the tool in the spindle
  std::size_t assumptions_commented_ = 0;
  std::size_t errors_checked_ = 0;
  bool stopped_ = false;
};

InterpretResult Interpreter::run() {
  InterpretResult result;
  const auto projects = m_.instances_of("PROJECT");
  if (projects.empty()) {
    // Nothing to interpret is an error here, whatever inspect makes of it.
    diagnostics_.push_back(no_program_diagnostic(m_));
    diagnostics_.back().severity = diag::Severity::Error;
  } else {
    const Instance& project = *projects.front();
    machine_.start_program(entity(project));
    const Instance* main = ref(project, "main_workplan", "workplan");
    if (main != nullptr) executable(*main, 0);
    if (stopped()) {
      result.diagnostics = std::move(diagnostics_);
      result.calls = machine_.calls();
      return result;  // no end sequence: the program is incomplete
    }
    machine_.end_program(entity(project));
  }
  result.diagnostics = std::move(diagnostics_);
  result.calls = machine_.calls();
  return result;
}

void Interpreter::set_up(const Instance& setup) {
  // Machine ← setup origin ← workpiece origin: the setup places the workpiece set-ups on the
  // machine table; each workpiece set-up places a workpiece. Toolpaths of a feature are in the
  // feature's placement, which sits in the workpiece (docs/interpreter.md, "Placements").
  Frame setup_frame;
  if (const auto origin = geometry_.get(setup, "its_origin"); origin && !origin->is_omitted()) {
    if (auto f = geometry_.placement(origin)) setup_frame = *f;
  }
  workpiece_origins_.clear();
  workpiece_setups_.clear();
  if (const auto list = geometry_.get(setup, "its_workpiece_setup"); list && list->is_list()) {
    for (Value v : m_.items(*list)) {
      const Instance* ws = geometry_.instance(v, "workpiece_setup", &setup, "its_workpiece_setup");
      if (ws == nullptr) continue;
      const auto origin = geometry_.placement(geometry_.get(*ws, "its_origin"));
      workpiece_origins_.push_back(setup_frame.then(origin.value_or(Frame{})));
      workpiece_setups_.push_back(ws);
    }
  }
  workpiece_ = workpiece_origins_.empty() ? setup_frame : workpiece_origins_.front();
  if (workpiece_origins_.size() > 1)
    note(setup, detail::describe(m_, setup) + " has " + std::to_string(workpiece_origins_.size()) +
                    " workpiece set-ups; each workingstep uses the one of its feature's workpiece");
  // The setup's security plane until a workingstep names its own.
  set_security_plane(setup);
}

// The owner's its_secplane, if set: a PLANE whose placement's location gives the height.
void Interpreter::set_security_plane(const Instance& owner) {
  if (const Instance* plane = ref(owner, "its_secplane", "elementary_surface", true)) {
    if (auto f = geometry_.placement(geometry_.get(*plane, "position")))
      machine_.set_security_z(workpiece_.point(f->origin).z);
  }
}

void Interpreter::executable(const Instance& e, unsigned depth) {
  if (stopped()) return;
  if (depth > options_.max_nesting) {
    geometry_.error(diag::Code::StepncTooDeep, e,
                    detail::describe(m_, e) + " is nested more than " +
                        std::to_string(options_.max_nesting) + " workplans deep");
    return;
  }
  if (!a_.is_executable(e)) {
    geometry_.error(diag::Code::StepncWrongType, e,
                    detail::describe(m_, e) + " is not an ISO 14649 executable");
    return;
  }
  if (!on_path_.insert(e.id).second) {
    geometry_.error(diag::Code::StepncCycle, e, "#" + std::to_string(e.id) + " contains itself");
    return;
  }
  if (geometry_.is_a(e, "workplan")) {
    emit(canon::Begin{canon::Scope::Workplan, entity(e)});
    const Instance* setup = ref(e, "its_setup", "setup", true);
    if (setup) {
      emit(canon::Begin{canon::Scope::Setup, entity(*setup)});
      set_up(*setup);
    }
    elements(e, "its_elements", depth);
    if (setup) emit(canon::End{canon::Scope::Setup, entity(*setup)});
    emit(canon::End{canon::Scope::Workplan, entity(e)});
  } else if (geometry_.is_a(e, "machining_workingstep")) {
    workingstep(e);
  } else if (geometry_.is_a(e, "rapid_movement")) {
    rapid_movement(e);
  } else if (geometry_.is_a(e, "nc_function")) {
    nc_function(e);
  } else if (geometry_.is_a(e, "non_sequential")) {
    note(e, detail::describe(m_, e) + ": NON_SEQUENTIAL elements run in file order");
    elements(e, "its_elements", depth);
  } else if (geometry_.is_a(e, "parallel")) {
    note(e, detail::describe(m_, e) +
                ": PARALLEL branches run one after another on this "
                "single-channel machine");
    elements(e, "branches", depth);
  } else if (geometry_.is_a(e, "selective")) {
    const auto list = geometry_.get(e, "its_elements");
    if (list && list->is_list() && list->count() > 0) {
      note(e, detail::describe(m_, e) + ": SELECTIVE runs its first element; the other " +
                  std::to_string(list->count() - 1) + " are alternatives for the operator");
      if (const Instance* first =
              geometry_.instance(m_.items(*list)[0], "executable", &e, "its_elements"))
        executable(*first, depth + 1);
    }
  } else if (geometry_.is_a(e, "if_statement") || geometry_.is_a(e, "while_statement")) {
    geometry_.error(diag::Code::StepncCondition, e,
                    detail::describe(m_, e) +
                        ": its condition depends on NC variables set while the program runs, "
                        "which a post-processor cannot evaluate; the statement is not executed");
  } else {
    not_implemented(e, "this executable");
  }
  on_path_.erase(e.id);
}

void Interpreter::elements(const Instance& owner, std::string_view attribute, unsigned depth) {
  const auto list = geometry_.get(owner, attribute);
  if (!list || !list->is_list()) return;
  for (Value v : m_.items(*list))
    if (const Instance* e = geometry_.instance(v, "executable", &owner, attribute))
      executable(*e, depth + 1);
}

void Interpreter::nc_function(const Instance& f) {
  if (geometry_.is_a(f, "program_stop")) {
    emit(canon::ProgramStop{});
  } else if (geometry_.is_a(f, "optional_stop")) {
    emit(canon::OptionalProgramStop{});
  } else if (geometry_.is_a(f, "display_message")) {
    const auto text = geometry_.get(f, "its_text");
    emit(canon::Message{text && text->kind() == p21::ValueKind::String ? m_.as_string(*text)
                                                                       : name(f)});
  } else if (geometry_.is_a(f, "load_tool")) {
    if (const Instance* t = ref(f, "its_tool", "machining_tool")) tool(*t);
    comment_assumptions();
  } else if (geometry_.is_a(f, "unload_tool")) {
    machine_.unload_tool();
  } else if (geometry_.is_a(f, "exchange_pallet") || geometry_.is_a(f, "index_pallet") ||
             geometry_.is_a(f, "index_table")) {
    // RS274 has no pallet or table call: the operator is told, and the program stops for it.
    std::string what = std::string(m_.type_name(f));
    if (const auto index = geometry_.get(f, "its_index"); index && index->is_number())
      what += " " + std::to_string(m_.as_integer(*index));
    emit(canon::Message{what});
    emit(canon::ProgramStop{});
  } else if (geometry_.is_a(f, "set_mark") || geometry_.is_a(f, "wait_for_mark")) {
    emit(canon::Comment{std::string(m_.type_name(f)) + " " + name(f)});
    note(f, detail::describe(m_, f) + ": channel synchronisation has no effect on one channel");
  } else {
    not_implemented(f, "this NC function");
  }
}

bool Interpreter::tool(const Instance& t) {
  tool_ = &t;
  if (machine_.holds(t.id)) return true;
  note_variants(t);
  double assembly_length = 0;
  if (const auto l = geometry_.get(t, "overall_assembly_length"); l && l->is_number())
    assembly_length = m_.as_real(*l);
  const auto load = detail::tool_load(t.id, name(t), assembly_length,
                                      options_.tools ? &*options_.tools : nullptr);
  if (!load) {
    geometry_.error(diag::Code::StepncToolTable, t,
                    detail::describe(m_, t) + " '" + name(t) + "' is not in the tool table");
    return false;
  }
  machine_.change_tool(*load);
  return true;
}

void Interpreter::technology(const Instance* tech) {
  if (tech == nullptr) return;
  units::Written written;
  written.feed = geometry_.number(*tech, "feedrate");
  const bool milling = geometry_.is_a(*tech, "milling_technology");
  if (milling) {
    written.spindle = geometry_.number(*tech, "spindle");
    written.cutspeed = geometry_.number(*tech, "cutspeed");
    written.feed_per_tooth = geometry_.number(*tech, "feedrate_per_tooth");
  }
  std::optional<double> feed = written.feed;
  std::optional<double> spindle = written.spindle;
  if (tolerant()) {
    // Units that do not add up (units.hpp): the plausible reading, noted, or an error; checked
    // and reported where a technology is first used with a tool, the reading kept for its
    // later uses (a toolpath list may name the same technology thousands of times).
    const UnitsKey key{tech->id, tool_ ? tool_->id : 0};
    auto taken = units_read_.find(key);
    if (taken == units_read_.end()) {
      const units::Reading reading = units::cross_check(written, tool_size(tool_));
      for (const std::string& n : reading.notes)
        geometry_.error(diag::Code::InteropUnits, *tech, detail::describe(m_, *tech) + ": " + n);
      for (const std::string& e : reading.errors)
        geometry_.error(diag::Code::InteropUnitsConflict, *tech,
                        detail::describe(m_, *tech) + ": " + e);
      taken = units_read_.emplace(key, std::make_pair(reading.feed, reading.spindle)).first;
    }
    feed = taken->second.first;
    spindle = taken->second.second;
  }
  if (feed) machine_.feed_rate(*feed * kFeedToMmPerMin);
  // NIST's convention (ex1.stp's notes): a negative speed turns clockwise.
  if (milling && spindle) machine_.spindle(*spindle);
}

void Interpreter::note_variants(const Instance& t) {
  if (!tolerant()) return;
  const Instance* body = referenced(t, "its_tool_body", "tool_body");
  const Instance* dimension = body ? referenced(*body, "dimension", "") : nullptr;
  for (const Instance* i : {&t, body, dimension}) {
    const Variant* row = i ? a_.variant(*i) : nullptr;
    if (row == nullptr || !variants_noted_.insert(i->id).second) continue;
    std::string message = detail::describe(m_, *i) + ": " + std::string(row->assumption);
    if (const auto d = tool_size(&t).diameter)
      message += "; tool " + detail::describe(m_, t) + " '" + name(t) + "' of diameter " +
                 features::fmt(*d) + " mm";
    geometry_.error(diag::Code::InteropVariant, *i, std::move(message));
  }
}

const Instance* Interpreter::referenced(const Instance& owner, std::string_view attribute,
                                        std::string_view type) {
  const auto v = geometry_.get(owner, attribute);
  const Instance* target = v && v->is_reference() ? m_.find(v->id()) : nullptr;
  return target != nullptr && (type.empty() || geometry_.is_a(*target, type)) ? target : nullptr;
}

units::ToolSize Interpreter::tool_size(const Instance* t) {
  units::ToolSize out;
  const Instance* body = t ? referenced(*t, "its_tool_body", "milling_machine_tool_body") : nullptr;
  if (body == nullptr) return out;
  if (const Instance* d = referenced(*body, "dimension", "milling_tool_dimension"))
    out.diameter = geometry_.number(*d, "diameter");
  if (const auto teeth = geometry_.get(*body, "number_of_teeth");
      teeth && teeth->kind() == p21::ValueKind::Integer)
    out.teeth = static_cast<int>(m_.as_integer(*teeth));
  return out;
}

void Interpreter::comment_assumptions() {
  for (; assumptions_commented_ < diagnostics_.size(); ++assumptions_commented_) {
    const diag::Diagnostic& d = diagnostics_[assumptions_commented_];
    if (d.severity == diag::Severity::Note && d.code_id().starts_with("INTEROP-"))
      emit(canon::Comment{"ASSUMED " + d.message});
  }
}

void Interpreter::machine_functions(const Instance* functions) {
  if (functions == nullptr) return;
  const auto flag = [&](std::string_view attribute) -> std::optional<bool> {
    const auto v = geometry_.get(*functions, attribute);
    if (v && v->is_omitted() && required(*functions, attribute))
      // A tolerant check lets '$' through where ISO 14649 requires the flag.
      // Tolerant, an assumption like the others (INTEROP-009), so the posted program says it
      // too; strict (a file read unchecked, without a schema of its own), the note of before.
      geometry_.error(tolerant() ? diag::Code::InteropFlagUnset : diag::Code::StepncNote,
                      *functions,
                      detail::describe(m_, *functions) + " attribute " + std::string(attribute) +
                          (tolerant() ? " is unset" : " is '$'") +
                          ", which ISO 14649 does not allow: it is left as it was (off at the "
                          "start of the program)");
    if (!v || v->is_omitted()) return std::nullopt;
    const auto l = m_.as_logical(*v);
    if (!l) return std::nullopt;
    return *l == p21::Logical::True;
  };
  machine_.coolant(flag("coolant"), flag("mist"));
}

void Interpreter::toolpaths(const Instance* list, const Frame& frame, bool rapid) {
  if (list == nullptr) return;
  const auto items = geometry_.get(*list, "its_list");
  if (!items || !items->is_list()) return;
  for (Value v : m_.items(*items)) {
    const Instance* path = geometry_.instance(v, "toolpath", list, "its_list");
    if (path == nullptr) continue;
    if (geometry_.is_a(*path, "feedstop")) {
      // A pause in the path: the tool dwells where it is.
      if (const auto seconds = geometry_.number(*path, "dwell")) emit(canon::Dwell{*seconds});
      continue;
    }
    if (!geometry_.is_a(*path, "cutter_location_trajectory")) {
      not_implemented(*path,
                      "this kind of toolpath (CUTTER_LOCATION_TRAJECTORY and FEEDSTOP are; "
                      "cutter-contact paths need the tool's geometry, axis trajectories "
                      "per-axis commands)");
      continue;
    }
    // its_speed .RAPID. (speed_name, bare or typed) moves at rapid; a ratio or a speed curve
    // is not implemented.
    bool rapid_speed = false;
    if (const auto speed = geometry_.get(*path, "its_speed"); speed && !speed->is_omitted()) {
      const Value named = speed->kind() == p21::ValueKind::Typed ? m_.typed_child(*speed) : *speed;
      rapid_speed = named.kind() == p21::ValueKind::Enumeration && m_.enumeration(named) == "RAPID";
      if (!rapid_speed)
        not_implemented(*path, "a toolpath speed profile (its_speed) other than .RAPID.");
    }
    technology(ref(*path, "its_technology", "technology", true));
    machine_functions(ref(*path, "its_machine_functions", "machine_functions", true));
    comment_assumptions();
    const Instance* curve = ref(*path, "basiccurve", "bounded_curve");
    if (curve == nullptr) continue;
    auto segments = curves_.segments(*curve);
    if (!segments || segments->empty()) continue;
    // its_direction .F.: the path runs from the curve's end to its start.
    if (const auto direction = geometry_.get(*path, "its_direction");
        direction && m_.as_logical(*direction) == p21::Logical::False)
      detail::reverse(*segments);
    if (const Instance* axis_curve = ref(*path, "its_toolaxis", "bounded_curve", true);
        axis_curve != nullptr && !curves_.apply_tool_axis(*segments, *axis_curve))
      not_implemented(*path, "a tool-axis curve other than a polyline matching a polyline path");
    const auto type = geometry_.get(*path, "its_type");
    const bool non_contact = type && m_.enumeration(*type) == "NON_CONTACT";
    const Vec3 start = frame.point(segments->front().start);
    const bool first_of_list = v == m_.items(*items)[0];
    if (machine_.join(start, first_of_list, rapid))
      geometry_.error(diag::Code::StepncDiscontinuous, *path,
                      detail::describe(m_, *path) +
                          " starts away from where the previous toolpath ended; the tool " +
                          (rapid ? "moves" : "feeds") + " across");
    machine_.motion(*segments, frame, rapid || non_contact || rapid_speed);
  }
}

void Interpreter::workingstep(const Instance& ws) {
  emit(canon::Begin{canon::Scope::Workingstep, entity(ws)});
  const Instance* operation = ref(ws, "its_operation", "machining_operation");
  const Instance* feature = ref(ws, "its_feature", "manufacturing_feature", true);
  set_security_plane(ws);
  // The feature's workpiece picks the workpiece set-up; its placement is the toolpaths' frame.
  Frame frame = workpiece_;
  if (feature != nullptr) {
    if (const auto wp = geometry_.get(*feature, "its_workpiece"); wp && wp->is_reference()) {
      for (std::size_t i = 0; i < workpiece_setups_.size(); ++i) {
        const auto w = geometry_.get(*workpiece_setups_[i], "its_workpiece");
        if (w && w->is_reference() && w->id() == wp->id()) frame = workpiece_origins_[i];
      }
    }
    if (const auto placement = geometry_.get(*feature, "feature_placement");
        placement && !placement->is_omitted()) {
      if (auto f = geometry_.placement(placement)) frame = frame.then(*f);
    }
  }
  if (operation != nullptr) {
    const Instance* tool_instance = ref(*operation, "its_tool", "machining_tool");
    if (tool_instance != nullptr && tool(*tool_instance)) {
      technology(ref(*operation, "its_technology", "technology"));
      machine_functions(ref(*operation, "its_machine_functions", "machine_functions"));
      comment_assumptions();
      const Instance* list = ref(*operation, "its_toolpath", "toolpath_list", true);
      if (list == nullptr) {
        generated(ws, *operation, feature, *tool_instance, frame);
      } else {
        toolpaths(list, frame, false);
      }
    }
  }
  emit(canon::End{canon::Scope::Workingstep, entity(ws)});
}

// A workingstep without explicit toolpaths (conformance class 3): the path is generated from the
// feature (features/, docs/features.md) in the feature's coordinates and played like an
// explicit one: the first rapid is the approach from the security plane.
void Interpreter::generated(const Instance& ws, const Instance& operation, const Instance* feature,
                            const Instance& tool_instance, const Frame& frame) {
  features::Request request{
      &ws, &operation, feature, &tool_instance, machine_.feed(), machine_.spindle_speed()};
  const features::Path path = features::generate(geometry_, request, options_.features);
  comment_assumptions();
  if (!path.ok) return;
  const bool upright = std::abs(frame.z.z - 1) < 1e-9;
  bool first = true;
  for (const features::Move& mv : path.moves) {
    switch (mv.kind) {
      case features::Move::Kind::Rapid:
        if (first)
          machine_.approach(frame.point(mv.to), false);
        else
          emit(canon::StraightTraverse{flat_pose(frame.point(mv.to))});
        machine_.set_position(frame.point(mv.to));
        first = false;
        break;
      case features::Move::Kind::Feed:
        emit(canon::StraightFeed{flat_pose(frame.point(mv.to))});
        machine_.set_position(frame.point(mv.to));
        break;
      case features::Move::Kind::Arc: {
        const Vec3 end = frame.point(mv.to);
        const Vec3 centre = frame.point(mv.centre);
        const Vec3 normal = frame.z;
        emit(canon::ArcFeed{flat_pose(end),
                            {centre.x, centre.y, centre.z},
                            {normal.x, normal.y, normal.z},
                            mv.turns});
        machine_.set_position(end);
        break;
      }
      case features::Move::Kind::FeedRate:
        machine_.feed_rate(mv.value);
        break;
      case features::Move::Kind::Spindle:
        machine_.spindle(mv.value);
        break;
      case features::Move::Kind::Dwell:
        emit(canon::Dwell{mv.value});
        break;
      case features::Move::Kind::Cycle: {
        if (!upright) {
          geometry_.error(diag::Code::StepncFeatureNotImplemented, ws,
                          detail::describe(m_, ws) +
                              ": a hole cycle along an axis other than "
                              "+Z (" +
                              detail::describe(m_, *feature) + ") is not implemented");
          return;
        }
        // Over the hole at the security plane (the cycle's initial level), then the cycle.
        const Vec3 top = frame.point({mv.to.x, mv.to.y, mv.to.z});
        const double safe = std::max(machine_.security_z().value_or(top.z), top.z);
        machine_.approach({top.x, top.y, safe}, false);
        canon::Cycle c;
        c.kind = mv.cycle == features::Move::CycleKind::Drill  ? canon::CycleKind::Drill
                 : mv.cycle == features::Move::CycleKind::Peck ? canon::CycleKind::PeckDrill
                 : mv.cycle == features::Move::CycleKind::Tap  ? canon::CycleKind::Tap
                 : mv.cycle == features::Move::CycleKind::Bore ? canon::CycleKind::Bore
                                                               : canon::CycleKind::Ream;
        c.x = top.x;
        c.y = top.y;
        c.safe_z = safe;
        c.r_z = top.z;
        c.bottom_z = frame.point({mv.to.x, mv.to.y, mv.bottom}).z;
        c.feed = mv.feed;
        c.dwell = mv.dwell;
        c.peck = mv.peck;
        c.peck_retract = mv.peck_retract;
        c.pitch = mv.pitch;
        c.spindle_speed = mv.rpm;
        c.left_hand = mv.left_hand;
        c.spindle_stop = mv.spindle_stop;
        emit(c);
        machine_.set_position(Vec3{top.x, top.y, safe});
        first = false;
        break;
      }
    }
  }
}

void Interpreter::rapid_movement(const Instance& rm) {
  emit(canon::Begin{canon::Scope::Workingstep, entity(rm)});
  set_security_plane(rm);
  // A rapid movement has no feature: its toolpath is in the workpiece's coordinates.
  toolpaths(ref(rm, "its_toolpath", "toolpath_list", true), workpiece_, true);
  emit(canon::End{canon::Scope::Workingstep, entity(rm)});
}

}  // namespace

bool InterpretResult::ok() const {
  return std::none_of(diagnostics.begin(), diagnostics.end(),
                      [](const auto& d) { return d.severity == diag::Severity::Error; });
}

const ToolTableEntry* ToolTable::find(std::string_view name) const {
  for (const auto& e : entries)
    if (e.name == name) return &e;
  return nullptr;
}

ToolTable read_tool_table(std::string_view text, std::vector<diag::Diagnostic>& diagnostics) {
  ToolTable table;
  std::uint32_t line_number = 0;
  while (!text.empty()) {
    const std::size_t eol = text.find('\n');
    std::string_view line = text.substr(0, eol);
    text = eol == std::string_view::npos ? std::string_view() : text.substr(eol + 1);
    ++line_number;
    while (!line.empty() && std::isspace(static_cast<unsigned char>(line.front())))
      line.remove_prefix(1);
    if (line.empty() || !std::isdigit(static_cast<unsigned char>(line.front())))
      continue;  // heading
    // POCKET  FMS  TLO  DIAM  [HOLDER  DESCRIPTION...]; FMS may be quoted with ' or ".
    ToolTableEntry e;
    auto [p, ec] = std::from_chars(line.data(), line.data() + line.size(), e.pocket);
    line.remove_prefix(static_cast<std::size_t>(p - line.data()));
    while (!line.empty() && std::isspace(static_cast<unsigned char>(line.front())))
      line.remove_prefix(1);
    if (!line.empty() && (line.front() == '\'' || line.front() == '"')) {
      const char quote = line.front();
      const std::size_t close = line.find(quote, 1);
      if (close == std::string_view::npos) {
        diagnostics.push_back(diag::make(diag::Code::StepncToolTable, line_number, 1,
                                         "unclosed quote in the tool name"));
        continue;
      }
      e.name = std::string(line.substr(1, close - 1));
      line.remove_prefix(close + 1);
    } else {
      const std::size_t end = line.find_first_of(" \t");
      e.name = std::string(line.substr(0, end));
      line.remove_prefix(end == std::string_view::npos ? line.size() : end);
    }
    double numbers[2] = {0, 0};
    for (double& n : numbers) {
      while (!line.empty() && std::isspace(static_cast<unsigned char>(line.front())))
        line.remove_prefix(1);
      auto [q, ec2] = std::from_chars(line.data(), line.data() + line.size(), n);
      if (ec2 != std::errc()) {
        diagnostics.push_back(
            diag::make(diag::Code::StepncToolTable, line_number, 1,
                       "expected the length offset and diameter of tool '" + e.name + "'"));
        break;
      }
      line.remove_prefix(static_cast<std::size_t>(q - line.data()));
    }
    e.length_offset = numbers[0];
    e.diameter = numbers[1];
    if (ec == std::errc() && !e.name.empty()) table.entries.push_back(std::move(e));
  }
  return table;
}

InterpretResult interpret(const p21::Model& model, const AttributeReader& attributes,
                          canon::Sink& sink, const InterpretOptions& options) {
  return Interpreter(model, attributes, sink, options).run();
}

}  // namespace ncpost::stepnc
