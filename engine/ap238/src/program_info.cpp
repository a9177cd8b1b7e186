// ap238::inspect: the AIM program's tree in the JSON shape of stepnc::inspect (docs/inspect.md),
// read through the same structure functions as the interpreter (program.hpp).

#include <algorithm>
#include <unordered_set>

#include "aim.hpp"
#include "ncpost/ap238/ap238.hpp"
#include "ncpost/stepnc/machine.hpp"
#include "program.hpp"

namespace ncpost::ap238 {
namespace {

using detail::Aim;
using detail::Instance;
using nlohmann::ordered_json;

class Inspector {
 public:
  Inspector(const p21::Model& model, const express::SchemaSet& schema,
            const stepnc::InspectOptions& options)
      : model_(model),
        attributes_(model, schema),
        aim_(model, attributes_, diagnostics_),
        options_(options) {}

  stepnc::ProgramInfo run() {
    ordered_json out;
    out["header"] = stepnc::header_json(model_);
    out["project"] = project();
    out["workpieces"] = workpieces_;
    out["tools"] = tools();
    out["statistics"] = stepnc::statistics_json(model_, workingsteps_);
    return {std::move(out), std::move(diagnostics_)};
  }

 private:
  ordered_json summary(const Instance& i) {
    ordered_json j;
    j["id"] = i.id;
    j["type"] = std::string(model_.type_name(i));
    j["name"] = detail::arm_name(aim_, i);
    return j;
  }

  ordered_json project() {
    const auto p = detail::find_project(aim_);
    if (!p) return nullptr;
    ordered_json j;
    j["id"] = p->project->id;
    j["name"] = p->name;
    if (p->definition != nullptr) {
      for (const Instance* r :
           aim_.referring(*p->definition, "machining_project_workpiece_relationship",
                          "relating_product_definition")) {
        const Instance* d = aim_.ref(*r, "related_product_definition");
        const Instance* product = d ? detail::product_of(aim_, *d) : nullptr;
        if (product != nullptr) workpieces_.push_back(summary(*product));
      }
    }
    j["main_workplan"] =
        p->main_workplan ? executable(*p->main_workplan, 0) : ordered_json(nullptr);
    return j;
  }

  ordered_json list(const std::vector<const Instance*>& elements, unsigned depth) {
    ordered_json out = ordered_json::array();
    for (const Instance* e : elements) out.push_back(executable(*e, depth + 1));
    return out;
  }

  ordered_json executable(const Instance& e, unsigned depth) {
    ordered_json j = summary(e);
    if (!aim_.is_a(e, "machining_process_executable")) {
      aim_.report(diag::Code::StepncUnknownExecutable, e,
                  aim_.describe(e) + " is not a MACHINING_PROCESS_EXECUTABLE");
      return j;
    }
    if (depth > options_.max_nesting) {
      aim_.report(diag::Code::StepncTooDeep, e,
                  aim_.describe(e) + " is nested more than " +
                      std::to_string(options_.max_nesting) + " workplans deep");
      return j;
    }
    if (!on_path_.insert(e.id).second) {
      aim_.report(diag::Code::StepncCycle, e, aim_.describe(e) + " contains itself");
      return j;
    }
    const std::string description = aim_.text(e, "description");
    if (aim_.is_a(e, "machining_workingstep")) {
      ++workingsteps_;
      if (const Instance* f = detail::feature_of(aim_, e)) j["feature"] = summary(*f);
      if (const Instance* op = detail::operation_of(aim_, e)) {
        j["operation"] = summary(*op);
        const auto tools = detail::tools_of(aim_, *op);
        if (!tools.empty()) {
          j["tool"] = summary(*tools.front());
          note_tool(*tools.front(), e);
        }
      } else {
        aim_.report(diag::Code::Ap238Missing, e,
                    aim_.describe(e) + " has no operation (no MACHINING_OPERATION_RELATIONSHIP)");
      }
    } else if (aim_.is_a(e, "machining_workplan")) {
      if (const Instance* setup = detail::setup_of(aim_, e))
        if (const Instance* product = detail::product_of(aim_, *setup))
          j["setup"] = summary(*product);
      j["elements"] = list(aim_.related(e, "machining_process_sequence_relationship"), depth);
    } else if (aim_.is_a(e, "machining_nc_function")) {
      if (description == "load tool" || description == "unload tool") {
        const auto tools = detail::tools_of(aim_, e);
        if (!tools.empty()) {
          j["tool"] = summary(*tools.front());
          note_tool(*tools.front(), e);
        }
      } else if (description == "display message") {
        for (const auto& p : aim_.properties(e))
          if (p.name == "message text")
            if (auto t = aim_.description_of(aim_.item(p, "descriptive_representation_item")))
              j["text"] = *t;
      }
    } else if (description == "non-sequential" || description == "selective") {
      j["elements"] =
          list(aim_.related(e, description == "selective" ? "machining_process_branch_relationship"
                                                          : "machining_process_body_relationship"),
               depth);
    } else if (description == "parallel") {
      j["branches"] = list(aim_.related(e, "machining_process_concurrent_relationship"), depth);
    } else if (description == "if statement") {
      for (const Instance* r :
           aim_.referring(e, "machining_process_branch_relationship", "relating_method")) {
        const std::string branch = aim_.text(*r, "name");
        if (branch != "true branch" && branch != "false branch") continue;
        const Instance* target = aim_.ref(*r, "related_method");
        j[branch == "true branch" ? "true_branch" : "false_branch"] =
            target ? executable(*target, depth + 1) : ordered_json(nullptr);
      }
    } else if (description == "while statement") {
      const auto body = aim_.related(e, "machining_process_body_relationship");
      j["body"] = body.empty() ? ordered_json(nullptr) : executable(*body.front(), depth + 1);
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

  // Each tool with its users and, what the AIM gives beyond the ARM's summary, its data: the
  // number it is loaded as (the shared rule of stepnc::detail::tool_load), and its diameter,
  // corner radius and assembly length (mm) when the file has them.
  ordered_json tools() {
    ordered_json out = ordered_json::array();
    for (const auto& [tool, users] : tools_) {
      ordered_json j = summary(*tool);
      j["used_by"] = users;
      const auto data = detail::tool_data(aim_, *tool);
      const auto load = stepnc::detail::tool_load(tool->id, detail::arm_name(aim_, *tool),
                                                  data.assembly_length.value_or(0), nullptr);
      if (load) j["number"] = load->pocket;
      if (!data.body.empty()) j["body"] = data.body;
      if (data.diameter) j["diameter"] = *data.diameter;
      if (data.corner_radius) j["corner_radius"] = *data.corner_radius;
      if (data.assembly_length) j["length"] = *data.assembly_length;
      out.push_back(std::move(j));
    }
    return out;
  }

  const p21::Model& model_;
  std::vector<diag::Diagnostic> diagnostics_;
  stepnc::AttributeReader attributes_;
  Aim aim_;
  const stepnc::InspectOptions& options_;
  ordered_json workpieces_ = ordered_json::array();
  std::vector<std::pair<const Instance*, std::vector<std::uint64_t>>> tools_;
  std::unordered_set<std::uint64_t> on_path_;
  std::size_t workingsteps_ = 0;
};

}  // namespace

stepnc::ProgramInfo inspect(const p21::Model& model, const express::SchemaSet& schema,
                            const stepnc::InspectOptions& options) {
  return Inspector(model, schema, options).run();
}

}  // namespace ncpost::ap238
