#include "ncpost/pipeline/jobs.hpp"

#include "ncpost/ap238/ap238.hpp"
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

json to_json(const stepnc::ProgramInfo& info) {
  json out;
  json& header = out["header"];
  for (const auto& [name, value] : info.header.fields) header[name] = to_json(value);
  header["schemas"] = info.header.schemas;
  if (info.project) {
    json& project = out["project"];
    project["id"] = info.project->id;
    project["name"] = info.project->name;
    project["main_workplan"] =
        info.project->main_workplan ? to_json(*info.project->main_workplan) : json(nullptr);
  } else {
    out["project"] = nullptr;
  }
  json& workpieces = out["workpieces"] = json::array();
  for (const auto& w : info.workpieces) {
    json j = to_json(w.self);
    if (w.material) j["material"] = *w.material;
    if (w.clamping_positions) j["clamping_positions"] = *w.clamping_positions;
    workpieces.push_back(std::move(j));
  }
  json& tools = out["tools"] = json::array();
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
  json& statistics = out["statistics"];
  statistics["bytes"] = info.statistics.bytes;
  statistics["instances"] = info.statistics.instances;
  statistics["workingsteps"] = info.statistics.workingsteps;
  statistics["entity_types"] = info.statistics.by_type.size();
  json& by_type = statistics["by_type"] = json::object();
  for (const auto& [name, n] : info.statistics.by_type) by_type[name] = n;
  return out;
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

Inspection inspect(Input input, const JobContext& context) {
  ReadOptions options;
  options.name_what_is_not_a_program = false;  // the structure report below says it
  Program program = read(std::move(input), context, options);
  const bool has_model =
      program.cancelled ||
      require_model(program, "inspect", "trace it (ncpost trace, POST /v1/traces) instead");
  Inspection inspection;
  inspection.job = read_result(program);
  if (program.cancelled || !has_model) return inspection;
  const auto started = Clock::now();
  const p21::Model& model = program.loaded.model;
  stepnc::InspectOptions inspect_options;
  inspect_options.mode = program.loaded.mode;
  inspection.info = ap238::is_aim(model)
                        ? ap238::inspect(model, *program.loaded.schema)
                        : stepnc::inspect(model, *program.loaded.schema, inspect_options);
  inspection.job.work_time = Clock::now() - started;
  append(inspection.job.diagnostics, diag::with_file(inspection.info.diagnostics, program.name));
  inspection.job.ok = !diag::has_errors(inspection.job.diagnostics);
  return inspection;
}

nlohmann::ordered_json program_info_json(const stepnc::ProgramInfo& info) {
  return to_json(info);
}

nlohmann::ordered_json inspection_json(const Inspection& inspection) {
  nlohmann::ordered_json json = to_json(inspection.info);
  json["diagnostics"] = diagnostics_json(inspection.job.diagnostics);
  return json;
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
