#include "ncpost/pipeline/jobs.hpp"

#include "ncpost/ap238/ap238.hpp"
#include "ncpost/canon/json_trace.hpp"
#include "ncpost/canon/trace.hpp"
#include "ncpost/canon/xml.hpp"
#include "ncpost/express/express_x.hpp"
#include "ncpost/express/parse.hpp"
#include "ncpost/p21/writer.hpp"
#include "ncpost/p28/p28.hpp"
#include "ncpost/pipeline/diagnostics.hpp"
#include "ncpost/stepnc/attributes.hpp"

namespace ncpost::pipeline {
namespace {

using Clock = std::chrono::steady_clock;

void append(std::vector<diag::FileDiagnostic>& to, std::vector<diag::FileDiagnostic> more) {
  to.insert(to.end(), std::make_move_iterator(more.begin()), std::make_move_iterator(more.end()));
}

// Notes whether anything reached the sink.
TextSink noting_start(const TextSink& out, bool& started) {
  return [&out, &started](std::string_view piece) {
    started = started || !piece.empty();
    out(piece);
  };
}

// ---- the JSON form of program information (docs/inspect.md) ----

using json = nlohmann::ordered_json;

json to_json(const stepnc::EntityRef& ref) {
  json j;
  j["id"] = ref.id;
  j["type"] = ref.type;
  j["name"] = ref.name ? json(*ref.name) : json(nullptr);
  return j;
}

json to_json(const stepnc::HeaderValue& value) {
  if (const auto* one = std::get_if<std::string>(&value)) return *one;
  if (const auto* list = std::get_if<std::vector<std::string>>(&value)) return *list;
  return nullptr;
}

// The tree as nested objects; recursion is bounded by the inspector's nesting limit.
json to_json(const stepnc::Executable& x) {
  using Shape = stepnc::Executable::Shape;
  if (x.missing) return nullptr;
  json j = to_json(x.self);
  const auto children = [&] {
    json list = json::array();
    for (const auto& child : x.children) list.push_back(to_json(child));
    return list;
  };
  switch (x.shape) {
    case Shape::Workingstep:
      if (x.feature) j["feature"] = to_json(*x.feature);
      if (x.operation) j["operation"] = to_json(*x.operation);
      if (x.tool) j["tool"] = to_json(*x.tool);
      break;
    case Shape::Sequence:
      if (x.setup) j["setup"] = to_json(*x.setup);
      j["elements"] = children();
      break;
    case Shape::Parallel:
      j["branches"] = children();
      break;
    case Shape::If:
      j["true_branch"] = to_json(x.children.at(0));
      j["false_branch"] = to_json(x.children.at(1));
      break;
    case Shape::While:
      j["body"] = to_json(x.children.at(0));
      break;
    case Shape::Message:
      if (x.text) j["text"] = *x.text;
      break;
    case Shape::ToolChange:
      if (x.tool) j["tool"] = to_json(*x.tool);
      break;
    case Shape::Leaf:
      break;
  }
  return j;
}

json header_json(const stepnc::Header& h) {
  json header;
  for (const auto& [name, value] : h.fields) header[name] = to_json(value);
  header["schemas"] = h.schemas;
  return header;
}

json workpieces_json(const stepnc::ProgramInfo& info) {
  json workpieces = json::array();
  for (const auto& w : info.workpieces) {
    json j = to_json(w.self);
    if (w.material) j["material"] = *w.material;
    if (w.clamping_positions) j["clamping_positions"] = *w.clamping_positions;
    workpieces.push_back(std::move(j));
  }
  return workpieces;
}

json tools_json(const stepnc::ProgramInfo& info) {
  json tools = json::array();
  for (const auto& t : info.tools) {
    json j = to_json(t.self);
    j["used_by"] = t.used_by;
    if (t.number) j["number"] = *t.number;
    if (t.body) j["body"] = *t.body;
    if (t.diameter) j["diameter"] = *t.diameter;
    if (t.corner_radius) j["corner_radius"] = *t.corner_radius;
    if (t.length) j["length"] = *t.length;
    tools.push_back(std::move(j));
  }
  return tools;
}

json statistics_json(const stepnc::ProgramInfo& info) {
  json statistics;
  statistics["bytes"] = info.statistics.bytes;
  statistics["instances"] = info.statistics.instances;
  statistics["workingsteps"] = info.statistics.workingsteps;
  statistics["entity_types"] = info.statistics.by_type.size();
  json& by_type = statistics["by_type"] = json::object();
  for (const auto& [name, n] : info.statistics.by_type) by_type[name] = n;
  return statistics;
}

json to_json(const stepnc::ProgramInfo& info) {
  json out;
  out["header"] = header_json(info.header);
  if (info.project) {
    json& project = out["project"];
    project["id"] = info.project->id;
    project["name"] = info.project->name;
    project["main_workplan"] =
        info.project->main_workplan ? to_json(*info.project->main_workplan) : json(nullptr);
  } else {
    out["project"] = nullptr;
  }
  out["workpieces"] = workpieces_json(info);
  out["tools"] = tools_json(info);
  out["statistics"] = statistics_json(info);
  return out;
}

// Writes what nlohmann's dump(2) writes for a document, one member at a time, so that a large
// inspection is never held as a tree of JSON values next to the program information (issue 23:
// `ncpost inspect` of the 104 MB file peaked at 3.7x the file). Small values are dumped whole
// and indented to their depth.
class IndentedJsonWriter {
 public:
  explicit IndentedJsonWriter(const TextSink& out) : out_(out) {}

