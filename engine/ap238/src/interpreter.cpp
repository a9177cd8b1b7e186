// The AP238 AIM interpreter. See ap238.hpp, and docs/ap238.md for the mapping as implemented.

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <unordered_map>
#include <unordered_set>

#include "aim.hpp"
#include "ncpost/ap238/ap238.hpp"
#include "ncpost/express/registry.hpp"
#include "ncpost/stepnc/machine.hpp"
#include "program.hpp"
#include "vendor.hpp"

namespace ncpost::ap238 {
namespace {

using detail::Aim;
using detail::Instance;
using detail::Property;
using detail::Quantity;
using detail::Segment;
using stepnc::detail::Frame;
using stepnc::detail::Machine;
using stepnc::detail::Vec3;

constexpr double kSecondsPerMinute = 60.0;

// What kind of AIM object a property was found on: the standard names differ per kind.
enum class Owner : std::uint8_t {
  Workplan,
  Workingstep,
  Operation,
  Technology,
  Functions,
  Toolpath,
  Tool,
  NcFunction,
  Executable
};

// The property names ISO 10303-238 defines for each kind (the WHERE rules of the AIM).
// Read ones change the canonical program; the others are the ARM attributes that the ISO 14649
// interpreter does not use either (priorities, override flags, strategies' parameters, ...).
bool standard(Owner owner, std::string_view name) {
  static constexpr std::string_view kWorkplan[] = {"channel"};
  static constexpr std::string_view kWorkingstep[] = {"security plane"};
  static constexpr std::string_view kOperation[] = {
      "cut start point",     "retract plane",      "tool direction",
      "overcut length",      "cutting depth",      "dwell time bottom",
      "feedrate on retract", "previous diameter",  "allowance bottom",
      "axial cutting depth", "allowance side",     "radial cutting depth",
      "depth of step",       "dwell time step",    "first depth",
      "retract distance",    "spindle stop",       "testcut depth",
      "waiting position",    "compensation chuck", "helical movement on forward",
      "security plane"};
  static constexpr std::string_view kTechnology[] = {"feedrate",
                                                     "feedrate reference",
                                                     "inhibit feedrate override",
                                                     "inhibit spindle override",
                                                     "spindle",
                                                     "synchronize spindle with feed",
                                                     "synchronize spindle with z feed"};
  static constexpr std::string_view kFunctions[] = {"axis clamping",
                                                    "chip removal",
                                                    "coolant",
                                                    "coolant pressure",
                                                    "coolant type",
                                                    "follow rest",
                                                    "mist",
                                                    "oriented spindle stop",
                                                    "other functions",
                                                    "steady rest",
                                                    "tail stock",
                                                    "through spindle coolant",
                                                    "through spindle pressure",
                                                    "axis constraints"};
  static constexpr std::string_view kToolpath[] = {"angle",
                                                   "axis commands",
                                                   "basic curve",
                                                   "bend distance",
                                                   "contact type",
                                                   "direction",
                                                   "down direction",
                                                   "dwell",
                                                   "fix point",
                                                   "fix point direction",
                                                   "path maximum deviation",
                                                   "priority",
                                                   "radius",
                                                   "speed profile",
                                                   "surface normal",
                                                   "tool axis",
                                                   "tool axis maximum deviation",
                                                   "trajectory type",
                                                   "up direction"};
  static constexpr std::string_view kTool[] = {"direction for spindle orientation",
                                               "minimum cutting diameter",
                                               "overall assembly length",
                                               "overall assembly width",
                                               "tool body",
                                               "tool holder diameter for spindle orientation",
                                               "tool holder profile"};
  static constexpr std::string_view kNcFunction[] = {"channel", "function text", "message text",
                                                     "pallet index", "table index"};
  static constexpr std::string_view kExecutable[] = {"condition", "lvalue", "rvalue"};
  const auto in = [&](std::span<const std::string_view> names) {
    return std::find(names.begin(), names.end(), name) != names.end();
  };
  switch (owner) {
    case Owner::Workplan:
      return in(kWorkplan);
    case Owner::Workingstep:
      return in(kWorkingstep);
    case Owner::Operation:
      return in(kOperation);
    case Owner::Technology:
      return in(kTechnology);
    case Owner::Functions:
      return in(kFunctions);
    case Owner::Toolpath:
      return in(kToolpath);
    case Owner::Tool:
      return in(kTool);
    case Owner::NcFunction:
      return in(kNcFunction);
    case Owner::Executable:
      return in(kExecutable);
  }
  return false;
}

const detail::VendorAdapter* vendor_of(std::string_view property) {
  for (const detail::VendorAdapter* a : detail::vendor_adapters())
    if (a->documents(property)) return a;
  return nullptr;
}

// A machining technology, read once however many toolpaths share it.
struct Technology {
  std::optional<double> feed;     // mm/min
  std::optional<double> spindle;  // revolutions per second, negative clockwise
};

// Machine functions, likewise.
struct Functions {
  std::optional<bool> flood;
  std::optional<bool> mist;
};

class Interpreter {
 public:
  Interpreter(const p21::Model& model, const stepnc::AttributeReader& attributes, canon::Sink& sink,
              const stepnc::InterpretOptions& options)
      : m_(model),
        aim_(model, attributes, diagnostics_),
        machine_(sink),
        options_(options),
        curves_(aim_.geometry(), options.arc_tolerance) {}

