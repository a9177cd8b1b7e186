#include "ncpost/stepnc/program_info.hpp"

#include <algorithm>
#include <array>
#include <cstdio>
#include <map>
#include <unordered_set>

#include "ncpost/p21/reader.hpp"
#include "ncpost/stepnc/attributes.hpp"

namespace ncpost::stepnc {
namespace {

using p21::Instance;
using p21::Model;
using p21::Value;
using p21::ValueKind;

// A header or attribute value that is a string, a list of strings, or unset.
HeaderValue text_value(const Model& model, Value v) {
  if (v.kind() == ValueKind::String) return model.as_string(v);
  if (v.is_list()) {
    std::vector<std::string> list;
    for (Value item : model.items(v))
      if (item.kind() == ValueKind::String) list.push_back(model.as_string(item));
    return list;
  }
  return std::monostate{};
}

}  // namespace

Header read_header(const Model& model) {
  Header h;
  static constexpr std::pair<std::string_view, std::array<std::string_view, 7>> kFields[] = {
      {"FILE_DESCRIPTION", {"description", "implementation_level"}},
      {"FILE_NAME",
       {"name", "time_stamp", "author", "organization", "preprocessor_version",
        "originating_system", "authorization"}},
  };
  for (const auto& [entity, fields] : kFields) {
    const Instance* inst = model.header_entity(entity);
    for (std::size_t i = 0; i < fields.size() && !fields[i].empty(); ++i) {
      HeaderValue value;
      if (inst != nullptr && i < inst->count) value = text_value(model, model.params(*inst)[i]);
      h.fields.emplace_back(std::string(fields[i]), std::move(value));
    }
  }
  if (const Instance* fs = model.header_entity("FILE_SCHEMA"); fs && fs->count > 0) {
    HeaderValue schemas = text_value(model, model.params(*fs)[0]);
    if (auto* list = std::get_if<std::vector<std::string>>(&schemas))
      h.schemas = std::move(*list);
    else if (auto* one = std::get_if<std::string>(&schemas))
      h.schemas = {std::move(*one)};
  }
  return h;
}

Statistics count_instances(const Model& model, std::size_t workingsteps) {
  Statistics s;
  s.bytes = model.text().size();
  s.instances = model.instances().size();
  s.workingsteps = workingsteps;
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
        ++s.by_type["(" + name + ")"];
      }
      continue;
    }
    s.by_type[std::string(model.keyword(k))] += n;
  }
  return s;
}

namespace {

class Inspector {
 public:
  Inspector(const Model& model, const express::SchemaSet& schema, const InspectOptions& options)
      : model_(model),
        attributes_(model, schema, options.mode),
        options_(options),
        lines_(model.text()) {}

  ProgramInfo run() {
    info_.header = read_header(model_);
    info_.project = project();
    info_.statistics = count_instances(model_, workingsteps_);
    return std::move(info_);
  }

