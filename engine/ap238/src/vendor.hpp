#pragma once
// Vendor adapters: what a CAM writer adds to AP238 beyond the standard, read the way that
// writer documents it. One small adapter per vendor; the interpreter asks each whether it
// documents a property it does not know, and for a toolpath's geometry when the toolpath has
// no standard curve. A property nobody documents is counted and reported (AP238-009), never a
// reason to stop.

#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "aim.hpp"
#include "ncpost/stepnc/curves.hpp"

namespace ncpost::ap238::detail {

using stepnc::detail::Segment;

class VendorAdapter {
 public:
  VendorAdapter() = default;
  VendorAdapter(const VendorAdapter&) = delete;
  VendorAdapter& operator=(const VendorAdapter&) = delete;
  virtual ~VendorAdapter() = default;

  // The writer, as diagnostics name it ("Next-NC").
  [[nodiscard]] virtual std::string_view vendor() const = 0;
  // True when `property` is a name this writer documents.
  [[nodiscard]] virtual bool documents(std::string_view property) const = 0;
  // True when that documented property carries a toolpath's geometry.
  [[nodiscard]] virtual bool is_geometry(std::string_view property) const = 0;
  // The geometry `property` (is_geometry) gives `toolpath` of `operation`, in mm in the
  // workpiece's coordinates; nullopt after reporting why (AP238-013).
  [[nodiscard]] virtual std::optional<std::vector<Segment>> toolpath_geometry(
      Aim& aim, const Instance& operation, const Instance& toolpath, const Property& property,
      double arc_tolerance) const = 0;
};

// Every adapter ncpost has (stateless; one per vendor).
[[nodiscard]] std::span<const VendorAdapter* const> vendor_adapters();

}  // namespace ncpost::ap238::detail
