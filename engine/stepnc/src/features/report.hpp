#pragma once
// How feature readers and planners say what they cannot do: findings about the instances of the
// model they name, in the order found. Readers report while they read (so their findings and
// the geometry reader's own stay in file order); planners report through the same interface,
// which their unit tests replace with `Findings`, a list (docs/features.md, "Read, then plan").

#include <string>
#include <string_view>
#include <vector>

#include "ncpost/diag/diagnostic.hpp"
#include "ncpost/p21/model.hpp"

namespace ncpost::stepnc::features {

// A number for a message: up to 4 decimals, trailing zeros dropped.
[[nodiscard]] std::string fmt(double x);

// An instance that a spec refers to: where a finding about it is reported (the instance's
// place in the file) and how messages name it, "#113 (MILLING_CUTTING_TOOL)". A Subject made
// without an instance stands for an unset attribute and is named "$".
struct Subject {
  const p21::Instance* instance = nullptr;
  std::string_view type;  // the entity name, as the model spells it

  [[nodiscard]] std::string name() const;
  [[nodiscard]] explicit operator bool() const { return instance != nullptr; }
};

struct Finding {
  diag::Code code{};
  Subject at;
  std::string message;
};

class Report {
 public:
  // `workingstep` is where what the generator cannot do at all is reported.
  explicit Report(Subject workingstep) : workingstep_(workingstep) {}
  Report(const Report&) = delete;
  Report& operator=(const Report&) = delete;
  virtual ~Report() = default;

  [[nodiscard]] const Subject& workingstep() const { return workingstep_; }

  // Each returns false, so that a reader or planner can `return report.unfit(...)`.
  // STEPNC-101 at the workingstep: "<workingstep>: <what> is not implemented; ...".
  bool not_implemented(std::string_view what);
  // STEPNC-102: the tool cannot make the feature as the operation asks.
  bool unfit(const Subject& at, std::string message);
  // STEPNC-103: data the path needs is missing, inconsistent or beyond a limit.
  bool bad(const Subject& at, std::string message);
  // STEPNC-103 at the workingstep: the path would need more than `max_moves` motions.
  bool limit_reached(std::size_t max_moves);
  // STEPNC-120 (a warning): a roughing pass leaves more stock than its allowance somewhere (a
  // corner tighter than the tool), which the finishing pass has to remove.
  void stock_left(const Subject& at, std::string message);
  // STEPNC-016: how a reading or a plan came about where the standard leaves it open.
  void note(const Subject& at, std::string message);
  // STEPNC-016 for a value a reader assumed where the file leaves it implicit:
  // "<at>: <what> taken as <value> (<why>)".
  void assumed(const Subject& at, std::string_view what, double value, std::string_view why);
  // A finding of another code (the INTEROP notes of values left implicit, implicit.hpp).
  void add_finding(diag::Code code, const Subject& at, std::string message) {
    add({code, at, std::move(message)});
  }

 protected:
  virtual void add(Finding finding) = 0;

 private:
  Subject workingstep_;
};

// A report that keeps its findings: what planner unit tests read.
class Findings final : public Report {
 public:
  using Report::Report;
  [[nodiscard]] const std::vector<Finding>& all() const { return findings_; }

 private:
  void add(Finding finding) override { findings_.push_back(std::move(finding)); }
  std::vector<Finding> findings_;
};

}  // namespace ncpost::stepnc::features