 private:
  void report(diag::Code code, const Instance& at, std::string message) {
    const auto pos = lines_.at(at.offset);
    info_.diagnostics.push_back(diag::make(code, pos.line, pos.column, std::move(message)));
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
  EntityRef ref(const Instance& inst) const {
    return {inst.id, std::string(model_.type_name(inst)), string_attribute(inst, "its_id")};
  }

  std::optional<Project> project() {
    const auto projects = model_.instances_of("PROJECT");
    if (projects.empty()) {
      info_.diagnostics.push_back(no_program_diagnostic(model_));
      return std::nullopt;
    }
    if (projects.size() > 1)
      report(diag::Code::StepncManyProjects, *projects[1],
             std::to_string(projects.size()) + " PROJECT instances; " + name_of(*projects[0]) +
                 " is used");
    const Instance& p = *projects[0];
    Project project;
    project.id = p.id;
    project.name = string_attribute(p, "its_id").value_or("");
    note_workpieces(p);
    const Instance* main = deref(attribute(p, "main_workplan"));
    if (options_.visitor) options_.visitor->begin_project(project);
    if (main == nullptr || !attributes_.is_a(*main, "workplan"))
      report(diag::Code::StepncWrongType, p,
             "PROJECT " + name_of(p) + " attribute main_workplan does not refer to a WORKPLAN");
    else
      project.main_workplan = executable(*main, 0);
    if (options_.visitor) options_.visitor->end_project();
    return project;
  }

  void note_workpieces(const Instance& project) {
    auto list = attribute(project, "its_workpieces");
    if (!list || !list->is_list()) return;
    for (Value w : model_.items(*list)) {
      const Instance* wp = model_.find(w.is_reference() ? w.id() : 0);
      if (wp == nullptr) continue;
      Workpiece workpiece{ref(*wp), std::nullopt, std::nullopt};
      if (const Instance* mat = deref(attribute(*wp, "its_material")))
        workpiece.material = string_attribute(*mat, "material_identifier").value_or("");
      if (auto cp = attribute(*wp, "clamping_positions"); cp && cp->is_list())
        workpiece.clamping_positions = cp->count();
      info_.workpieces.push_back(std::move(workpiece));
    }
  }

  // Where an executable's children are: the instances of a list attribute (a workplan's
  // elements, a parallel's branches), or single attributes (an If's branches, a While's body).
  struct Children {
    std::string_view list;
    std::vector<std::string_view> singles;
    bool on_path = false;  // `e` was put on the path, and leaves it after its children
  };

  // `e` and everything under it: handed to the visitor as it is read, or returned whole.
  Executable executable(const Instance& e, unsigned depth) {
    Executable x;
    const Children children = read_node(e, depth, x);
    TreeVisitor* const visitor = options_.visitor;
    if (visitor) visitor->enter(x);
    if (!children.list.empty()) elements(e, attribute(e, children.list), depth, x);
    for (std::string_view single : children.singles) add(x, branch(e, single, depth));
    if (children.on_path) on_path_.erase(e.id);
    if (visitor) visitor->leave(x);
    return x;
  }

  // The child goes to the parent's children unless a visitor has had it.
  void add(Executable& parent, Executable&& child) const {
    if (!options_.visitor) parent.children.push_back(std::move(child));
  }

  // `e` into `x` without its children; which children it has.
  Children read_node(const Instance& e, unsigned depth, Executable& x) {
    x.self = ref(e);
    if (!attributes_.is_executable(e)) {
      report(diag::Code::StepncUnknownExecutable, e,
             name_of(e) + " (" + std::string(model_.type_name(e)) +
                 ") is not an executable that this version understands");
      return {};
    }
    if (depth > options_.max_nesting) {
      report(diag::Code::StepncTooDeep, e,
             name_of(e) + " is nested more than " + std::to_string(options_.max_nesting) +
                 " workplans deep");
      return {};
    }
    if (!on_path_.insert(e.id).second) {
      report(diag::Code::StepncCycle, e, name_of(e) + " contains itself");
      return {};
    }
    Children children;
    children.on_path = true;
    // Subtypes count: the schema decides what is a workplan, a workingstep, a tool change.
    const auto is = [&](std::string_view entity) { return attributes_.is_a(e, entity); };
    if (is("machining_workingstep")) {
      x.shape = Executable::Shape::Workingstep;
      ++workingsteps_;
      if (const Instance* f = deref(attribute(e, "its_feature"))) x.feature = ref(*f);
      if (const Instance* op = deref(attribute(e, "its_operation"))) {
        x.operation = ref(*op);
        if (const Instance* tool = deref(attribute(*op, "its_tool"))) {
          x.tool = ref(*tool);
          note_tool(*tool, e);
        }
      } else {
        report(diag::Code::StepncBadAttribute, e,
               name_of(e) + " attribute its_operation does not refer to an instance");
      }
    } else if (is("workplan") || is("non_sequential") || is("selective")) {
      x.shape = Executable::Shape::Sequence;
      children.list = "its_elements";
    } else if (is("parallel")) {
      x.shape = Executable::Shape::Parallel;
      children.list = "branches";
    } else if (is("if_statement")) {
      x.shape = Executable::Shape::If;
      children.singles = {"true_branch", "false_branch"};
    } else if (is("while_statement")) {
      x.shape = Executable::Shape::While;
      children.singles = {"body"};
    } else if (is("display_message")) {
      x.shape = Executable::Shape::Message;
      x.text = string_attribute(e, "its_text");
    } else if (is("load_tool") || is("unload_tool")) {
      x.shape = Executable::Shape::ToolChange;
      if (const Instance* tool = deref(attribute(e, "its_tool"))) {
        x.tool = ref(*tool);
        note_tool(*tool, e);
      }
    }
    return children;
  }

  void elements(const Instance& owner, std::optional<Value> list, unsigned depth,
                Executable& parent) {
    if (!list || !list->is_list()) {
      if (list && !list->is_omitted())
        report(diag::Code::StepncBadAttribute, owner,
               name_of(owner) + " has an element list that is not a list");
      return;
    }
    // Exactly as many as the list holds: a workplan of 40,000 workingsteps would otherwise leave
    // up to as many unused slots of a large struct (issue 23: 16, inspect's memory).
    if (!options_.visitor) parent.children.reserve(model_.items(*list).size());
    for (Value v : model_.items(*list)) {
      const Instance* e = v.is_reference() ? model_.find(v.id()) : nullptr;
      if (e == nullptr) {
        report(diag::Code::StepncBadAttribute, owner,
               name_of(owner) + " has an element that is not a reference to an instance");
        continue;
      }
      add(parent, executable(*e, depth + 1));
    }
  }

  // An If branch or a While body: the executable, or a `missing` one when the file has none.
  Executable branch(const Instance& owner, std::string_view attribute_name, unsigned depth) {
    if (const Instance* b = deref(attribute(owner, attribute_name)))
      return executable(*b, depth + 1);
    Executable missing;
    missing.missing = true;
    if (options_.visitor) {
      options_.visitor->enter(missing);
      options_.visitor->leave(missing);
    }
    return missing;
  }

  void note_tool(const Instance& tool, const Instance& user) {
    auto it = std::find_if(info_.tools.begin(), info_.tools.end(),
                           [&](const ToolUse& t) { return t.self.id == tool.id; });
    if (it == info_.tools.end()) {
      ToolUse use;
      use.self = ref(tool);
      info_.tools.push_back(std::move(use));
      it = info_.tools.end() - 1;
    }
    it->used_by.push_back(user.id);
  }

  std::size_t workingsteps_ = 0;
  const Model& model_;
  AttributeReader attributes_;
  const InspectOptions& options_;
  p21::LineIndex lines_;
  ProgramInfo info_;
  std::unordered_set<std::uint64_t> on_path_;
};

}  // namespace

void replay(const Executable& root, TreeVisitor& visitor) {
  // Depth first without recursion: each node is entered when first seen and left after its
  // children (the tree's depth is bounded by the inspector's nesting limit, but a replayed tree
  // may come from elsewhere).
  std::vector<std::pair<const Executable*, std::size_t>> stack{{&root, 0}};
  visitor.enter(root);
  while (!stack.empty()) {
    auto& [node, next] = stack.back();
    if (next < node->children.size()) {
      const Executable& child = node->children[next++];
      visitor.enter(child);
      stack.emplace_back(&child, 0);
    } else {
      visitor.leave(*node);
      stack.pop_back();
    }
  }
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
                      "schema); ncpost reads ISO 14649 ARM programs only");
  return diag::make(diag::Code::StepncNoProject, 0, 0,
                    "no PROJECT instance: not an ISO 14649 program");
}

