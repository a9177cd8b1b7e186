#include "program.hpp"

namespace ncpost::ap238::detail {
namespace {

// A length measure item of a tool's representation, in mm.
std::optional<double> length_item(Aim& aim, const Instance& representation, std::string_view name) {
  for (const Instance* item : aim.items(representation)) {
    if (!aim.is_a(*item, "measure_representation_item") || !aim.text_is(*item, "name", name))
      continue;
    const auto q = aim.measure(*item);
    if (q && q->dimensions == kLength) return q->value;
  }
  return std::nullopt;
}

}  // namespace

std::string arm_name(Aim& aim, const Instance& i) {
  if (aim.is_a(i, "product")) {
    std::string id = aim.text(i, "id");
    return id.empty() ? aim.text(i, "name") : id;
  }
  return aim.text(i, "name");
}

const Instance* product_of(Aim& aim, const Instance& definition) {
  const Instance* formation = aim.ref(definition, "formation");
  return formation ? aim.ref(*formation, "of_product") : nullptr;
}

std::optional<Project> find_project(Aim& aim) {
  const std::vector<const Instance*> projects = aim.instances_of("machining_project");
  if (projects.empty()) {
    aim.report_unplaced(diag::Code::Ap238NoProject,
                        "no MACHINING_PROJECT: not an AP238 CNC program");
    return std::nullopt;
  }
  if (projects.size() > 1)
    aim.report(diag::Code::Ap238ManyProjects, *projects[1],
               std::to_string(projects.size()) + " MACHINING_PROJECTs; " +
                   aim.describe(*projects[0]) + " is used");
  Project p;
  p.project = projects[0];
  p.name = arm_name(aim, *p.project);
  // MACHINING_PROJECT ← PRODUCT_DEFINITION_FORMATION ← PRODUCT_DEFINITION ←
  // PROCESS_PRODUCT_ASSOCIATION → PRODUCT_DEFINITION_PROCESS 'machining' → MACHINING_WORKPLAN.
  std::vector<const Instance*> workplans;
  for (const Instance* f :
       aim.referring(*p.project, "product_definition_formation", "of_product")) {
    for (const Instance* d : aim.referring(*f, "product_definition", "formation")) {
      for (const Instance* a :
           aim.referring(*d, "process_product_association", "defined_product")) {
        const Instance* process = aim.ref(*a, "process");
        const Instance* plan = process ? aim.ref(*process, "chosen_method") : nullptr;
        // 'machining' by the mapping; a set-up's process chooses its workplan the same way.
        if (plan == nullptr || !aim.is_a(*plan, "machining_workplan") ||
            aim.text_is(*process, "name", "setup"))
          continue;
        if (p.definition == nullptr) p.definition = d;
        workplans.push_back(plan);
      }
    }
  }
  if (workplans.empty()) {
    aim.report(diag::Code::Ap238Missing, *p.project,
               aim.describe(*p.project) + " '" + p.name +
                   "' has no main workplan (a PROCESS_PRODUCT_ASSOCIATION of its "
                   "PRODUCT_DEFINITION with a PRODUCT_DEFINITION_PROCESS 'machining' whose "
                   "chosen_method is a MACHINING_WORKPLAN)");
    return p;
  }
  if (workplans.size() > 1)
    aim.report(diag::Code::Ap238ManyProjects, *p.project,
               aim.describe(*p.project) + " has " + std::to_string(workplans.size()) +
                   " main workplans; " + aim.describe(*workplans[0]) + " is used");
  p.main_workplan = workplans[0];
  return p;
}

const Instance* operation_of(Aim& aim, const Instance& workingstep) {
  const auto operations = aim.related(workingstep, "machining_operation_relationship");
  if (operations.size() > 1)
    aim.report(diag::Code::Ap238Ambiguous, workingstep,
               aim.describe(workingstep) + " has " + std::to_string(operations.size()) +
                   " operations; " + aim.describe(*operations[0]) + " is used");
  return operations.empty() ? nullptr : operations[0];
}

std::vector<const Instance*> tools_of(Aim& aim, const Instance& user) {
  // Links follows no other attribute of an action resource than its usage: a MACHINING_TOOL
  // among the referrers names `user` there (no scan of usage lists, which may be long: one
  // tool serves every operation that uses it).
  std::vector<const Instance*> out;
  for (const std::uint32_t index : aim.links().referrers(user)) {
    const Instance& tool = aim.links().instance(index);
    if ((out.empty() || out.back() != &tool) && aim.is_a(tool, "machining_tool"))
      out.push_back(&tool);
  }
  return out;
}

const Instance* feature_of(Aim& aim, const Instance& workingstep) {
  for (const Instance* process : aim.related(workingstep, "machining_feature_relationship"))
    for (const Instance* action : aim.referring(*process, "property_process", "chosen_method"))
      for (const Instance* association :
           aim.referring(*action, "process_property_association", "process"))
        if (const Instance* feature = aim.ref(*association, "property_or_shape")) return feature;
  return nullptr;
}

const Instance* setup_of(Aim& aim, const Instance& workplan) {
  for (const Instance* process :
       aim.referring(workplan, "product_definition_process", "chosen_method")) {
    if (!aim.text_is(*process, "name", "setup")) continue;
    for (const Instance* a : aim.referring(*process, "process_product_association", "process")) {
      const Instance* definition = aim.ref(*a, "defined_product");
      const Instance* product = definition ? product_of(aim, *definition) : nullptr;
      if (product != nullptr && aim.is_a(*product, "machining_setup")) return definition;
    }
  }
  return nullptr;
}

ToolData tool_data(Aim& aim, const Instance& tool) {
  ToolData data;
  for (const Property& p : aim.properties(tool)) {
    if (p.name == "overall assembly length") {
      if (const Instance* item = aim.item(p, "measure_representation_item")) {
        const auto q = aim.measure(*item);
        if (q && q->dimensions == kLength) data.assembly_length = q->value;
      }
    } else if (p.name == "tool body") {
      // The body representation names the kind of tool; its dimensions are in the
      // MACHINING_TOOL_DIMENSION_REPRESENTATION it is related to (rep_1 → rep_2).
      p.representations.for_each([&](const Instance& body) {
        if (data.body.empty()) data.body = aim.text(body, "name");
        for (const Instance* rr : aim.referring(body, "representation_relationship", "rep_1")) {
          const Instance* dimensions = aim.ref(*rr, "rep_2");
          if (dimensions == nullptr) continue;
          if (!data.diameter) data.diameter = length_item(aim, *dimensions, "diameter");
          if (!data.corner_radius)
            data.corner_radius = length_item(aim, *dimensions, "edge radius");
        }
      });
    }
  }
  return data;
}

}  // namespace ncpost::ap238::detail
