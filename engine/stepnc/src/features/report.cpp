#include "report.hpp"

#include <cstdio>

namespace ncpost::stepnc::features {

std::string fmt(double x) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.4f", x);
  std::string s(buffer);
  while (!s.empty() && s.back() == '0') s.pop_back();
  if (!s.empty() && s.back() == '.') s.pop_back();
  return s == "-0" ? "0" : s;
}

std::string Subject::name() const {
  if (instance == nullptr) return "$";
  return "#" + std::to_string(instance->id) + " (" + std::string(type) + ")";
}

bool Report::not_implemented(std::string_view what) {
  add({diag::Code::StepncFeatureNotImplemented, workingstep_,
       workingstep_.name() + ": " + std::string(what) +
           " is not implemented; nothing is generated"});
  return false;
}

bool Report::unfit(const Subject& at, std::string message) {
  add({diag::Code::StepncToolUnfit, at, std::move(message)});
  return false;
}

bool Report::bad(const Subject& at, std::string message) {
  add({diag::Code::StepncFeatureData, at, std::move(message)});
  return false;
}

bool Report::limit_reached(std::size_t max_moves) {
  return bad(workingstep_,
             workingstep_.name() + ": the generated path needs more than " +
                 std::to_string(max_moves) +
                 " motions (FeatureOptions::max_moves); check the stepover and depths");
}

void Report::stock_left(const Subject& at, std::string message) {
  add({diag::Code::StepncCornerStock, at, std::move(message)});
}

void Report::note(const Subject& at, std::string message) {
  add({diag::Code::StepncNote, at, std::move(message)});
}

void Report::assumed(const Subject& at, std::string_view what, double value, std::string_view why) {
  note(at, at.name() + ": " + std::string(what) + " taken as " + fmt(value) + " (" +
               std::string(why) + ")");
}

}  // namespace ncpost::stepnc::features
