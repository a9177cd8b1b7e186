#pragma once
// What every feature reader shares: the workingstep's instances, typed access to their
// attributes by name through the schema (numbers checked finite, toleranced lengths, booleans,
// enumerations, directions, placements), the tool, the operation's common parameters and the
// feature's depth as specs, and the report that names what is wrong. The reader of a feature
// kind (face.hpp, pocket.hpp, ...) fills its spec with it; planners never see it, nor the model
// (docs/features.md, "Read, then plan").

#include <optional>
#include <string>
#include <string_view>

#include "generator.hpp"
#include "report.hpp"
#include "spec.hpp"

namespace ncpost::stepnc::features {

using p21::Instance;

// The report of a generation: each finding becomes a diagnostic at its instance's line and
// column at once, after whatever the geometry reader has reported, so that both stay in the
// order they were found.
class ModelReport final : public Report {
 public:
  ModelReport(detail::GeometryReader& geometry, Subject workingstep)
      : Report(workingstep), geometry_(geometry) {}

 private:
  void add(Finding finding) override;
  detail::GeometryReader& geometry_;
};

class Reader {
 public:
  // `request.workingstep`, `operation` and `tool` must be set; `feature` too before a reader of
  // a feature kind runs.
  Reader(detail::GeometryReader& geometry, const Request& request, const FeatureOptions& options,
         Report& report);

  [[nodiscard]] const Instance& workingstep() const { return *request_.workingstep; }
  [[nodiscard]] const Instance& operation() const { return *request_.operation; }
  [[nodiscard]] const Instance& feature() const { return *request_.feature; }
  // The technology in force: feed (mm/min) and spindle (ISO rev/s, negative = clockwise).
  [[nodiscard]] std::optional<double> feed() const { return request_.feed; }
  [[nodiscard]] std::optional<double> spindle() const { return request_.spindle; }
  [[nodiscard]] const FeatureOptions& options() const { return options_; }
  [[nodiscard]] Report& report() { return report_; }
  [[nodiscard]] const p21::Model& model() const { return model_; }
  [[nodiscard]] detail::GeometryReader& geometry() { return geometry_; }

  [[nodiscard]] Subject subject(const Instance& instance) const;
  [[nodiscard]] Subject subject(const Instance* instance) const;  // nullptr: "$"
  [[nodiscard]] std::string name(const Instance& instance) const;
  [[nodiscard]] std::string name(const Instance* instance) const;  // nullptr: "$"

  // `entity` and `attribute` must be literals (GeometryReader caches by their address).
  [[nodiscard]] bool is(const Instance* instance, std::string_view entity);
  [[nodiscard]] bool is(const Subject& subject, std::string_view entity) {
    return is(subject.instance, entity);
  }
  [[nodiscard]] bool set(const Instance& owner, std::string_view attribute);
  // A list attribute with at least one item (bosses, islands).
  [[nodiscard]] bool has_items(const Instance& owner, std::string_view attribute);
  [[nodiscard]] std::optional<p21::Value> get(const Instance& owner, std::string_view attribute);
  // An optional reference; null when unset. A reference of the wrong type is reported.
  const Instance* ref(const Instance& owner, std::string_view attribute, std::string_view type);
  // A number attribute, nullopt when unset. Typed values (e.g. LENGTH_MEASURE(2.)) are unwrapped.
  std::optional<double> number(const Instance& owner, std::string_view attribute);
  // A toleranced_length_measure (or a plain number) attribute.
  std::optional<Toleranced> toleranced(const Instance& owner, std::string_view attribute);
  std::optional<bool> boolean(const Instance& owner, std::string_view attribute);
  std::string_view enumeration(const Instance& owner, std::string_view attribute);
  // A string attribute; empty when unset or not a string.
  std::string text(const Instance& owner, std::string_view attribute);
  // A DIRECTION attribute in the feature's frame (normalised); nullopt when unset or bad.
  std::optional<Vec3> direction(const Instance& owner, std::string_view attribute);
  // An AXIS2_PLACEMENT_3D or CARTESIAN_POINT attribute; nullopt after reporting a bad one.
  std::optional<detail::Frame> placement(const Instance& owner, std::string_view attribute);
  std::optional<Vec3> point(const Instance& owner, std::string_view attribute);

  // False, after reporting, when a length is beyond FeatureOptions::max_length.
  bool size_ok(const Instance& at, double value, std::string_view what);

  // The depth of a machining feature: its depth plane's location along -z of the feature.
  std::optional<double> read_depth();
  std::optional<Tool> read_tool();
  Operation read_operation();

 private:
  detail::GeometryReader& geometry_;
  const p21::Model& model_;
  const Request& request_;
  const FeatureOptions& options_;
  Report& report_;
};

}  // namespace ncpost::stepnc::features