  void begin(char bracket) {
    separate();
    buffer_ += bracket;
    levels_.push_back({bracket == '{' ? '}' : ']'});
  }
  void end() {
    const Level level = levels_.back();
    levels_.pop_back();
    if (!level.empty) {
      buffer_ += '\n';
      indent();
    }
    buffer_ += level.close;
    flush_when_full();
  }
  void key(std::string_view name) {
    separate();
    buffer_ += json(name).dump();
    buffer_ += ": ";
    after_key_ = true;
  }
  void value(const json& small) {
    separate();
    const std::string text = small.dump(2, ' ', false, json::error_handler_t::replace);
    if (levels_.empty()) {
      buffer_ += text;
    } else {
      for (const char c : text) {
        buffer_ += c;
        if (c == '\n') indent();
      }
    }
    flush_when_full();
  }
  void finish() {
    if (!buffer_.empty()) out_(buffer_);
    buffer_.clear();
  }

 private:
  struct Level {
    char close;
    bool empty = true;
  };
  void separate() {
    if (after_key_) {
      after_key_ = false;
      return;
    }
    if (levels_.empty()) return;
    buffer_ += levels_.back().empty ? "\n" : ",\n";
    levels_.back().empty = false;
    indent();
  }
  void indent() { buffer_.append(2 * levels_.size(), ' '); }
  void flush_when_full() {
    if (buffer_.size() >= kFlushBytes) finish();
  }

  static constexpr std::size_t kFlushBytes = 64 * 1024;
  const TextSink& out_;
  std::string buffer_;
  std::vector<Level> levels_;
  bool after_key_ = false;
};

void write_ref_members(IndentedJsonWriter& w, const stepnc::EntityRef& ref) {
  w.key("id");
  w.value(ref.id);
  w.key("type");
  w.value(ref.type);
  w.key("name");
  w.value(ref.name ? json(*ref.name) : json(nullptr));
}

// The workplan tree as JSON, written as the inspector walks it (or as a built tree is
// replayed): the same members in the same order as to_json(Executable).
class TreeJsonWriter final : public stepnc::TreeVisitor {
 public:
  explicit TreeJsonWriter(IndentedJsonWriter& w) : w_(w) {}

  void begin_project(const stepnc::Project& project) override {
    w_.begin('{');
    w_.key("id");
    w_.value(project.id);
    w_.key("name");
    w_.value(project.name);
    w_.key("main_workplan");
    root_written_ = false;
  }
  void end_project() override {
    if (!root_written_) w_.value(nullptr);
    w_.end();
  }

