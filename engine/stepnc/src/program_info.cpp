#include "ncpost/stepnc/program_info.hpp"

#include <algorithm>
#include <map>
#include <unordered_set>

#include "ncpost/p21/reader.hpp"
#include "ncpost/stepnc/attributes.hpp"

namespace ncpost::stepnc {
namespace {

using nlohmann::ordered_json;
using p21::Instance;
using p21::Model;
using p21::Value;
using p21::ValueKind;

// JSON for a header or attribute value that is a string, a list of strings, or unset.
ordered_json text_value(const Model& model, Value v) {
  if (v.kind() == ValueKind::String) return model.as_string(v);
  if (v.is_list()) {
    ordered_json list = ordered_json::array();
    for (Value item : model.items(v))
      if (item.kind() == ValueKind::String) list.push_back(model.as_string(item));
    return list;
  }
  return nullptr;
}

class Inspector {
 public:
  Inspector(const Model& model, const express::SchemaSet& schema, const InspectOptions& options)
      : model_(model), attributes_(model, schema), options_(options), lines_(model.text()) {}

  ProgramInfo run() {
    ordered_json out;
    out["header"] = header_json(model_);
    out["project"] = project();
    out["workpieces"] = workpieces_;
    out["tools"] = tools();
    out["statistics"] = statistics_json(model_, workingsteps_);
    return {std::move(out), std::move(diagnostics_)};
  }

 private:
  void report(diag::Code code, const Instance& at, std::string message) {
    const auto pos = lines_.at(at.offset);
    diagnostics_.push_back(diag::make(code, pos.line, pos.column, std::move(message)));
  }
  static std::string name_of(const Instance& i) { return "#" + std::to_string(i.id); }

  const Instance* deref(std::optional<Value> v) const {
    if (!v || !v->is_reference()) return nullptr;
    return model_.find(v->id());
  }
  std::optional<Value> attribute(const Instance& inst, std::string_view name) const {
    return attributes_.get(inst, name);
  }
  std::optional<std::string> string_attribute(const Instance& inst, std::string_view name) const {
    auto v = attribute(inst, name);
    if (!v || v->kind() != ValueKind::String) return std::nullopt;
    return model_.as_string(*v);
  }
  // id, entity and its_id: every ISO 14649 executable, feature, operation, tool and workpiece
  // has an its_id, wherever its entity's layout puts it.
  ordered_json ref_summary(const Instance& inst) const {
    ordered_json j;
    j["id"] = inst.id;
    j["type"] = std::string(model_.type_name(inst));
    auto name = string_attribute(inst, "its_id");
    j["name"] = name ? ordered_json(*name) : ordered_json(nullptr);
    return j;
  }

  ordered_json project() {
    const auto projects = model_.instances_of("PROJECT");
    if (projects.empty()) {
      diagnostics_.push_back(no_program_diagnostic(model_));
      return nullptr;
    }
    if (projects.size() > 1)
      report(diag::Code::StepncManyProjects, *projects[1],
             std::to_string(projects.size()) + " PROJECT instances; " + name_of(*projects[0]) +
                 " is used");
    const Instance& p = *projects[0];
    ordered_json j;
    j["id"] = p.id;
    j["name"] = string_attribute(p, "its_id").value_or("");
    if (auto ws = attribute(p, "its_workpieces"); ws && ws->is_list()) {
      for (Value w : model_.items(*ws)) {
        const Instance* wp = model_.find(w.is_reference() ? w.id() : 0);
        if (wp == nullptr) continue;
        ordered_json wj = ref_summary(*wp);
        if (const Instance* mat = deref(attribute(*wp, "its_material")))
          wj["material"] = string_attribute(*mat, "material_identifier").value_or("");
        if (auto cp = attribute(*wp, "clamping_positions"); cp && cp->is_list())
          wj["clamping_positions"] = cp->count();
        workpieces_.push_back(std::move(wj));
      }
    }
    const Instance* main = deref(attribute(p, "main_workplan"));
    if (main == nullptr || !attributes_.is_a(*main, "workplan")) {
      report(diag::Code::StepncWrongType, p,
             "PROJECT " + name_of(p) + " attribute main_workplan does not refer to a WORKPLAN");
      j["main_workplan"] = nullptr;
    } else {
      j["main_workplan"] = executable(*main, 0);
    }
    return j;
  }

