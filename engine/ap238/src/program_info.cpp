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

class Inspector {
 public:
  Inspector(const p21::Model& model, const express::SchemaSet& schema,
            const stepnc::InspectOptions& options)
      : model_(model),
        attributes_(model, schema),
        aim_(model, attributes_, diagnostics_),
        options_(options) {}

  stepnc::ProgramInfo run() {
    stepnc::ProgramInfo info;
    info.header = stepnc::read_header(model_);
    info.project = project();
    info.workpieces = std::move(workpieces_);
    info.tools = tools();
    info.statistics = stepnc::count_instances(model_, workingsteps_);
    info.diagnostics = std::move(diagnostics_);
    return info;
  }

 private:
  stepnc::EntityRef summary(const Instance& i) {
    return {i.id, std::string(model_.type_name(i)), detail::arm_name(aim_, i)};
  }

  std::optional<stepnc::Project> project() {
    const auto p = detail::find_project(aim_);
    if (!p) return std::nullopt;
    stepnc::Project out;
    out.id = p->project->id;
    out.name = p->name;
    if (p->definition != nullptr) {
      for (const Instance* r :
           aim_.referring(*p->definition, "machining_project_workpiece_relationship",
                          "relating_product_definition")) {
        const Instance* d = aim_.ref(*r, "related_product_definition");
        const Instance* product = d ? detail::product_of(aim_, *d) : nullptr;
        if (product != nullptr) workpieces_.push_back({summary(*product), {}, {}});
      }
    }
    if (p->main_workplan) out.main_workplan = executable(*p->main_workplan, 0);
    return out;
  }

  std::vector<stepnc::Executable> list(const std::vector<const Instance*>& elements,
                                       unsigned depth) {
    std::vector<stepnc::Executable> out;
    out.reserve(elements.size());
    for (const Instance* e : elements) out.push_back(executable(*e, depth + 1));
    return out;
  }

  static stepnc::Executable missing() {
    stepnc::Executable x;
    x.missing = true;
    return x;
  }

  stepnc::Executable executable(const Instance& e, unsigned depth) {
    using Shape = stepnc::Executable::Shape;
    stepnc::Executable x;
    x.self = summary(e);
    if (!aim_.is_a(e, "machining_process_executable")) {
      aim_.report(diag::Code::StepncUnknownExecutable, e,
                  aim_.describe(e) + " is not a MACHINING_PROCESS_EXECUTABLE");
      return x;
    }
    if (depth > options_.max_nesting) {
      aim_.report(diag::Code::StepncTooDeep, e,
                  aim_.describe(e) + " is nested more than " +
                      std::to_string(options_.max_nesting) + " workplans deep");
      return x;
    }
    if (!on_path_.insert(e.id).second) {
      aim_.report(diag::Code::StepncCycle, e, aim_.describe(e) + " contains itself");
      return x;
    }
    const std::string description = aim_.text(e, "description");
    if (aim_.is_a(e, "machining_workingstep")) {
      ++workingsteps_;
      x.shape = Shape::Workingstep;
      if (const Instance* f = detail::feature_of(aim_, e)) x.feature = summary(*f);
      if (const Instance* op = detail::operation_of(aim_, e)) {
        x.operation = summary(*op);
        const auto tools = detail::tools_of(aim_, *op);
        if (!tools.empty()) {
          x.tool = summary(*tools.front());
          note_tool(*tools.front(), e);
        }
      } else {
        aim_.report(diag::Code::Ap238Missing, e,
                    aim_.describe(e) + " has no operation (no MACHINING_OPERATION_RELATIONSHIP)");
      }
    } else if (aim_.is_a(e, "machining_workplan")) {
      x.shape = Shape::Sequence;
      if (const Instance* setup = detail::setup_of(aim_, e))
        if (const Instance* product = detail::product_of(aim_, *setup)) x.setup = summary(*product);
      x.children = list(aim_.related(e, "machining_process_sequence_relationship"), depth);
    } else if (aim_.is_a(e, "machining_nc_function")) {
      if (description == "load tool" || description == "unload tool") {
        x.shape = Shape::ToolChange;
        const auto tools = detail::tools_of(aim_, e);
        if (!tools.empty()) {
          x.tool = summary(*tools.front());
          note_tool(*tools.front(), e);
        }
      } else if (description == "display message") {
        x.shape = Shape::Message;
        for (const auto& p : aim_.properties(e))
          if (p.name == "message text")
            if (auto t = aim_.description_of(aim_.item(p, "descriptive_representation_item")))
              x.text = *t;
      }
    } else if (description == "non-sequential" || description == "selective") {
      x.shape = Shape::Sequence;
      x.children =
          list(aim_.related(e, description == "selective" ? "machining_process_branch_relationship"
                                                          : "machining_process_body_relationship"),
               depth);
    } else if (description == "parallel") {
      x.shape = Shape::Parallel;
      x.children = list(aim_.related(e, "machining_process_concurrent_relationship"), depth);
    } else if (description == "if statement") {
      x.shape = Shape::If;
      x.children = {missing(), missing()};
      for (const Instance* r :
           aim_.referring(e, "machining_process_branch_relationship", "relating_method")) {
        const std::string branch = aim_.text(*r, "name");
        if (branch != "true branch" && branch != "false branch") continue;
        const Instance* target = aim_.ref(*r, "related_method");
        if (target != nullptr)
          x.children[branch == "true branch" ? 0 : 1] = executable(*target, depth + 1);
      }
    } else if (description == "while statement") {
      x.shape = Shape::While;
      const auto body = aim_.related(e, "machining_process_body_relationship");
      x.children = {body.empty() ? missing() : executable(*body.front(), depth + 1)};
    }
    on_path_.erase(e.id);
    return x;
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
  std::vector<stepnc::ToolUse> tools() {
    std::vector<stepnc::ToolUse> out;
    for (const auto& [tool, users] : tools_) {
      stepnc::ToolUse use;
      use.self = summary(*tool);
      use.used_by = users;
      const auto data = detail::tool_data(aim_, *tool);
      const auto load = stepnc::detail::tool_load(tool->id, detail::arm_name(aim_, *tool),
                                                  data.assembly_length.value_or(0), nullptr);
      if (load) use.number = load->pocket;
      if (!data.body.empty()) use.body = data.body;
      use.diameter = data.diameter;
      use.corner_radius = data.corner_radius;
      use.length = data.assembly_length;
      out.push_back(std::move(use));
    }
    return out;
  }

  const p21::Model& model_;
  std::vector<diag::Diagnostic> diagnostics_;
  stepnc::AttributeReader attributes_;
  Aim aim_;
  const stepnc::InspectOptions& options_;
  std::vector<stepnc::Workpiece> workpieces_;
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