namespace {

std::string display(const EntityRef& ref) {
  std::string s = "#" + std::to_string(ref.id) + " " + ref.type;
  if (ref.name) s += " '" + *ref.name + "'";
  return s;
}

// A string as JSON writes it (the text tree shows DISPLAY_MESSAGE texts quoted and escaped).
std::string quoted(const std::string& text) {
  std::string out = "\"";
  for (unsigned char c : text) {
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\t':
        out += "\\t";
        break;
      case '\r':
        out += "\\r";
        break;
      case '\b':
        out += "\\b";
        break;
      case '\f':
        out += "\\f";
        break;
      default:
        if (c < 0x20) {
          char buffer[8];
          std::snprintf(buffer, sizeof buffer, "\\u%04x", c);
          out += buffer;
        } else {
          out += static_cast<char>(c);
        }
    }
  }
  return out + "\"";
}

std::string text_of(const HeaderValue& value) {
  if (const auto* one = std::get_if<std::string>(&value)) return *one;
  if (const auto* list = std::get_if<std::vector<std::string>>(&value)) {
    std::string s;
    for (const auto& x : *list) s += (s.empty() ? "" : ", ") + x;
    return s;
  }
  return "-";
}

}  // namespace

TextWriter::TextWriter(const Header& header, Sink out) : out_(std::move(out)) {
  const auto field = [&](std::string_view name) {
    for (const auto& [key, value] : header.fields)
      if (key == name) return text_of(value);
    return std::string("-");
  };
  out_("file:        " + field("name") + " (" + field("time_stamp") + ")\n" +
       "description: " + field("description") + "\n" + "author:      " + field("author") + " / " +
       field("organization") + "\n" + "schemas:     " + text_of(header.schemas) + "\n");
}

