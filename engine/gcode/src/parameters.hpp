#pragma once
// Parameters (variables) of one read: numbered ones (#1, R1, Q1), named ones (LinuxCNC
// #<name>, Sinumerik DEF variables), frames for the locals of a call, and the ranges whose
// value is the machine state (the current position, the tool) or a value only the machine
// knows (a probe result), as the dialect declares them.

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "ncpost/gcode/dialect.hpp"
#include "value.hpp"

namespace ncpost::gcode::detail {

// The converter's state as parameters show it.
class StateView {
 public:
  virtual ~StateView() = default;
  // In the current length unit, current coordinate system (axis 0..8 = X Y Z A B C U V W).
  [[nodiscard]] virtual double position(int axis) const = 0;
  [[nodiscard]] virtual double machine_position(int axis) const = 0;
  [[nodiscard]] virtual int tool() const = 0;
  [[nodiscard]] virtual int work_offset_index() const = 0;
  [[nodiscard]] virtual double work_offset(int index, int axis) const = 0;
  virtual void set_work_offset(int index, int axis, double value) = 0;
  [[nodiscard]] virtual double axis_offset(int axis) const = 0;
  [[nodiscard]] virtual bool metric() const = 0;
  // A named value of the state (LinuxCNC #<_x>, #<_metric>, ...), or nullopt.
  [[nodiscard]] virtual std::optional<double> named(std::string_view name) const = 0;
};

enum class ParamStatus : std::uint8_t { Ok, OutOfRange, NotInteger, ReadOnly, Undefined };

struct ParamRead {
  Value value{};
  ParamStatus status = ParamStatus::Ok;
  const ParameterRange* machine = nullptr;  // read a Machine range (assumed value)
};

class Parameters {
 public:
  Parameters(const ParameterRules& rules, StateView& state);

  // #n, Rn, Qn. `number` is the evaluated value (must be a non-negative integer).
  [[nodiscard]] ParamRead get(double number) const;
  [[nodiscard]] ParamStatus set(double number, Value value);

  // Named parameters: LinuxCNC's are local to the call unless they start with '_'.
  [[nodiscard]] std::optional<Value> get_named(std::string_view name) const;
  void set_named(std::string_view name, Value value);
  [[nodiscard]] bool exists_named(std::string_view name) const;

  // A call's frame: the locals (numbered local range and local names) are saved and cleared
  // on push, restored on pop.
  void push_frame();
  void pop_frame();
  [[nodiscard]] std::size_t depth() const noexcept { return frames_.size(); }

  // The machine ranges, for warnings that name them.
  [[nodiscard]] const ParameterRange* range_of(std::uint32_t number) const noexcept;

 private:
  [[nodiscard]] Value& slot(std::uint32_t number);
  [[nodiscard]] const Value* find(std::uint32_t number) const;
  [[nodiscard]] bool is_local_name(std::string_view name) const noexcept;

  const ParameterRules& rules_;
  StateView& state_;
  std::vector<Value> dense_;                         // [0, kDense)
  std::unordered_map<std::uint32_t, Value> sparse_;  // beyond
  std::map<std::string, Value, std::less<>> globals_;
  struct Frame {
    std::vector<Value> locals;
    std::map<std::string, Value, std::less<>> names;
  };
  std::vector<Frame> frames_;
  std::map<std::string, Value, std::less<>> names_;  // the current frame's local names
};

}  // namespace ncpost::gcode::detail
