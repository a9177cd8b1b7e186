#pragma once
// The AIM's links, followed backwards.
//
// In the AIM a property points at what it describes, a relationship at the methods it relates,
// a tool at the operations it serves: the ARM's "workingstep.its_operation" is a
// MACHINING_OPERATION_RELATIONSHIP that points at the workingstep. Reading the program top down
// therefore needs, for each instance, the instances that point at it. Links answers that for
// the attributes the mapping follows (the table in links.cpp), built in two linear passes over
// the model (count, then fill: one compressed array, no per-instance allocation).

#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "ncpost/p21/model.hpp"
#include "ncpost/stepnc/attributes.hpp"

namespace ncpost::ap238::detail {

// Which attribute a referrer refers through (the rules of links.cpp, in their order).
enum class Link : std::uint8_t {
  PropertyDefinition,      // action_property.definition: a method's property
  PropertyRepresentation,  // action_property_representation.property
  ResourceProperty,        // resource_property.resource: a tool's property
  ResourceRepresentation,  // resource_property_representation.property
  RelatingMethod,          // action_method_relationship.relating_method
  Usage,                   // action_resource.usage: the operations a tool serves
  OfProduct,               // product_definition_formation.of_product
  Formation,               // product_definition.formation
  DefinedProduct,          // process_product_association.defined_product
  Process,                 // process_product_association.process
  ChosenMethod,            // action.chosen_method
  PropertyProcess,         // process_property_association.process
  Definition,              // property_definition.definition
  RepresentedDefinition,   // property_definition_representation.definition
  RelatingDefinition,      // product_definition_relationship.relating_product_definition
  Rep1,                    // representation_relationship.rep_1
  ProductRelation,         // context_dependent_shape_representation.represented_product_relation
};

// The attribute name of a link.
[[nodiscard]] std::string_view attribute_of(Link link);

class Links {
 public:
  Links(const p21::Model& model, const stepnc::AttributeReader& attributes);

  // The instances that refer to `target` through one of the followed attributes, in file
  // order (an instance that refers twice, e.g. a process_product_association whose product and
  // process are both `target`, appears twice).
  [[nodiscard]] std::span<const std::uint32_t> referrers(const p21::Instance& target) const;
  // Parallel to referrers(target): the link each refers through.
  [[nodiscard]] std::span<const Link> links(const p21::Instance& target) const;
  [[nodiscard]] const p21::Instance& instance(std::uint32_t index) const {
    return model_.instances()[index];
  }
  [[nodiscard]] std::uint32_t index_of(const p21::Instance& instance) const {
    return static_cast<std::uint32_t>(&instance - model_.instances().data());
  }
  // Referrers in all, for the benchmark's and tests' sake.
  [[nodiscard]] std::size_t size() const { return from_.size(); }

 private:
  const p21::Model& model_;
  std::vector<std::uint32_t> start_;  // per instance index: its referrers in from_[start_[i]..]
  std::vector<std::uint32_t> from_;
  std::vector<Link> link_;  // parallel to from_
};

}  // namespace ncpost::ap238::detail