  stepnc::InterpretResult run();

 private:
  // ---- helpers ----
  void emit(const canon::Call& c) { machine_.emit(c); }
  canon::Entity entity(const Instance& i) {
    return {i.id, std::string(m_.type_name(i)), detail::arm_name(aim_, i)};
  }
  std::string named(const Instance& i) {
    return aim_.describe(i) + " '" + detail::arm_name(aim_, i) + "'";
  }
  void not_implemented(const Instance& at, const std::string& what) {
    aim_.report(diag::Code::Ap238NotImplemented, at,
                named(at) + ": " + what + " is not implemented");
  }
  bool stopped();
  bool refuse_non_milling();
  // Properties of `owner`, each counted once per instance for the end-of-program lists of what
  // was not mapped (AP238-009) and what a vendor documents (AP238-010).
  std::vector<Property> properties(const Instance& owner, Owner kind);
  void properties(const Instance& owner, Owner kind, std::vector<Property>& out);
  void report_properties();

  // ---- program ----
  void executable(const Instance& e, unsigned depth);
  void elements(const std::vector<const Instance*>& list, unsigned depth);
  void workplan(const Instance& plan, unsigned depth);
  void workingstep(const Instance& ws);
  void rapid_movement(const Instance& rm);
  void nc_function(const Instance& f);
  void set_up(const Instance& setup);
  void security_plane(const Instance& owner, const std::vector<Property>& properties);

  // ---- machine state ----
  bool tool(const Instance& tool);
  void technology(const Instance& operation_or_toolpath);
  void functions(const Instance& operation_or_toolpath);
  const Technology& read_technology(const Instance& tech);
  const Functions& read_functions(const Instance& f);
  void toolpaths(const Instance& operation, const Frame& frame, bool rapid);
  std::optional<std::vector<Segment>> toolpath_geometry(const Instance& operation,
                                                        const Instance& path,
                                                        const std::vector<Property>& props);

  // ---- placements (in mm) ----
  std::optional<Frame> placement(const Instance& axis, double mm);
  std::optional<Frame> shape_placement(const Instance& definition);
  std::optional<Frame> workpiece_placement(const Instance& relationship);

  const p21::Model& m_;
  std::vector<diag::Diagnostic> diagnostics_;
  Aim aim_;
  Machine machine_;
  const stepnc::InterpretOptions& options_;
  stepnc::detail::CurveReader curves_;