  ordered_json elements(const Instance& owner, std::optional<Value> list, unsigned depth) {
    ordered_json out = ordered_json::array();
    if (!list || !list->is_list()) {
      if (list && !list->is_omitted())
        report(diag::Code::StepncBadAttribute, owner,
               name_of(owner) + " has an element list that is not a list");
      return out;
    }
    for (Value v : model_.items(*list)) {
      const Instance* e = v.is_reference() ? model_.find(v.id()) : nullptr;
      if (e == nullptr) {
        report(diag::Code::StepncBadAttribute, owner,
               name_of(owner) + " has an element that is not a reference to an instance");
        continue;
      }
      out.push_back(executable(*e, depth + 1));
    }
    return out;
  }

  ordered_json executable(const Instance& e, unsigned depth) {
    ordered_json j = ref_summary(e);
    if (!attributes_.is_executable(e)) {
      report(diag::Code::StepncUnknownExecutable, e,
             name_of(e) + " (" + std::string(model_.type_name(e)) +
                 ") is not an executable that this version understands");
      return j;
    }
    if (depth > options_.max_nesting) {
      report(diag::Code::StepncTooDeep, e,
             name_of(e) + " is nested more than " + std::to_string(options_.max_nesting) +
                 " workplans deep");
      return j;
    }
    if (!on_path_.insert(e.id).second) {
      report(diag::Code::StepncCycle, e, name_of(e) + " contains itself");
      return j;
    }
    // Subtypes count: the schema decides what is a workplan, a workingstep, a tool change.
    const auto is = [&](std::string_view entity) { return attributes_.is_a(e, entity); };
    if (is("machining_workingstep")) {
      ++workingsteps_;
      if (const Instance* f = deref(attribute(e, "its_feature"))) j["feature"] = ref_summary(*f);
      if (const Instance* op = deref(attribute(e, "its_operation"))) {
        j["operation"] = ref_summary(*op);
        if (const Instance* tool = deref(attribute(*op, "its_tool"))) {
          j["tool"] = ref_summary(*tool);
          note_tool(*tool, e);
        }
      } else {
        report(diag::Code::StepncBadAttribute, e,
               name_of(e) + " attribute its_operation does not refer to an instance");
      }
    } else if (is("workplan") || is("non_sequential") || is("selective")) {
      j["elements"] = elements(e, attribute(e, "its_elements"), depth);
    } else if (is("parallel")) {
      j["branches"] = elements(e, attribute(e, "branches"), depth);
    } else if (is("if_statement")) {
      for (std::string_view branch : {"true_branch", "false_branch"}) {
        const Instance* b = deref(attribute(e, branch));
        j[std::string(branch)] = b ? executable(*b, depth + 1) : ordered_json(nullptr);
      }
    } else if (is("while_statement")) {
      const Instance* body = deref(attribute(e, "body"));
      j["body"] = body ? executable(*body, depth + 1) : ordered_json(nullptr);
    } else if (is("display_message")) {
      if (auto text = string_attribute(e, "its_text")) j["text"] = *text;
    } else if (is("load_tool") || is("unload_tool")) {
      if (const Instance* tool = deref(attribute(e, "its_tool"))) {
        j["tool"] = ref_summary(*tool);
        note_tool(*tool, e);
      }
    }
    on_path_.erase(e.id);
    return j;
  }

  void note_tool(const Instance& tool, const Instance& user) {
    auto it =
        std::find_if(tools_.begin(), tools_.end(), [&](const auto& t) { return t.first == &tool; });
    if (it == tools_.end()) {
      tools_.emplace_back(&tool, std::vector<std::uint64_t>{});
      it = tools_.end() - 1;
    }
    it->second.push_back(user.id);
  }