  void enter(const stepnc::Executable& x) override {
    using Shape = stepnc::Executable::Shape;
    if (!open_.empty()) {
      // An If's and a While's children are members; the others' are array items.
      Open& parent = open_.back();
      if (parent.shape == Shape::If) w_.key(parent.children == 0 ? "true_branch" : "false_branch");
      if (parent.shape == Shape::While) w_.key("body");
      ++parent.children;
    }
    root_written_ = true;
    open_.push_back({x.shape, x.missing});
    if (x.missing) return w_.value(nullptr);
    w_.begin('{');
    write_ref_members(w_, x.self);
    const auto ref = [this](std::string_view name, const auto& optional_ref) {
      if (!optional_ref) return;
      w_.key(name);
      w_.value(to_json(*optional_ref));
    };
    switch (x.shape) {
      case Shape::Workingstep:
        ref("feature", x.feature);
        ref("operation", x.operation);
        ref("tool", x.tool);
        break;
      case Shape::Sequence:
        ref("setup", x.setup);
        w_.key("elements");
        w_.begin('[');
        break;
      case Shape::Parallel:
        w_.key("branches");
        w_.begin('[');
        break;
      case Shape::Message:
        if (x.text) {
          w_.key("text");
          w_.value(*x.text);
        }
        break;
      case Shape::ToolChange:
        ref("tool", x.tool);
        break;
      case Shape::If:
      case Shape::While:
      case Shape::Leaf:
        break;
    }
  }

  void leave(const stepnc::Executable&) override {
    using Shape = stepnc::Executable::Shape;
    const Open node = open_.back();
    open_.pop_back();
    if (node.missing) return;
    if (node.shape == Shape::Sequence || node.shape == Shape::Parallel) w_.end();
    w_.end();
  }

