#include "parameters.hpp"

#include <algorithm>
#include <cmath>

namespace ncpost::gcode::detail {

namespace {
// Numbers below this live in a flat array (LinuxCNC's 5602 fit); rarer large numbers (FANUC
// system variables) in a map.
constexpr std::uint32_t kDense = 8192;
}  // namespace

Parameters::Parameters(const ParameterRules& rules, StateView& state)
    : rules_(rules), state_(state) {
  const Value unset = rules_.vacant ? Value::empty() : Value::of(0);
  dense_.assign(std::min(rules_.count, kDense), unset);
}

const ParameterRange* Parameters::range_of(std::uint32_t number) const noexcept {
  for (const auto& r : rules_.ranges)
    if (number >= r.first && number <= r.last) return &r;
  return nullptr;
}

Value& Parameters::slot(std::uint32_t number) {
  if (number < dense_.size()) return dense_[number];
  auto [it, inserted] = sparse_.try_emplace(number, rules_.vacant ? Value::empty() : Value::of(0));
  return it->second;
}

const Value* Parameters::find(std::uint32_t number) const {
  if (number < dense_.size()) return &dense_[number];
  const auto it = sparse_.find(number);
  return it == sparse_.end() ? nullptr : &it->second;
}

namespace {
bool to_index(double number, std::uint32_t count, std::uint32_t& out, ParamStatus& status) {
  const double r = std::round(number);
  if (!std::isfinite(number) || std::abs(number - r) > 1e-4) {
    status = ParamStatus::NotInteger;
    return false;
  }
  if (r < 0 || r >= static_cast<double>(count)) {
    status = ParamStatus::OutOfRange;
    return false;
  }
  out = static_cast<std::uint32_t>(r);
  return true;
}
}  // namespace

ParamRead Parameters::get(double number) const {
  ParamRead out;
  std::uint32_t n = 0;
  if (!to_index(number, rules_.count, n, out.status)) return out;
  if (const ParameterRange* r = range_of(n)) {
    const int k = static_cast<int>(n - r->first);
    switch (r->source) {
      case ParameterSource::Machine:
        out.value = Value{r->assumed, false, true};
        out.machine = r;
        return out;
      case ParameterSource::Position:
        out.value = Value::of(state_.position(k));
        return out;
      case ParameterSource::MachinePosition:
        out.value = Value::of(state_.machine_position(k));
        return out;
      case ParameterSource::Tool:
        out.value = Value::of(state_.tool());
        return out;
      case ParameterSource::WorkOffsetIndex:
        out.value = Value::of(state_.work_offset_index());
        return out;
      case ParameterSource::WorkOffsets:
        out.value = Value::of(state_.work_offset(k / 20 + 1, k % 20));
        return out;
      case ParameterSource::AxisOffsets:
        out.value = Value::of(state_.axis_offset(k));
        return out;
      case ParameterSource::Units:
        out.value = Value::of(state_.metric() ? 0 : 1);
        return out;
    }
  }
  if (rules_.vacant && n == 0) {
    out.value = Value::empty();
    return out;
  }
  const Value* v = find(n);
  out.value = v ? *v : (rules_.vacant ? Value::empty() : Value::of(0));
  return out;
}

ParamStatus Parameters::set(double number, Value value) {
  ParamStatus status = ParamStatus::Ok;
  std::uint32_t n = 0;
  if (!to_index(number, rules_.count, n, status)) return status;
  if (n == 0 && rules_.zero_read_only) return ParamStatus::ReadOnly;
  if (const ParameterRange* r = range_of(n)) {
    if (!r->writable) return ParamStatus::ReadOnly;
    if (r->source == ParameterSource::WorkOffsets) {
      const int k = static_cast<int>(n - r->first);
      state_.set_work_offset(k / 20 + 1, k % 20, value.number);
    }
  }
  slot(n) = value;
  return ParamStatus::Ok;
}

bool Parameters::is_local_name(std::string_view name) const noexcept {
  return !name.empty() && name.front() != '_';
}

std::optional<Value> Parameters::get_named(std::string_view name) const {
  if (const auto s = state_.named(name)) return Value::of(*s);
  const auto& table = is_local_name(name) ? names_ : globals_;
  const auto it = table.find(name);
  if (it == table.end()) return std::nullopt;
  return it->second;
}

bool Parameters::exists_named(std::string_view name) const {
  return get_named(name).has_value();
}

void Parameters::set_named(std::string_view name, Value value) {
  auto& table = is_local_name(name) ? names_ : globals_;
  const auto it = table.find(name);
  if (it != table.end())
    it->second = value;
  else
    table.emplace(std::string(name), value);
}

void Parameters::push_frame() {
  Frame f;
  if (rules_.local_last >= rules_.local_first && rules_.local_first > 0) {
    const Value unset = rules_.vacant ? Value::empty() : Value::of(0);
    for (std::uint32_t i = rules_.local_first; i <= rules_.local_last; ++i) {
      f.locals.push_back(slot(i));
      slot(i) = unset;
    }
  }
  f.names = std::move(names_);
  names_.clear();
  frames_.push_back(std::move(f));
}

void Parameters::pop_frame() {
  if (frames_.empty()) return;
  Frame f = std::move(frames_.back());
  frames_.pop_back();
  for (std::size_t i = 0; i < f.locals.size(); ++i)
    slot(rules_.local_first + static_cast<std::uint32_t>(i)) = f.locals[i];
  names_ = std::move(f.names);
}

}  // namespace ncpost::gcode::detail
