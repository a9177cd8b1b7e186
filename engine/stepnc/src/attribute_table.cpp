// Attribute positions of the ISO 14649-10/-11 entities that `inspect` reads, in ISO 10303-21
// order (supertype attributes first). Transcribed from ISO 14649-10:2004 and -11:2004; the
// EXPRESS stage replaces this table with schema look-ups.

#include <algorithm>
#include <array>
#include <cctype>
#include <initializer_list>
#include <string_view>

#include "ncpost/stepnc/attributes.hpp"

namespace ncpost::stepnc {
namespace {

struct Layout {
  std::string_view entity;  // lower case
  std::initializer_list<std::string_view> attributes;
  bool executable = false;
};

// clang-format off
const std::array kLayouts = {
  // Project and program structure.
  Layout{"project", {"its_id", "main_workplan", "its_workpieces", "its_owner", "its_release", "its_status"}},
  Layout{"workplan", {"its_id", "its_elements", "its_channel", "its_setup", "its_effect"}, true},
  Layout{"non_sequential", {"its_id", "its_elements"}, true},
  Layout{"parallel", {"its_id", "branches"}, true},
  Layout{"selective", {"its_id", "its_elements"}, true},
  Layout{"if_statement", {"its_id", "condition", "true_branch", "false_branch"}, true},
  Layout{"while_statement", {"its_id", "condition", "body"}, true},
  Layout{"assignment", {"its_id", "its_lvalue", "its_rvalue"}, true},
  // Workingsteps.
  Layout{"machining_workingstep", {"its_id", "its_secplane", "its_feature", "its_operation", "its_effect"}, true},
  Layout{"rapid_movement", {"its_id", "its_secplane", "its_toolpath", "its_tool_direction"}, true},
  Layout{"tool_length_probing", {"its_id", "its_secplane", "its_toolpath", "its_tool_direction", "measured_offset", "offset", "max_wear", "its_tool"}, true},
  Layout{"tool_radius_probing", {"its_id", "its_secplane", "its_toolpath", "its_tool_direction", "measured_offset", "offset", "max_wear", "its_tool"}, true},
  Layout{"workpiece_probing", {"its_id", "its_secplane", "its_toolpath", "its_tool_direction", "measured_offset", "start_position", "its_workpiece", "its_direction", "expected_value", "its_probe"}, true},
  Layout{"workpiece_complete_probing", {"its_id", "its_secplane", "its_toolpath", "its_tool_direction", "measured_offset", "probing_distance", "its_probe", "its_workpiece", "computed_offset"}, true},
  // NC functions.
  Layout{"display_message", {"its_id", "its_text"}, true},
  Layout{"program_stop", {"its_id"}, true},
  Layout{"optional_stop", {"its_id"}, true},
  Layout{"exchange_pallet", {"its_id"}, true},
  Layout{"index_pallet", {"its_id", "its_index"}, true},
  Layout{"index_table", {"its_id", "its_index"}, true},
  Layout{"load_tool", {"its_id", "its_tool"}, true},
  Layout{"unload_tool", {"its_id", "its_tool"}, true},
  Layout{"set_mark", {"its_id"}, true},
  Layout{"wait_for_mark", {"its_id", "its_channel"}, true},
  // Resources.
  Layout{"workpiece", {"its_id", "its_material", "global_tolerance", "its_rawpiece", "its_geometry", "its_bounding_geometry", "clamping_positions"}},
  Layout{"material", {"standard_identifier", "material_identifier", "material_property"}},
  Layout{"setup", {"its_id", "its_origin", "its_secplane", "its_workpiece_setup"}},
  Layout{"channel", {"its_id"}},
};

// Roles: the leading attributes that all subtypes of an abstract supertype share.
const Layout kMachiningOperation{"machining_operation", {"its_toolpath", "its_tool_direction", "its_id", "retract_plane", "start_point", "its_tool", "its_technology", "its_machine_functions"}};
const Layout kManufacturingFeature{"manufacturing_feature", {"its_id", "its_workpiece", "its_operations"}};
const Layout kMachiningTool{"machining_tool", {"its_id"}};
// clang-format on

bool equals_lower(std::string_view name, std::string_view lower) {
  return name.size() == lower.size() &&
         std::equal(name.begin(), name.end(), lower.begin(), [](char a, char b) {
           return std::tolower(static_cast<unsigned char>(a)) == b;
         });
}

const Layout* layout_for(std::string_view entity) {
  for (const Layout& layout : kLayouts)
    if (equals_lower(entity, layout.entity)) return &layout;
  return nullptr;
}

}  // namespace

std::optional<p21::Value> attribute(const p21::Model& model, const p21::Instance& instance,
                                    std::string_view name, Role role) {
  const Layout* layout = nullptr;
  switch (role) {
    case Role::Exact: layout = layout_for(model.type_name(instance)); break;
    case Role::MachiningOperation: layout = &kMachiningOperation; break;
    case Role::ManufacturingFeature: layout = &kManufacturingFeature; break;
    case Role::MachiningTool: layout = &kMachiningTool; break;
  }
  if (layout == nullptr || model.is_complex(instance)) return std::nullopt;
  const auto params = model.params(instance);
  std::size_t position = 0;
  for (std::string_view attribute_name : layout->attributes) {
    if (attribute_name == name) {
      if (position >= params.size()) return std::nullopt;
      return params[position];
    }
    ++position;
  }
  return std::nullopt;
}

bool is_known_entity(std::string_view entity) { return layout_for(entity) != nullptr; }

bool is_executable(std::string_view entity) {
  const Layout* layout = layout_for(entity);
  return layout != nullptr && layout->executable;
}

}  // namespace ncpost::stepnc