 private:
  struct Open {
    stepnc::Executable::Shape shape;
    bool missing = false;
    std::size_t children = 0;
  };
  IndentedJsonWriter& w_;
  std::vector<Open> open_;
  bool root_written_ = false;
};

// to_json(ProgramInfo) without the document: the workplan tree, the tools and the workpieces
// member by member, the small parts dumped whole.
void write_header(IndentedJsonWriter& w, const stepnc::Header& header) {
  w.key("header");
  w.value(header_json(header));
}

// What follows the project: workpieces, tools and statistics.
void write_program_rest(IndentedJsonWriter& w, const stepnc::ProgramInfo& info) {
  w.key("workpieces");
  w.value(workpieces_json(info));
  w.key("tools");
  w.value(tools_json(info));
  w.key("statistics");
  w.value(statistics_json(info));
}

void write_program_info(IndentedJsonWriter& w, const stepnc::ProgramInfo& info) {
  write_header(w, info.header);
  w.key("project");
  if (info.project) {
    TreeJsonWriter tree(w);
    stepnc::Project project_alone{info.project->id, info.project->name, std::nullopt};
    tree.begin_project(project_alone);
    if (info.project->main_workplan) stepnc::replay(*info.project->main_workplan, tree);
    tree.end_project();
  } else {
    w.value(nullptr);
  }
  write_program_rest(w, info);
}

bool cancelled(const JobContext& context) {
  return context.cancel != nullptr && context.cancel->load(std::memory_order_relaxed);
}

}  // namespace

JobResult trace(Input input, const JobContext& context, TraceFormat format, const TextSink& out) {
  const Program program = read(std::move(input), context);
  JobResult result = read_result(program);
  if (!result.ok) return result;
  const auto started = Clock::now();
  const TextSink sink = noting_start(out, result.started);
  Interpretation interpreted;
  if (format == TraceFormat::Text) {
    canon::TraceWriter trace(sink);
    interpreted = interpret(program, trace, context);
  } else if (format == TraceFormat::Json || format == TraceFormat::JsonDocument) {
    const std::string stock =
        "\"stock\":" +
        stock_json(program).dump(-1, ' ', false, nlohmann::ordered_json::error_handler_t::replace);
    canon::JsonTraceWriter json(
        sink, format == TraceFormat::Json ? canon::JsonLayout::Lines : canon::JsonLayout::Document,
        stock);
    interpreted = interpret(program, json, context);
    // The end record says whether the trace is whole, with every diagnostic so far.
    std::vector<diag::FileDiagnostic> all = result.diagnostics;
    all.insert(all.end(), interpreted.diagnostics.begin(), interpreted.diagnostics.end());
    const bool ok = interpreted.ok && !cancelled(context);
    json.finish("\"ok\":" + std::string(ok ? "true" : "false") +
                ",\"call_count\":" + std::to_string(interpreted.calls) + ",\"diagnostics\":" +
                diagnostics_json(all).dump(-1, ' ', false,
                                           nlohmann::ordered_json::error_handler_t::replace));
  } else {
    canon::XmlDocumentWriter xml(sink);
    canon::Chunker chunker(xml);
    interpreted = interpret(program, chunker, context);
    chunker.finish();
    xml.finish();
  }
  result.work_time = Clock::now() - started;
  result.cancelled = cancelled(context);
  result.ok = interpreted.ok && !result.cancelled;
  append(result.diagnostics, std::move(interpreted.diagnostics));
  return result;
}

nlohmann::ordered_json stock_json(const Program& program) {
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  if (program.loaded.schema == nullptr || !program.text.empty()) return out;
  const stepnc::AttributeReader attributes(program.loaded.model, *program.loaded.schema);
  for (const verify::StockBox& box : verify::stock_boxes(program.loaded.model, attributes)) {
    nlohmann::ordered_json corners = nlohmann::ordered_json::array();
    for (const verify::Position& c : box.corners) corners.push_back({c.x, c.y, c.z});
    nlohmann::ordered_json entry;
    entry["workpiece"] = box.workpiece;
    entry["name"] = box.name;
    entry["setup"] = box.setup == 0 ? nlohmann::ordered_json() : nlohmann::ordered_json(box.setup);
    entry["corners"] = std::move(corners);
    out.push_back(std::move(entry));
  }
  return out;
}

VerifyOutcome verify(Input input, const JobContext& context, const VerifySettings& settings) {
  const Program program = read(std::move(input), context);
  VerifyOutcome outcome;
  outcome.job = read_result(program);
  if (!outcome.job.ok) return outcome;
  verify::VerifyOptions options;
  options.interpret.tools = context.tools;
  options.interpret.cancel = context.cancel;
  options.tolerance = settings.tolerance;
  options.grid = settings.grid;
  const auto started = Clock::now();
  const p21::Model& model = program.loaded.model;
  const stepnc::AttributeReader attributes(model, *program.loaded.schema, program.loaded.mode);
  outcome.result = verify::verify(model, attributes, options);
  outcome.job.work_time = Clock::now() - started;
  outcome.job.cancelled = cancelled(context);
  return outcome;
}

std::string verify_report_text(const VerifyOutcome& outcome, std::string_view name) {
  return outcome.result ? verify::format_text(*outcome.result, name) : std::string();
}

std::string verify_report_json(const VerifyOutcome& outcome, std::string_view name) {
  return outcome.result ? verify::format_json(*outcome.result, name) : std::string();
}

std::vector<diag::FileDiagnostic> verify_diagnostics(const VerifyOutcome& outcome,
                                                     std::string_view name) {
  std::vector<diag::FileDiagnostic> out;
  if (!outcome.result) return out;
  out = diag::with_file(outcome.result->interpreter, name);
  for (const auto& finding : outcome.result->findings)
    out.push_back({std::string(name), finding.diagnostic});
  return out;
}

namespace {

// Reads the program and inspects it. With `json_out`, an ISO 14649 program's inspection is
// written as JSON while the inspector walks the model, so that the workplan tree is never held
// next to the model (issue 23: `ncpost inspect` of the 104 MB file); the returned main workplan
// is then its root alone. Other inspections are written whole at the end.
// How run_inspection writes what it finds as it goes: not at all (the caller formats the tree),
// as JSON, or as text.
enum class Written : std::uint8_t { Not, Json, Text };

void write_inspection(const Inspection& inspection, Written form, const TextSink& out) {
  if (form == Written::Json) write_inspection_json(inspection, out);
  if (form == Written::Text) out(inspection_text(inspection));
}

Inspection run_inspection(Input input, const JobContext& context, Written form,
                          const TextSink& out) {
  ReadOptions options;
  options.name_what_is_not_a_program = false;  // the structure report below says it
  Program program = read(std::move(input), context, options);
  const bool has_model =
      program.cancelled ||
      require_model(program, "inspect", "trace it (ncpost trace, POST /v1/traces) instead");
  Inspection inspection;
  inspection.job = read_result(program);
  if (program.cancelled || !has_model) {
    write_inspection(inspection, form, out);
    return inspection;
  }
  const auto started = Clock::now();
  const p21::Model& model = program.loaded.model;
  // The structure's diagnostics join the reading's, and decide whether the job is ok.
  const auto conclude = [&] {
    inspection.job.work_time = Clock::now() - started;
    append(inspection.job.diagnostics, diag::with_file(inspection.info.diagnostics, program.name));
    inspection.job.ok = !diag::has_errors(inspection.job.diagnostics);
  };
  const bool aim = ap238::is_aim(model);
  // An AP238 AIM program is inspected into a tree, then written whole.
  if (form == Written::Not || aim) {
    if (aim) {
      inspection.info = ap238::inspect(model, *program.loaded.schema);
    } else {
      stepnc::InspectOptions inspect_options;
      inspect_options.mode = program.loaded.mode;
      inspection.info = stepnc::inspect(model, *program.loaded.schema, inspect_options);
    }
    conclude();
    write_inspection(inspection, form, out);
    return inspection;
  }
  stepnc::InspectOptions inspect_options;
  inspect_options.mode = program.loaded.mode;
  if (form == Written::Text) {
    stepnc::TextWriter text(stepnc::read_header(model), out);
    inspect_options.visitor = &text;
    inspection.info = stepnc::inspect(model, *program.loaded.schema, inspect_options);
    text.finish(inspection.info);
    conclude();
    return inspection;
  }
  IndentedJsonWriter w(out);
  w.begin('{');
  write_header(w, stepnc::read_header(model));
  w.key("project");
  TreeJsonWriter tree(w);
  inspect_options.visitor = &tree;
  inspection.info = stepnc::inspect(model, *program.loaded.schema, inspect_options);
  if (!inspection.info.project) w.value(nullptr);
  write_program_rest(w, inspection.info);
  conclude();
  w.key("diagnostics");
  w.value(diagnostics_json(inspection.job.diagnostics));
  w.end();
  w.finish();
  return inspection;
}

}  // namespace

Inspection inspect(Input input, const JobContext& context) {
  return run_inspection(std::move(input), context, Written::Not, [](std::string_view) {});
}

Inspection inspect_to_json(Input input, const JobContext& context, const TextSink& out) {
  return run_inspection(std::move(input), context, Written::Json, out);
}

Inspection inspect_to_text(Input input, const JobContext& context, const TextSink& out) {
  return run_inspection(std::move(input), context, Written::Text, out);
}

nlohmann::ordered_json program_info_json(const stepnc::ProgramInfo& info) {
  return to_json(info);
}

nlohmann::ordered_json inspection_json(const Inspection& inspection) {
  nlohmann::ordered_json json = to_json(inspection.info);
  json["diagnostics"] = diagnostics_json(inspection.job.diagnostics);
  return json;
}

void write_inspection_json(const Inspection& inspection, const TextSink& out) {
  IndentedJsonWriter w(out);
  w.begin('{');
  write_program_info(w, inspection.info);
  w.key("diagnostics");
  w.value(diagnostics_json(inspection.job.diagnostics));
  w.end();
  w.finish();
}

std::string inspection_text(const Inspection& inspection) {
  return stepnc::format_text(inspection.info);
}

JobResult convert(Input input, const JobContext& context, ConvertTo to, const TextSink& out) {
  ReadOptions options;
  options.validate = false;
  Program program = read(std::move(input), context, options);
  if (program.ok()) (void)require_model(program, "convert", "it has no P21/P28 form to convert to");
  JobResult result = read_result(program);
  if (!result.ok) return result;
  const auto started = Clock::now();
  const TextSink sink = noting_start(out, result.started);
  if (to == ConvertTo::P21) {
    p21::write(program.loaded.model, sink);
  } else {
    const auto notes =
        p28::write(program.loaded.model, program.loaded.schema,
                   to == ConvertTo::P28Early ? p28::Binding::Early : p28::Binding::Late, sink);
    append(result.diagnostics, diag::with_file(notes, program.name));
  }
  result.work_time = Clock::now() - started;
  return result;
}

JobResult schema_to_xml(std::string_view express_text, std::string_view name, const TextSink& out) {
  const auto started = Clock::now();
  const express::ParseResult parsed = express::parse_express(express_text);
  JobResult result;
  result.diagnostics = diag::with_file(parsed.diagnostics, name);
  result.ok = parsed.ok();
  if (!result.ok) return result;
  const std::string xml = express::to_express_x(parsed.schemas);
  result.started = !xml.empty();
  out(xml);
  result.work_time = Clock::now() - started;
  return result;
}

}  // namespace ncpost::pipeline
