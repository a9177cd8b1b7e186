#pragma once
// Semantic equality of two models: the same header entities, sections, anchors, and instances
// by id with the same entity names and values. Numbers compare by value, strings by their
// decoded text, so the comparison holds across writers that spell literals differently.

#include <optional>
#include <string>

#include "ncpost/p21/model.hpp"

namespace ncpost::p21 {

// The first difference found, described for a test failure message; nullopt when equal.
[[nodiscard]] std::optional<std::string> first_difference(const Model& a, const Model& b);

}  // namespace ncpost::p21
