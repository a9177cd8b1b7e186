#include "ncpost/p21/compare.hpp"

#include <cmath>

namespace ncpost::p21 {
namespace {

bool same_name(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const auto ua = static_cast<unsigned char>(a[i]);
    const auto ub = static_cast<unsigned char>(b[i]);
    if (std::toupper(ua) != std::toupper(ub)) return false;
  }
  return true;
}

class Comparer {
 public:
  Comparer(const Model& a, const Model& b) : a_(a), b_(b) {}

  // Recursion is bounded by the models' max_depth(), which the readers cap.
  std::optional<std::string> values(Value x, Value y, const std::string& where) const {
    if (x.kind() != y.kind())
      return where + ": value kinds differ (" + std::to_string(static_cast<int>(x.kind())) +
             " vs " + std::to_string(static_cast<int>(y.kind())) + ")";
    switch (x.kind()) {
      case ValueKind::Omitted:
      case ValueKind::Derived:
        return std::nullopt;
      case ValueKind::Integer:
        if (a_.as_integer(x) != b_.as_integer(y))
          return where + ": integers differ (" + std::string(a_.slice(x)) + " vs " +
                 std::string(b_.slice(y)) + ")";
        return std::nullopt;
      case ValueKind::Real: {
        const double dx = a_.as_real(x);
        const double dy = b_.as_real(y);
        if (dx != dy && !(std::isnan(dx) && std::isnan(dy)))
          return where + ": reals differ (" + std::string(a_.slice(x)) + " vs " +
                 std::string(b_.slice(y)) + ")";
        return std::nullopt;
      }
      case ValueKind::String:
        if (a_.as_string(x) != b_.as_string(y))
          return where + ": strings differ ('" + a_.as_string(x) + "' vs '" + b_.as_string(y) +
                 "')";
        return std::nullopt;
      case ValueKind::Enumeration:
      case ValueKind::ConstantName:
      case ValueKind::ValueName:
        if (!same_name(a_.slice(x), b_.slice(y)))
          return where + ": names differ (" + std::string(a_.slice(x)) + " vs " +
                 std::string(b_.slice(y)) + ")";
        return std::nullopt;
      case ValueKind::Binary:
      case ValueKind::Resource:
        if (a_.slice(x) != b_.slice(y)) return where + ": binary or resource values differ";
        return std::nullopt;
      case ValueKind::Reference:
        if (x.id() != y.id())
          return where + ": references differ (#" + std::to_string(x.id()) + " vs #" +
                 std::to_string(y.id()) + ")";
        return std::nullopt;
      case ValueKind::List:
        return lists(a_.items(x), b_.items(y), where);
      case ValueKind::Typed:
        if (!same_name(a_.keyword(x.keyword_id()), b_.keyword(y.keyword_id())))
          return where + ": typed parameter names differ (" +
                 std::string(a_.keyword(x.keyword_id())) + " vs " +
                 std::string(b_.keyword(y.keyword_id())) + ")";
        return values(a_.typed_child(x), b_.typed_child(y),
                      where + " " + std::string(a_.keyword(x.keyword_id())));
    }
    return std::nullopt;
  }

  std::optional<std::string> lists(std::span<const Value> x, std::span<const Value> y,
                                   const std::string& where) const {
    if (x.size() != y.size())
      return where + ": " + std::to_string(x.size()) + " vs " + std::to_string(y.size()) +
             " parameters";
    for (std::size_t i = 0; i < x.size(); ++i)
      if (auto d = values(x[i], y[i], where + "[" + std::to_string(i + 1) + "]")) return d;
    return std::nullopt;
  }

  std::optional<std::string> instances(const Instance& x, const Instance& y,
                                       const std::string& where) const {
    if (!same_name(a_.type_name(x), b_.type_name(y)))
      return where + ": entity names differ (" + std::string(a_.type_name(x)) + " vs " +
             std::string(b_.type_name(y)) + ")";
    return lists(a_.params(x), b_.params(y), where);
  }

 private:
  const Model& a_;
  const Model& b_;
};

}  // namespace

std::optional<std::string> first_difference(const Model& a, const Model& b) {
  const Comparer cmp(a, b);
  if (a.header().size() != b.header().size())
    return "header entity counts differ: " + std::to_string(a.header().size()) + " vs " +
           std::to_string(b.header().size());
  for (std::size_t i = 0; i < a.header().size(); ++i)
    if (auto d = cmp.instances(a.header()[i], b.header()[i],
                               "header " + std::string(a.type_name(a.header()[i]))))
      return d;
  if (a.sections().size() != b.sections().size()) return "DATA section counts differ";
  for (std::size_t i = 0; i < a.sections().size(); ++i) {
    const auto& sa = a.sections()[i];
    const auto& sb = b.sections()[i];
    if (auto d = cmp.lists(a.all_values().subspan(sa.first_param, sa.param_count),
                           b.all_values().subspan(sb.first_param, sb.param_count),
                           "DATA section " + std::to_string(i + 1) + " parameters"))
      return d;
    if (sa.end_instance - sa.first_instance != sb.end_instance - sb.first_instance)
      return "DATA section " + std::to_string(i + 1) + " instance counts differ";
  }
  if (a.anchors().size() != b.anchors().size()) return "anchor counts differ";
  for (std::size_t i = 0; i < a.anchors().size(); ++i)
    if (auto d =
            cmp.values(a.anchors()[i].item, b.anchors()[i].item, "anchor " + std::to_string(i + 1)))
      return d;
  if (a.instances().size() != b.instances().size())
    return "instance counts differ: " + std::to_string(a.instances().size()) + " vs " +
           std::to_string(b.instances().size());
  for (const Instance& x : a.instances()) {
    const Instance* y = b.find(x.id);
    const std::string where = "#" + std::to_string(x.id);
    if (y == nullptr) return where + " is missing from the second model";
    if (a.find(x.id) != &x) continue;  // a duplicate id: only the kept instance counts
    if (auto d = cmp.instances(x, *y, where)) return d;
  }
  return std::nullopt;
}

}  // namespace ncpost::p21