  ordered_json tools() const {
    ordered_json out = ordered_json::array();
    for (const auto& [tool, users] : tools_) {
      ordered_json j = ref_summary(*tool);
      j["used_by"] = users;
      out.push_back(std::move(j));
    }
    return out;
  }

  const Model& model_;
  AttributeReader attributes_;
  const InspectOptions& options_;
  p21::LineIndex lines_;
  std::vector<diag::Diagnostic> diagnostics_;
  ordered_json workpieces_ = ordered_json::array();
  std::vector<std::pair<const Instance*, std::vector<std::uint64_t>>> tools_;
  std::unordered_set<std::uint64_t> on_path_;
  std::size_t workingsteps_ = 0;
};

}  // namespace

ordered_json header_json(const p21::Model& model) {
  ordered_json h;
  static constexpr std::pair<std::string_view, std::array<std::string_view, 7>> kFields[] = {
      {"FILE_DESCRIPTION", {"description", "implementation_level"}},
      {"FILE_NAME",
       {"name", "time_stamp", "author", "organization", "preprocessor_version",
        "originating_system", "authorization"}},
  };
  for (const auto& [entity, fields] : kFields) {
    const Instance* inst = model.header_entity(entity);
    for (std::size_t i = 0; i < fields.size() && !fields[i].empty(); ++i) {
      ordered_json value = nullptr;
      if (inst != nullptr && i < inst->count) value = text_value(model, model.params(*inst)[i]);
      h[std::string(fields[i])] = value;
    }
  }
  ordered_json schemas = ordered_json::array();
  if (const Instance* fs = model.header_entity("FILE_SCHEMA"); fs && fs->count > 0)
    schemas = text_value(model, model.params(*fs)[0]);
  h["schemas"] = schemas;
  return h;
}

ordered_json statistics_json(const p21::Model& model, std::size_t workingsteps) {
  ordered_json s;
  s["bytes"] = model.text().size();
  s["instances"] = model.instances().size();
  s["workingsteps"] = workingsteps;
  std::map<std::string, std::size_t> by_type;
  for (p21::KeywordId k = 0; k < model.keyword_count(); ++k) {
    const auto n = model.instance_indices_of(k).size();
    if (n == 0) continue;
    if (k == Model::kComplexKeyword) {
      for (std::uint32_t index : model.instance_indices_of(k)) {
        std::string name;
        for (Value record : model.params(model.instances()[index])) {
          if (!name.empty()) name += '+';
          name += model.keyword(record.keyword_id());
        }
        ++by_type["(" + name + ")"];
      }
      continue;
    }
    by_type[std::string(model.keyword(k))] += n;
  }
  s["entity_types"] = by_type.size();
  ordered_json counts = ordered_json::object();
  for (const auto& [name, n] : by_type) counts[name] = n;
  s["by_type"] = std::move(counts);
  return s;
}

ProgramInfo inspect(const p21::Model& model, const express::SchemaSet& schema,
                    const InspectOptions& options) {
  return Inspector(model, schema, options).run();
}

ProgramInfo inspect(const p21::Model& model, const express::SchemaRegistry& schemas,
                    const InspectOptions& options) {
  express::SchemaSelection selection = schemas.select_or_builtin(model);
  ProgramInfo info = inspect(model, *selection.set(), options);
  selection.diagnostics.insert(selection.diagnostics.end(), info.diagnostics.begin(),
                               info.diagnostics.end());
  info.diagnostics = std::move(selection.diagnostics);
  return info;
}

diag::Diagnostic no_program_diagnostic(const p21::Model& model) {
  const bool aim = model.keyword_id("MACHINING_PROJECT").has_value() ||
                   model.keyword_id("PRODUCT_DEFINITION_PROCESS").has_value();
  if (aim)
    return diag::make(diag::Code::StepncAimNotSupported, 0, 0,
                      "this is an AP238 AIM file (MACHINING_PROJECT in the integrated CNC "
                      "schema), not an ISO 14649 ARM program: the AP238 interpreter reads it, "
                      "the ISO 14649 one does not");
  return diag::make(diag::Code::StepncNoProject, 0, 0,
                    "no PROJECT instance: not an ISO 14649 program");
}

nlohmann::ordered_json diagnostics_json(const std::vector<diag::Diagnostic>& list,
                                        std::string_view file) {
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  for (const auto& d : list) {
    nlohmann::ordered_json j;
    j["file"] = std::string(file);
    j["line"] = d.line;
    j["column"] = d.column;
    j["severity"] = std::string(diag::to_string(d.severity));
    j["code"] = std::string(d.code_id());
    j["message"] = d.message;
    out.push_back(std::move(j));
  }
  return out;
}

namespace {

std::string display(const nlohmann::ordered_json& node) {
  std::string s = "#" + std::to_string(node.value("id", std::uint64_t{0})) + " " +
                  node.value("type", std::string{});
  if (node.contains("name") && node["name"].is_string())
    s += " '" + node["name"].get<std::string>() + "'";
  return s;
}

// Explicit stack: the tree was bounded when it was built, but printing need not rely on that.
void append_tree(const nlohmann::ordered_json& root, std::string& out) {
  struct Item {
    const nlohmann::ordered_json* node;
    std::string indent;
    std::string label;
  };
  std::vector<Item> stack{{&root, "  ", ""}};
  while (!stack.empty()) {
    Item item = std::move(stack.back());
    stack.pop_back();
    const auto& node = *item.node;
    out += item.indent + item.label + display(node);
    if (node.contains("feature") && node["feature"].is_object())
      out += "\n" + item.indent + "    feature:   " + display(node["feature"]);
    if (node.contains("operation") && node["operation"].is_object())
      out += "\n" + item.indent + "    operation: " + display(node["operation"]);
    if (node.contains("tool") && node["tool"].is_object())
      out += "\n" + item.indent + "    tool:      " + display(node["tool"]);
    if (node.contains("text")) out += "\n" + item.indent + "    text: " + node["text"].dump();
    out += '\n';
    std::vector<Item> children;
    for (const char* key : {"elements", "branches"})
      if (node.contains(key))
        for (const auto& child : node[key]) children.push_back({&child, item.indent + "  ", ""});
    for (const char* key : {"true_branch", "false_branch", "body"})
      if (node.contains(key) && node[key].is_object())
        children.push_back({&node[key], item.indent + "  ", std::string(key) + ": "});
    for (auto it = children.rbegin(); it != children.rend(); ++it) stack.push_back(std::move(*it));
  }
}

}  // namespace

std::string format_text(const nlohmann::ordered_json& info) {
  std::string out;
  const auto& h = info["header"];
  const auto str = [](const nlohmann::ordered_json& v) {
    if (v.is_string()) return v.get<std::string>();
    if (v.is_array()) {
      std::string s;
      for (const auto& x : v) s += (s.empty() ? "" : ", ") + x.get<std::string>();
      return s;
    }
    return std::string("-");
  };
  out += "file:        " + str(h["name"]) + " (" + str(h["time_stamp"]) + ")\n";
  out += "description: " + str(h["description"]) + "\n";
  out += "author:      " + str(h["author"]) + " / " + str(h["organization"]) + "\n";
  out += "schemas:     " + str(h["schemas"]) + "\n";
  if (info["project"].is_object()) {
    const auto& p = info["project"];
    out += "project:     #" + std::to_string(p["id"].get<std::uint64_t>()) + " '" +
           p["name"].get<std::string>() + "'\n";
    if (p["main_workplan"].is_object()) append_tree(p["main_workplan"], out);
  } else {
    out += "project:     none\n";
  }
  for (const auto& w : info["workpieces"]) out += "workpiece:   " + display(w) + "\n";
  for (const auto& t : info["tools"]) out += "tool:        " + display(t) + "\n";
  const auto& s = info["statistics"];
  out += "instances:   " + std::to_string(s["instances"].get<std::size_t>()) + " of " +
         std::to_string(s["entity_types"].get<std::size_t>()) + " entity types\n";
  return out;
}

}  // namespace ncpost::stepnc
