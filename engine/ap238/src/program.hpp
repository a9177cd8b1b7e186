#pragma once
// The ARM objects read out of the AIM: the program structure that the interpreter and the
// inspector walk the same way (project → main workplan → elements; a workingstep's operation,
// tool and feature; a workplan's set-up).

#include <optional>
#include <string>
#include <vector>

#include "aim.hpp"

namespace ncpost::ap238::detail {

// Where a program's canonical calls and information start.
struct Project {
  const Instance* project = nullptr;        // MACHINING_PROJECT
  const Instance* definition = nullptr;     // its PRODUCT_DEFINITION
  const Instance* main_workplan = nullptr;  // MACHINING_WORKPLAN
  std::string name;                         // the ARM its_id: product.id (else its name)
};

// The project (AP238-001/002/003 reported when there is none, several, or no main workplan).
[[nodiscard]] std::optional<Project> find_project(Aim& aim);

// The ARM name of an AIM object: action_method.name, product.id, action_resource.name.
[[nodiscard]] std::string arm_name(Aim& aim, const Instance& i);

// A workingstep's operation: the related method of its MACHINING_OPERATION_RELATIONSHIP
// (AP238-004 when there are several; null without a report when there is none).
[[nodiscard]] const Instance* operation_of(Aim& aim, const Instance& workingstep);
// The MACHINING_TOOLs whose usage names `user` (an operation or a load-tool NC function).
[[nodiscard]] std::vector<const Instance*> tools_of(Aim& aim, const Instance& user);
// A workingstep's feature: MACHINING_FEATURE_RELATIONSHIP → MACHINING_FEATURE_PROCESS ←
// PROPERTY_PROCESS ← PROCESS_PROPERTY_ASSOCIATION → the feature (a shape aspect); null when
// the chain is not there.
[[nodiscard]] const Instance* feature_of(Aim& aim, const Instance& workingstep);
// A workplan's set-up: the PRODUCT_DEFINITION of the MACHINING_SETUP whose process
// (PRODUCT_DEFINITION_PROCESS named 'setup') chose the workplan; null when it has none.
[[nodiscard]] const Instance* setup_of(Aim& aim, const Instance& workplan);
// The product of a product definition (through its formation), or null.
[[nodiscard]] const Instance* product_of(Aim& aim, const Instance& definition);

// A tool's data, as far as the file gives it (mm).
struct ToolData {
  std::optional<double> diameter;
  std::optional<double> corner_radius;
  std::optional<double> assembly_length;
  std::string body;  // the tool body representation's name ('endmill', ...)
};
[[nodiscard]] ToolData tool_data(Aim& aim, const Instance& tool);

}  // namespace ncpost::ap238::detail
