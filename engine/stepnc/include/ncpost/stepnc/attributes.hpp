#pragma once
// Reading ISO 14649 attributes by name.
//
// Until the EXPRESS stage supplies a schema, attribute positions come from one table
// (src/attribute_table.cpp), transcribed from ISO 14649-10/-11 with supertype attributes first,
// as ISO 10303-21 orders them. Callers only ever ask by name, so replacing the table with schema
// look-ups changes nothing for them.

#include <optional>
#include <string_view>

#include "ncpost/p21/model.hpp"

namespace ncpost::stepnc {

// The attribute layouts that the table knows. A role is an entity or an abstract supertype
// whose subtypes share its leading attributes (every machining operation starts with the
// attributes of MACHINING_OPERATION, for example).
enum class Role : std::uint8_t {
  Exact,  // look the entity up by its own name
  MachiningOperation,
  ManufacturingFeature,
  MachiningTool,
};

// The value of attribute `name` of `instance`, or nullopt when the table does not know the
// entity (or role) or the instance has fewer parameters than the table expects.
[[nodiscard]] std::optional<p21::Value> attribute(const p21::Model& model,
                                                  const p21::Instance& instance,
                                                  std::string_view name,
                                                  Role role = Role::Exact);

// True when the table has a layout for this entity name (any case).
[[nodiscard]] bool is_known_entity(std::string_view entity);

// Entities that may appear in a workplan's element list (ISO 14649-10 EXECUTABLE subtypes).
[[nodiscard]] bool is_executable(std::string_view entity);

}  // namespace ncpost::stepnc