void TextWriter::begin_project(const Project& project) {
  saw_project_ = true;
  out_("project:     #" + std::to_string(project.id) + " '" + project.name + "'\n");
}

void TextWriter::enter(const Executable& node) {
  std::string label;
  if (!open_.empty()) {
    // An If's children alternate true and false branch; a While's is its body.
    Open& parent = open_.back();
    static constexpr const char* kIfLabels[] = {"true_branch: ", "false_branch: "};
    label = parent.shape == Executable::Shape::If      ? kIfLabels[parent.children % 2]
            : parent.shape == Executable::Shape::While ? "body: "
                                                       : "";
    ++parent.children;
  }
  open_.push_back({node.shape});
  if (node.missing) return;
  const std::string indent(2 * open_.size(), ' ');
  std::string line = indent + label + display(node.self);
  if (node.feature) line += "\n" + indent + "    feature:   " + display(*node.feature);
  if (node.operation) line += "\n" + indent + "    operation: " + display(*node.operation);
  if (node.tool) line += "\n" + indent + "    tool:      " + display(*node.tool);
  if (node.text) line += "\n" + indent + "    text: " + quoted(*node.text);
  out_(line + '\n');
}

void TextWriter::leave(const Executable&) {
  open_.pop_back();
}

void TextWriter::finish(const ProgramInfo& info) {
  std::string rest = saw_project_ ? std::string() : std::string("project:     none\n");
  for (const auto& w : info.workpieces) rest += "workpiece:   " + display(w.self) + "\n";
  for (const auto& t : info.tools) rest += "tool:        " + display(t.self) + "\n";
  rest += "instances:   " + std::to_string(info.statistics.instances) + " of " +
          std::to_string(info.statistics.by_type.size()) + " entity types\n";
  out_(rest);
}

std::string format_text(const ProgramInfo& info) {
  std::string out;
  TextWriter writer(info.header, [&out](std::string_view piece) { out += piece; });
  if (info.project) {
    writer.begin_project(*info.project);
    if (info.project->main_workplan) replay(*info.project->main_workplan, writer);
    writer.end_project();
  }
  writer.finish(info);
  return out;
}

}  // namespace ncpost::stepnc
