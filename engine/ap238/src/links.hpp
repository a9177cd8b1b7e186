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
#include <vector>

#include "ncpost/p21/model.hpp"
#include "ncpost/stepnc/attributes.hpp"

namespace ncpost::ap238::detail {

class Links {
 public:
  Links(const p21::Model& model, const stepnc::AttributeReader& attributes);

  // The instances that refer to `target` through one of the followed attributes, in file
  // order (an instance that refers twice, e.g. a process_product_association whose product and
  // process are both `target`, appears twice).
  [[nodiscard]] std::span<const std::uint32_t> referrers(const p21::Instance& target) const;
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
};

}  // namespace ncpost::ap238::detail