  Frame workpiece_;  // machine ← workpiece (set-up ∘ workpiece set-up)
  // The set-up's workpieces: (workpiece PRODUCT_DEFINITION, machine ← workpiece).
  std::vector<std::pair<const Instance*, Frame>> workpieces_;
  std::unordered_set<std::uint64_t> on_path_;
  std::unordered_map<std::uint64_t, Technology> technologies_;
  std::unordered_map<std::uint64_t, Functions> functions_;
  // Per (owner entity, property name): how often, the first property, a sample, the vendor.
  struct Tally {
    std::size_t count = 0;
    const Instance* first = nullptr;
    std::string owner;
    std::string sample;
    const detail::VendorAdapter* vendor = nullptr;
  };
  std::map<std::pair<std::string, std::string>, std::size_t> tally_index_;
  std::vector<Tally> tallies_;
  std::unordered_set<std::uint64_t> tallied_tools_;
  std::vector<Property> path_properties_;  // the current toolpath's, storage kept
  std::size_t errors_checked_ = 0;
  std::size_t errors_ = 0;
  bool stopped_ = false;
};

// ---------------------------------------------------------------------------------------------

stepnc::InterpretResult Interpreter::run() {
  stepnc::InterpretResult result;
  const auto finish = [&] {
    report_properties();
    result.diagnostics = std::move(diagnostics_);
    result.calls = machine_.calls();
    return result;
  };
  if (refuse_non_milling()) return finish();
  const auto project = detail::find_project(aim_);
  if (!project || project->main_workplan == nullptr) return finish();
  const canon::Entity program{project->project->id, std::string(m_.type_name(*project->project)),
                              project->name};
  machine_.start_program(program);
  executable(*project->main_workplan, 0);
  if (stopped()) return finish();  // no end sequence: the program is incomplete
  machine_.end_program(program);
  return finish();
}

bool Interpreter::stopped() {
  if (options_.cancel != nullptr && options_.cancel->load(std::memory_order_relaxed))
    stopped_ = true;
  for (; errors_checked_ < diagnostics_.size(); ++errors_checked_) {
    if (diagnostics_[errors_checked_].severity != diag::Severity::Error) continue;
    ++errors_;
    if (options_.stop_at_first_error) stopped_ = true;
    if (errors_ == options_.max_errors && !options_.stop_at_first_error) {
      stopped_ = true;
      diagnostics_.push_back(diag::make(
          diag::Code::Ap238TooManyErrors, 0, 0,
          "stopped after " + std::to_string(errors_) + " errors (InterpretOptions::max_errors)"));
      errors_checked_ = diagnostics_.size();
      break;
    }
  }
  return stopped_;
}

// A turning program (or one for another technology) is refused before any call: its
// coordinates (X radius, Z axial) are not a milling machine's, and posting them would move the
// wrong axes.
bool Interpreter::refuse_non_milling() {
  std::vector<std::pair<const Instance*, std::string>> found;  // instance, what it is
  for (const Instance* i : aim_.instances_of("turning_type_operation"))
    found.emplace_back(i, "a turning operation");
  static constexpr std::pair<const char*, const char*> kDescribed[] = {
      {"machining_workingstep", "workingstep"},
      {"machining_technology", "technology"},
      {"machining_functions", "machine functions"}};
  for (const auto& [entity, noun] : kDescribed) {
    const bool workingstep = std::string_view(noun) == "workingstep";
    for (const Instance* i : aim_.instances_of(entity)) {
      if (aim_.text_is(*i, "description", "turning")) {
        found.emplace_back(i, std::string("a turning ") + noun);
      } else if (!workingstep && !aim_.text_is(*i, "description", "milling")) {
        // Technology and functions say what they are for; an empty description says nothing.
        const std::string d = aim_.text(*i, "description");
        if (!d.empty()) found.emplace_back(i, "a '" + d + "' " + noun);
      }
    }
  }
  if (found.empty()) return false;
  const auto first = std::min_element(found.begin(), found.end(), [](const auto& a, const auto& b) {
    return a.first->offset < b.first->offset;
  });
  const bool turning = first->second.find("turning") != std::string::npos;
  aim_.report(
      diag::Code::Ap238NotMilling, *first->first,
      named(*first->first) + " is " + first->second +
          (turning ? ": turning programs are not supported"
                   : ": only milling programs are supported") +
          " (ncpost posts milling programs); the program is refused before any motion" +
          (found.size() > 1 ? " (" + std::to_string(found.size()) + " such instances)" : ""));
  return true;
}

std::vector<Property> Interpreter::properties(const Instance& owner, Owner kind) {
  std::vector<Property> list;
  properties(owner, kind, list);
  return list;
}

void Interpreter::properties(const Instance& owner, Owner kind, std::vector<Property>& list) {
  aim_.properties(owner, list);
  // Everything but a tool is read once (technologies and functions are remembered by id); a
  // tool is read at each load, and counted at its first.
  if (kind == Owner::Tool && !tallied_tools_.insert(owner.id).second) return;
  for (const Property& p : list) {
    if (standard(kind, p.name)) continue;
    const detail::VendorAdapter* vendor = vendor_of(p.name);
    if (vendor != nullptr && vendor->is_geometry(p.name)) continue;  // read as motion
    const std::pair<std::string, std::string> key{std::string(m_.type_name(owner)), p.name};
    auto [it, added] = tally_index_.emplace(key, tallies_.size());
    if (added) {
      Tally t;
      t.first = p.instance;
      t.owner = key.first;
      t.vendor = vendor;
      if (const auto d = aim_.description_of(aim_.item(p, "descriptive_representation_item")))
        t.sample = d->size() > 60 ? d->substr(0, 57) + "..." : *d;
      tallies_.push_back(std::move(t));
    }
    ++tallies_[it->second].count;
  }
}

void Interpreter::report_properties() {
  // In order of first appearance, so that the list reads like the file.
  std::vector<std::pair<std::string, const Tally*>> order;
  for (const auto& [key, index] : tally_index_) order.emplace_back(key.second, &tallies_[index]);
  std::stable_sort(order.begin(), order.end(), [](const auto& a, const auto& b) {
    return a.second->first->offset < b.second->first->offset;
  });
  for (const auto& [name, t] : order) {
    const std::string counted =
        " (" + std::to_string(t->count) + " on " + t->owner + (t->count == 1 ? ")" : "s)");
    if (t->vendor != nullptr) {
      aim_.report(diag::Code::Ap238VendorNote, *t->first,
                  std::string(t->vendor->vendor()) + " property '" + name + "'" + counted +
                      (t->sample.empty() ? "" : ", e.g. '" + t->sample + "'") +
                      ": read, no effect on the canonical program");
    } else {
      aim_.report(diag::Code::Ap238Unmapped, *t->first,
                  "property '" + name + "'" + counted +
                      (t->sample.empty() ? "" : ", e.g. '" + t->sample + "'") +
                      ": not mapped (neither ISO 10303-238 nor a known vendor's), ignored");
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Program structure

void Interpreter::executable(const Instance& e, unsigned depth) {
  if (stopped()) return;
  if (depth > options_.max_nesting) {
    aim_.report(diag::Code::StepncTooDeep, e,
                aim_.describe(e) + " is nested more than " + std::to_string(options_.max_nesting) +
                    " workplans deep");
    return;
  }
  if (!aim_.is_a(e, "machining_process_executable")) {
    not_implemented(e, "an element that is not a MACHINING_PROCESS_EXECUTABLE");
    return;
  }
  if (!on_path_.insert(e.id).second) {
    aim_.report(diag::Code::StepncCycle, e, "#" + std::to_string(e.id) + " contains itself");
    return;
  }
  const std::string description = aim_.text(e, "description");
  const bool structure =
      !aim_.is_a(e, "machining_workplan") && !aim_.is_a(e, "machining_workingstep") &&
      !aim_.is_a(e, "machining_rapid_movement") && !aim_.is_a(e, "machining_nc_function");
  if (structure) properties(e, Owner::Executable);  // the others read their own
  if (aim_.is_a(e, "machining_workplan")) {
    workplan(e, depth);
  } else if (aim_.is_a(e, "machining_workingstep")) {
    workingstep(e);
  } else if (aim_.is_a(e, "machining_rapid_movement")) {
    rapid_movement(e);
  } else if (aim_.is_a(e, "machining_nc_function")) {
    nc_function(e);
  } else if (aim_.is_a(e, "machining_touch_probing")) {
    not_implemented(e, "touch probing");
  } else if (description == "non-sequential") {
    aim_.report(diag::Code::StepncNote, e,
                named(e) + ": non-sequential elements run in file order");
    elements(aim_.related(e, "machining_process_body_relationship"), depth);
  } else if (description == "parallel") {
    aim_.report(diag::Code::StepncNote, e,
                named(e) +
                    ": parallel branches run one after another on this single-channel "
                    "machine");
    elements(aim_.related(e, "machining_process_concurrent_relationship"), depth);
  } else if (description == "selective") {
    const auto branches = aim_.related(e, "machining_process_branch_relationship");
    if (!branches.empty()) {
      aim_.report(diag::Code::StepncNote, e,
                  named(e) + ": a selective runs its first element; the other " +
                      std::to_string(branches.size() - 1) + " are alternatives for the operator");
      executable(*branches.front(), depth + 1);
    }
  } else if (description == "if statement" || description == "while statement") {
    aim_.report(diag::Code::StepncCondition, e,
                named(e) +
                    ": its condition depends on NC variables set while the program runs, which "
                    "a post-processor cannot evaluate; the statement is not executed");
  } else {
    not_implemented(e, "this executable ('" + description + "')");
  }
  on_path_.erase(e.id);
}

void Interpreter::elements(const std::vector<const Instance*>& list, unsigned depth) {
  for (const Instance* e : list) executable(*e, depth + 1);
}

void Interpreter::workplan(const Instance& plan, unsigned depth) {
  properties(plan, Owner::Workplan);
  emit(canon::Begin{canon::Scope::Workplan, entity(plan)});
  const Instance* setup = detail::setup_of(aim_, plan);
  const Instance* setup_product = setup ? detail::product_of(aim_, *setup) : nullptr;
  if (setup_product != nullptr) {
    emit(canon::Begin{canon::Scope::Setup, entity(*setup_product)});
    set_up(*setup);
  }
  elements(aim_.related(plan, "machining_process_sequence_relationship"), depth);
  if (setup_product != nullptr) emit(canon::End{canon::Scope::Setup, entity(*setup_product)});
  emit(canon::End{canon::Scope::Workplan, entity(plan)});
}

// A set-up (its PRODUCT_DEFINITION): its origin on the machine, its workpieces' places in it,
// its security plane. As in ISO 14649: machine ← set-up ← workpiece set-up ← feature.
void Interpreter::set_up(const Instance& setup) {
  const Frame setup_frame = shape_placement(setup).value_or(Frame{});
  workpieces_.clear();
  for (const Instance* r : aim_.referring(setup, "machining_setup_workpiece_relationship",
                                          "relating_product_definition")) {
    const Instance* workpiece = aim_.ref(*r, "related_product_definition");
    if (workpiece == nullptr) continue;
    workpieces_.emplace_back(workpiece,
                             setup_frame.then(workpiece_placement(*r).value_or(Frame{})));
  }
  workpiece_ = workpieces_.empty() ? setup_frame : workpieces_.front().second;
  if (workpieces_.size() > 1)
    aim_.report(diag::Code::StepncNote, setup,
                aim_.describe(setup) + " has " + std::to_string(workpieces_.size()) +
                    " workpiece set-ups; each workingstep uses the one of its feature's workpiece");
  // The set-up's security plane: its property_definition 'security plane'.
  for (const Instance* pd : aim_.referring(setup, "property_definition", "definition")) {
    if (!aim_.text_is(*pd, "name", "security plane")) continue;
    for (const Instance* pdr :
         aim_.referring(*pd, "property_definition_representation", "definition")) {
      const Instance* rep = aim_.ref(*pdr, "used_representation");
      if (rep == nullptr) continue;
      const double mm = aim_.context_units(*rep).mm_per_length;
      for (const Instance* item : aim_.items(*rep))
        if (aim_.is_a(*item, "elementary_surface"))
          if (const Instance* axis = aim_.ref(*item, "position"))
            if (const auto f = placement(*axis, mm))
              machine_.set_security_z(workpiece_.point(f->origin).z);
    }
  }
}

// A workingstep's or rapid movement's 'security plane': a plane whose location gives the height.
void Interpreter::security_plane(const Instance& owner, const std::vector<Property>& props) {
  for (const Property& p : props) {
    if (p.name != "security plane") continue;
    const Instance* plane = aim_.item(p, "elementary_surface");
    const Instance* axis = plane ? aim_.ref(*plane, "position") : nullptr;
    if (axis == nullptr) {
      aim_.report(diag::Code::Ap238BadValue, owner,
                  named(owner) + ": its 'security plane' has no ELEMENTARY_SURFACE item");
      continue;
    }
    const double mm = aim_.context_units(*p.representations.front()).mm_per_length;
    if (const auto f = placement(*axis, mm)) machine_.set_security_z(workpiece_.point(f->origin).z);
  }
}

void Interpreter::nc_function(const Instance& f) {
  const auto props = properties(f, Owner::NcFunction);
  const std::string kind = aim_.text(f, "description");
  const auto value_of = [&](std::string_view name) -> const Property* {
    for (const Property& p : props)
      if (p.name == name) return &p;
    return nullptr;
  };
  // The ARM entity name of the function, as the ISO 14649 interpreter writes it.
  std::string arm = kind;
  for (char& c : arm)
    c = c == ' ' ? '_' : static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  if (kind == "program stop") {
    emit(canon::ProgramStop{});
  } else if (kind == "optional stop") {
    emit(canon::OptionalProgramStop{});
  } else if (kind == "display message") {
    const Property* text = value_of("message text");
    const auto d = text ? aim_.description_of(aim_.item(*text, "descriptive_representation_item"))
                        : std::nullopt;
    emit(canon::Message{d.value_or(detail::arm_name(aim_, f))});
  } else if (kind == "load tool") {
    const auto tools = detail::tools_of(aim_, f);
    if (tools.empty())
      aim_.report(diag::Code::Ap238Missing, f,
                  named(f) + ": no MACHINING_TOOL names it in its usage");
    else
      tool(*tools.front());
  } else if (kind == "unload tool") {
    machine_.unload_tool();
  } else if (kind == "exchange pallet" || kind == "index pallet" || kind == "index table") {
    std::string what = arm;
    if (const Property* index = value_of(kind == "index table" ? "table index" : "pallet index"))
      if (const Instance* item = aim_.item(*index, "measure_representation_item"))
        if (const auto q = aim_.measure(*item))
          what += " " + std::to_string(static_cast<long long>(std::llround(q->value)));
    emit(canon::Message{what});
    emit(canon::ProgramStop{});
  } else if (kind == "set mark" || kind == "wait for mark") {
    emit(canon::Comment{arm + " " + detail::arm_name(aim_, f)});
    aim_.report(diag::Code::StepncNote, f,
                named(f) + ": channel synchronisation has no effect on one channel");
  } else {
    not_implemented(f, "the NC function '" + kind + "'");
  }
}

// ---------------------------------------------------------------------------------------------
// Workingsteps

void Interpreter::workingstep(const Instance& ws) {
  emit(canon::Begin{canon::Scope::Workingstep, entity(ws)});
  const auto props = properties(ws, Owner::Workingstep);
  security_plane(ws, props);
  // The feature's workpiece picks the workpiece set-up; its placement is the toolpaths' frame.
  Frame frame = workpiece_;
  if (const Instance* feature = detail::feature_of(aim_, ws)) {
    const Instance* shape =
        aim_.is_a(*feature, "shape_aspect") ? aim_.ref(*feature, "of_shape") : nullptr;
    const Instance* workpiece = shape ? aim_.ref(*shape, "definition") : nullptr;
    for (const auto& [definition, place] : workpieces_)
      if (definition == workpiece) frame = place;
    if (const auto f = shape_placement(*feature)) frame = frame.then(*f);
  }
  const Instance* operation = detail::operation_of(aim_, ws);
  if (operation == nullptr) {
    aim_.report(diag::Code::Ap238Missing, ws,
                named(ws) + " has no operation (no MACHINING_OPERATION_RELATIONSHIP from it)");
  } else {
    properties(*operation, Owner::Operation);
    const auto tools = detail::tools_of(aim_, *operation);
    if (tools.size() > 1)
      aim_.report(diag::Code::Ap238Ambiguous, *operation,
                  named(*operation) + " is in the usage of " + std::to_string(tools.size()) +
                      " MACHINING_TOOLs; " + aim_.describe(*tools.front()) + " is used");
    if (tools.empty()) {
      aim_.report(diag::Code::Ap238Missing, *operation,
                  named(*operation) + " has no tool (no MACHINING_TOOL names it in its usage)");
    } else if (tool(*tools.front())) {
      technology(*operation);
      functions(*operation);
      toolpaths(*operation, frame, false);
    }
  }
  emit(canon::End{canon::Scope::Workingstep, entity(ws)});
}

void Interpreter::rapid_movement(const Instance& rm) {
  emit(canon::Begin{canon::Scope::Workingstep, entity(rm)});
  security_plane(rm, properties(rm, Owner::Operation));
  // A rapid movement has no feature: its toolpaths are in the workpiece's coordinates.
  toolpaths(rm, workpiece_, true);
  emit(canon::End{canon::Scope::Workingstep, entity(rm)});
}

bool Interpreter::tool(const Instance& t) {
  if (machine_.holds(t.id)) return true;
  properties(t, Owner::Tool);
  const std::string name = detail::arm_name(aim_, t);
  const auto data = detail::tool_data(aim_, t);
  const auto load = stepnc::detail::tool_load(t.id, name, data.assembly_length.value_or(0),
                                              options_.tools ? &*options_.tools : nullptr);
  if (!load) {
    aim_.report(diag::Code::StepncToolTable, t,
                aim_.describe(t) + " '" + name + "' is not in the tool table");
    return false;
  }
  machine_.change_tool(*load);
  return true;
}

// The technology of an operation or a toolpath (its MACHINING_TECHNOLOGY_RELATIONSHIP).
void Interpreter::technology(const Instance& owner) {
  std::size_t count = 0;
  const Instance* tech = aim_.first_related(owner, "machining_technology_relationship", count);
  if (tech == nullptr) return;
  if (count > 1)
    aim_.report(diag::Code::Ap238Ambiguous, owner,
                named(owner) + " has " + std::to_string(count) + " technologies; " +
                    aim_.describe(*tech) + " is used");
  const Technology& t = read_technology(*tech);
  if (t.feed) machine_.feed_rate(*t.feed);
  if (t.spindle) machine_.spindle(*t.spindle);
}

const Technology& Interpreter::read_technology(const Instance& tech) {
  if (const auto known = technologies_.find(tech.id); known != technologies_.end())
    return known->second;
  Technology t;
  for (const Property& p : properties(tech, Owner::Technology)) {
    if (p.name == "feedrate") {
      const Instance* rep = p.representations.empty() ? nullptr : p.representations.front();
      const std::string form = rep ? aim_.text(*rep, "name") : std::string();
      if (form != "feed speed") {
        not_implemented(
            tech, "a feedrate given as '" + form + "' (a 'feed speed', length per time, is read)");
        continue;
      }
      const Instance* item = aim_.item(p, "measure_representation_item", "feed speed");
      const auto q = item ? aim_.measure(*item) : std::nullopt;
      if (!q || q->dimensions != detail::kLengthPerTime) {
        aim_.report(diag::Code::Ap238BadValue, tech,
                    named(tech) +
                        ": its feedrate has no 'feed speed' measure in a length per "
                        "time unit");
        continue;
      }
      t.feed = q->value * kSecondsPerMinute;  // mm/s → mm/min
    } else if (p.name == "spindle") {
      const Instance* rep = p.representations.empty() ? nullptr : p.representations.front();
      const std::string form = rep ? aim_.text(*rep, "name") : std::string();
      if (form != "spindle speed") {
        not_implemented(tech, "a spindle given as '" + form +
                                  "' (a 'spindle speed', revolutions per time, is read)");
        continue;
      }
      const Instance* item = aim_.item(p, "measure_representation_item", "rotational speed");
      const auto q = item ? aim_.measure(*item) : std::nullopt;
      if (!q || q->dimensions != detail::kRevolutionsPerTime) {
        aim_.report(diag::Code::Ap238BadValue, tech,
                    named(tech) +
                        ": its spindle has no 'rotational speed' measure in a "
                        "revolutions per time unit");
        continue;
      }
      // STEP Tools' and NIST's convention: positive counter-clockwise, negative clockwise.
      t.spindle = q->value;
    }
  }
  return technologies_.emplace(tech.id, t).first->second;
}

void Interpreter::functions(const Instance& owner) {
  std::size_t count = 0;
  const Instance* f = aim_.first_related(owner, "machining_functions_relationship", count);
  if (f == nullptr) return;
  if (count > 1)
    aim_.report(diag::Code::Ap238Ambiguous, owner,
                named(owner) + " has " + std::to_string(count) + " machine functions; " +
                    aim_.describe(*f) + " is used");
  const Functions& read = read_functions(*f);
  machine_.coolant(read.flood, read.mist);
}

// 'coolant' ('coolant on'/'coolant off') is flood coolant unless 'coolant type' (ISO 10303-238
// defines it for turning; writers use it for milling too) says 'mist'; 'mist' ('mist on'/'mist
// off') is mist. 'through tool' coolant has no canonical call and is reported.
const Functions& Interpreter::read_functions(const Instance& fi) {
  if (const auto known = functions_.find(fi.id); known != functions_.end()) return known->second;
  std::optional<bool> coolant;
  std::optional<bool> mist;
  std::string type;
  const auto value = [&](const Property& p) {
    return aim_.description_of(aim_.item(p, "descriptive_representation_item")).value_or("");
  };
  for (const Property& p : properties(fi, Owner::Functions)) {
    if (p.name == "coolant") {
      const std::string v = value(p);
      if (v == "coolant on" || v == "coolant off")
        coolant = v == "coolant on";
      else
        aim_.report(diag::Code::Ap238BadValue, fi,
                    named(fi) + ": coolant '" + v + "' is neither 'coolant on' nor 'coolant off'");
    } else if (p.name == "mist") {
      const std::string v = value(p);
      if (v == "mist on" || v == "mist off")
        mist = v == "mist on";
      else
        aim_.report(diag::Code::Ap238BadValue, fi,
                    named(fi) + ": mist '" + v + "' is neither 'mist on' nor 'mist off'");
    } else if (p.name == "coolant type") {
      type = value(p);
    }
  }
  Functions f;
  if (coolant) {
    if (type == "mist") {
      if (!mist) mist = *coolant;
      f.flood = false;
    } else if (type == "through tool") {
      aim_.report(diag::Code::Ap238NotImplemented, fi,
                  named(fi) +
                      ": through-tool coolant has no canonical call; no coolant is "
                      "switched for it");
    } else {
      f.flood = coolant;
    }
  }
  f.mist = mist;
  return functions_.emplace(fi.id, f).first->second;
}

// ---------------------------------------------------------------------------------------------
// Toolpaths

void Interpreter::toolpaths(const Instance& operation, const Frame& frame, bool rapid) {
  const auto paths = aim_.related(operation, "machining_toolpath_sequence_relationship");
  if (paths.empty()) {
    not_implemented(operation,
                    "an operation without toolpaths (feature-based, conformance class 3, in the "
                    "AIM form)");
    return;
  }
  bool first = true;
  for (const Instance* path : paths) {
    if (stopped()) return;
    if (!aim_.is_a(*path, "machining_toolpath")) {
      not_implemented(*path, "a toolpath sequence element that is not a MACHINING_TOOLPATH");
      continue;
    }
    properties(*path, Owner::Toolpath, path_properties_);
    const std::vector<Property>& props = path_properties_;
    const std::string kind = aim_.text(*path, "description");
    const auto find = [&](std::string_view name) -> const Property* {
      for (const Property& p : props)
        if (p.name == name) return &p;
      return nullptr;
    };
    const auto text_of = [&](std::string_view name) -> std::string_view {
      const Property* p = find(name);
      return p ? std::string_view(aim_.described(*p)) : std::string_view();
    };
    if (kind == "feedstop") {
      // A pause in the path: the tool dwells where it is.
      const Property* dwell = find("dwell");
      const Instance* item = dwell ? aim_.item(*dwell, "measure_representation_item") : nullptr;
      const auto q = item ? aim_.measure(*item) : std::nullopt;
      if (q && q->dimensions == detail::kTime && q->value >= 0)
        emit(canon::Dwell{q->value});
      else
        aim_.report(diag::Code::Ap238BadValue, *path,
                    named(*path) + ": a feedstop without a 'dwell' time measure");
      continue;
    }
    if (kind != "cutter location trajectory") {
      not_implemented(*path, "this kind of toolpath ('" + kind +
                                 "'; 'cutter location trajectory' and 'feedstop' are)");
      continue;
    }
    bool rapid_speed = false;
    if (const Property* speed = find("speed profile")) {
      rapid_speed = aim_.described(*speed) == "rapid";
      if (!rapid_speed) not_implemented(*path, "a speed profile other than 'rapid'");
    }
    technology(*path);
    functions(*path);
    auto segments = toolpath_geometry(operation, *path, props);
    if (!segments || segments->empty()) continue;
    if (text_of("direction") == "end to beginning") stepnc::detail::reverse(*segments);
    if (const Property* axis = find("tool axis")) {
      const Instance* curve = aim_.item(*axis, "bounded_curve");
      if (curve == nullptr || !curves_.apply_tool_axis(*segments, *curve))
        not_implemented(*path, "a tool-axis curve other than a polyline matching a polyline path");
    }
    const bool non_contact = text_of("trajectory type") == "non-contact";
    const Vec3 start = frame.point(segments->front().start);
    if (machine_.join(start, first, rapid))
      aim_.report(diag::Code::StepncDiscontinuous, *path,
                  named(*path) + " starts away from where the previous toolpath ended; the tool " +
                      (rapid ? "moves" : "feeds") + " across");
    machine_.motion(*segments, frame, rapid || non_contact || rapid_speed);
    first = false;
  }
}

// The toolpath's 'basic curve' (in its representation's units), else a vendor's geometry;
// without either the toolpath is refused by name (AP238-006), never skipped in silence.
std::optional<std::vector<Segment>> Interpreter::toolpath_geometry(
    const Instance& operation, const Instance& path, const std::vector<Property>& props) {
  for (const Property& p : props) {
    if (p.name != "basic curve") continue;
    const Instance* curve = nullptr;
    const Instance* in = nullptr;
    p.representations.for_each([&](const Instance& rep) {
      if (curve == nullptr && (curve = aim_.first_item(rep, "bounded_curve")) != nullptr) in = &rep;
    });
    if (curve == nullptr) continue;
    const auto units = aim_.context_units(*in);
    curves_.set_units(units.mm_per_length, units.radians_per_angle);
    return curves_.segments(*curve);
  }
  for (const Property& p : props) {
    const detail::VendorAdapter* vendor = vendor_of(p.name);
    if (vendor != nullptr && vendor->is_geometry(p.name))
      return vendor->toolpath_geometry(aim_, operation, path, p, options_.arc_tolerance);
  }
  aim_.report(diag::Code::Ap238NoGeometry, path,
              named(path) +
                  " has no geometry ncpost can read: no 'basic curve' with a bounded curve, no "
                  "vendor geometry (the post stops here rather than skip it)");
  return std::nullopt;
}

// ---------------------------------------------------------------------------------------------
// Placements

std::optional<Frame> Interpreter::placement(const Instance& axis, double mm) {
  auto f = aim_.geometry().placement(p21::Value::reference(axis.id));
  if (f) f->origin = f->origin * mm;
  return f;
}

// The placement of a set-up or a feature: the AXIS2_PLACEMENT_3D (named 'orientation' if several)
// of the shape representation of its property definition.
std::optional<Frame> Interpreter::shape_placement(const Instance& definition) {
  for (const Instance* pd : aim_.referring(definition, "property_definition", "definition")) {
    if (aim_.text_is(*pd, "name", "security plane")) continue;
    for (const Instance* pdr :
         aim_.referring(*pd, "property_definition_representation", "definition")) {
      const Instance* rep = aim_.ref(*pdr, "used_representation");
      if (rep == nullptr || !aim_.is_a(*rep, "shape_representation")) continue;
      const Instance* chosen = nullptr;
      for (const Instance* item : aim_.items(*rep)) {
        if (!aim_.is_a(*item, "axis2_placement_3d")) continue;
        if (chosen == nullptr || aim_.text_is(*item, "name", "orientation")) chosen = item;
      }
      if (chosen != nullptr) return placement(*chosen, aim_.context_units(*rep).mm_per_length);
    }
  }
  return std::nullopt;
}

// A workpiece in its set-up: the transformation of the REPRESENTATION_RELATIONSHIP_WITH_-
// TRANSFORMATION that a CONTEXT_DEPENDENT_SHAPE_REPRESENTATION gives the relationship's shape
// (ISO 10303-44's placement of a product in another): item_1 (in the workpiece's
// representation) lands on item_2 (in the set-up's). Else the placement of the relationship's
// own shape representation.
std::optional<Frame> Interpreter::workpiece_placement(const Instance& relationship) {
  for (const Instance* pds :
       aim_.referring(relationship, "product_definition_shape", "definition")) {
    for (const Instance* cdsr : aim_.referring(*pds, "context_dependent_shape_representation",
                                               "represented_product_relation")) {
      const Instance* rr = aim_.ref(*cdsr, "representation_relation");
      const Instance* t = rr ? aim_.ref(*rr, "transformation_operator") : nullptr;
      if (t == nullptr || !aim_.is_a(*t, "item_defined_transformation")) continue;
      const Instance* rep_1 = aim_.ref(*rr, "rep_1");
      const Instance* rep_2 = aim_.ref(*rr, "rep_2");
      const Instance* a = aim_.ref(*t, "transform_item_1");
      const Instance* b = aim_.ref(*t, "transform_item_2");
      if (rep_1 == nullptr || rep_2 == nullptr || a == nullptr || b == nullptr) continue;
      const auto from = placement(*a, aim_.context_units(*rep_1).mm_per_length);
      const auto to = placement(*b, aim_.context_units(*rep_2).mm_per_length);
      if (from && to) return to->then(stepnc::detail::inverse(*from));
    }
  }
  return shape_placement(relationship);
}

}  // namespace

bool is_aim(const p21::Model& model) noexcept {
  const p21::Instance* header = model.header_entity("FILE_SCHEMA");
  if (header == nullptr || header->count == 0) return false;
  const p21::Value list = model.params(*header)[0];
  if (!list.is_list()) return false;
  for (const p21::Value item : model.items(list)) {
    if (item.kind() != p21::ValueKind::String) continue;
    // The schema name before any ASN.1 object identifier, any case.
    const std::string_view text = model.slice(item);
    std::size_t begin = 0;
    while (begin < text.size() && text[begin] == ' ') ++begin;
    std::size_t end = begin;
    while (end < text.size() && text[end] != ' ' && text[end] != '{') ++end;
    const std::string_view name = text.substr(begin, end - begin);
    constexpr std::string_view kAim = "integrated_cnc_schema";
    if (name.size() == kAim.size() &&
        std::equal(name.begin(), name.end(), kAim.begin(), [](char a, char b) {
          return (a >= 'A' && a <= 'Z' ? char(a - 'A' + 'a') : a) == b;
        }))
      return true;
  }
  return false;
}

stepnc::InterpretResult interpret(const p21::Model& model,
                                  const stepnc::AttributeReader& attributes, canon::Sink& sink,
                                  const stepnc::InterpretOptions& options) {
  return Interpreter(model, attributes, sink, options).run();
}

}  // namespace ncpost::ap238
