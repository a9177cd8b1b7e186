// THREAD_DRILLING: the reader (threads.hpp).

#include <cctype>
#include <cmath>

#include "holes.hpp"
#include "reader.hpp"
#include "threads.hpp"

namespace ncpost::stepnc::features {
namespace {

constexpr double kEps = 1e-9;

std::string upper_no_space(std::string_view text) {
  std::string out;
  for (const char c : text)
    if (!std::isspace(static_cast<unsigned char>(c)))
      out += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return out;
}

// The ROUND_HOLE the THREAD names (applied_shape), on the thread's axis and top.
const Instance* read_thread_hole(Reader& reader) {
  Report& report = reader.report();
  const Instance& thread = reader.feature();
  const Instance& op = reader.operation();
  const Instance* hole = nullptr;
  if (const auto shapes = reader.get(thread, "applied_shape"); shapes && shapes->is_list()) {
    const auto items = reader.model().items(*shapes);
    if (items.size() == 1)
      hole = reader.geometry().instance(items[0], "machining_feature", &thread, "applied_shape");
  }
  if (hole == nullptr || !reader.is(hole, "round_hole")) {
    report.not_implemented(reader.name(op) + " on " + reader.name(thread) +
                           " whose applied_shape is not one ROUND_HOLE");
    return nullptr;
  }
  const auto thread_frame = reader.placement(thread, "feature_placement");
  const auto hole_frame = reader.placement(*hole, "feature_placement");
  if (!thread_frame || !hole_frame) return nullptr;
  if ((thread_frame->origin - hole_frame->origin).length() > 1e-6 ||
      (thread_frame->z - hole_frame->z).length() > 1e-9) {
    report.bad(reader.subject(thread), reader.name(thread) +
                                           " is not placed on the axis and top of its hole " +
                                           reader.name(*hole));
    return nullptr;
  }
  return hole;
}

// number_of_threads per its_parameter_unit: the pitch in mm.
std::optional<double> read_pitch(Reader& reader, const Instance& count, double threads) {
  const std::string unit = upper_no_space(reader.text(count, "its_parameter_unit"));
  if (unit == "1/MM" || unit == "/MM" || unit == "PERMM" || unit == "THREADSPERMM")
    return 1 / threads;
  if (unit == "1/IN" || unit == "/IN" || unit == "1/INCH" || unit == "PERINCH" || unit == "TPI" ||
      unit == "THREADSPERINCH")
    return 25.4 / threads;
  reader.report().bad(reader.subject(count),
                      reader.name(count) + " gives the number of threads per '" + unit +
                          "': per mm (1/MM) or per inch (1/IN, TPI) are understood, so the "
                          "pitch of " +
                          reader.name(reader.feature()) + " is unknown");
  return std::nullopt;
}

// The thread's own data: major diameter, pitch and hand.
bool read_thread(Reader& reader, double& major, ThreadSpec& spec) {
  Report& report = reader.report();
  const Instance& thread = reader.feature();
  const auto major_diameter = reader.number(thread, "major_diameter");
  const Instance* count = reader.ref(thread, "number_of_threads", "numeric_parameter");
  const Instance* hand = reader.ref(thread, "thread_hand", "descriptive_parameter");
  // 0 when missing (refused below); a plain double, which GCC does not think uninitialised.
  const double threads = count ? reader.number(*count, "its_parameter_value").value_or(0.0) : 0.0;
  if (!major_diameter || !(*major_diameter > 0) || !(threads > 0) || hand == nullptr)
    return report.bad(reader.subject(thread),
                      reader.name(thread) +
                          " needs a positive major_diameter and number_of_threads, and a "
                          "thread_hand");
  if (!reader.size_ok(thread, *major_diameter, "major_diameter")) return false;
  major = *major_diameter;
  const auto pitch = read_pitch(reader, *count, threads);
  if (!pitch) return false;
  spec.pitch = *pitch;
  const std::string hand_text = upper_no_space(reader.text(*hand, "descriptive_string"));
  if (hand_text.rfind("RIGHT", 0) == 0 || hand_text == "RH" || hand_text == "R")
    spec.right = true;
  else if (hand_text.rfind("LEFT", 0) == 0 || hand_text == "LH" || hand_text == "L")
    spec.right = false;
  else
    return report.bad(reader.subject(*hand), reader.name(*hand) + " thread_hand '" + hand_text +
                                                 "' is neither RIGHT nor LEFT");
  return true;
}

// The hole's diameter, bottom and depth against the thread's.
struct HoleData {
  Toleranced diameter;
  const Instance* bottom = nullptr;
  double depth = 0;
};

std::optional<HoleData> read_hole_data(Reader& reader, const Instance& hole, double major,
                                       ThreadSpec& spec) {
  Report& report = reader.report();
  const Instance& thread = reader.feature();
  HoleData out;
  const auto diameter = reader.toleranced(hole, "diameter");
  out.bottom = reader.ref(hole, "bottom_condition", "hole_bottom_condition");
  if (!diameter || !(diameter->size > 0) || out.bottom == nullptr) {
    report.bad(reader.subject(hole),
               reader.name(hole) + " needs a diameter and a bottom_condition");
    return std::nullopt;
  }
  out.diameter = *diameter;
  if (reader.set(hole, "change_in_diameter")) {
    report.not_implemented(reader.name(reader.operation()) + " in the tapered " +
                           reader.name(hole));
    return std::nullopt;
  }
  if (!(major > diameter->size)) {
    report.bad(reader.subject(thread), reader.name(thread) + " major_diameter " + fmt(major) +
                                           " is not larger than " + reader.name(hole) +
                                           "'s diameter " + fmt(diameter->size));
    return std::nullopt;
  }
  const auto thread_depth = reader.read_depth();  // the THREAD's own depth plane
  const Instance* hole_plane = reader.ref(hole, "depth", "elementary_surface");
  const auto hole_plane_frame =
      hole_plane ? reader.placement(*hole_plane, "position") : std::nullopt;
  if (!thread_depth || !hole_plane_frame) {
    if (hole_plane == nullptr)
      report.bad(reader.subject(hole), reader.name(hole) + " has no depth plane");
    return std::nullopt;
  }
  out.depth = -hole_plane_frame->origin.z;
  if (!(out.depth > 0) || std::abs(hole_plane_frame->z.z - 1) > 1e-9) {
    report.bad(
        reader.subject(*hole_plane),
        reader.name(*hole_plane) + " is not a depth plane below the top of " + reader.name(hole));
    return std::nullopt;
  }
  const bool through = reader.is(out.bottom, "through_bottom_condition");
  if (*thread_depth > out.depth + kEps && !through) {
    report.bad(reader.subject(thread), reader.name(thread) + " runs " + fmt(*thread_depth) +
                                           " deep, deeper than its hole " + reader.name(hole) +
                                           " (" + fmt(out.depth) + ")");
    return std::nullopt;
  }
  spec.length = *thread_depth;
  return out;
}

// A thread drill-mill whose drilling diameter is the hole's.
bool check_tool(Reader& reader, const Tool& tool, const Instance& hole, const Toleranced& hole_d) {
  const auto op = [&] { return reader.name(reader.operation()); };
  const auto thread = [&] { return reader.name(reader.feature()); };
  if (!reader.is(tool.body, "milling_threading_tool") && !reader.is(tool.body, "thread_mill"))
    return reader.report().unfit(tool.subject, tool.subject.name() + " is not a threading tool; " +
                                                   op() + " on " + thread() +
                                                   " needs a thread drill-mill");
  const double tool_d = 2 * tool.radius;
  if (tool_d > hole_d.size + hole_d.upper + kEps || tool_d + hole_d.lower + kEps < hole_d.size)
    return reader.report().unfit(tool.subject, tool.subject.name() + " diameter " + fmt(tool_d) +
                                                   " is not the diameter " + fmt(hole_d.size) +
                                                   " of " + reader.name(hole) + " that " + op() +
                                                   " drills for " + thread());
  return true;
}

// What the operation asks besides the helix.
bool read_drilling(Reader& reader, ThreadSpec& spec) {
  Report& report = reader.report();
  const Instance& op = reader.operation();
  if (!reader.feed() || !(*reader.feed() > 0))
    return report.bad(reader.subject(op), reader.name(op) + " has no feed rate in its technology");
  spec.retract_z = reader.number(op, "retract_plane").value_or(reader.options().clearance);
  if (!(spec.retract_z > 0))
    return report.bad(reader.subject(op),
                      reader.name(op) + " retract_plane must be above the hole");
  spec.dwell = reader.number(op, "dwell_time_bottom").value_or(0);
  if (spec.dwell < 0)
    return report.bad(reader.subject(op), reader.name(op) + " dwell_time_bottom is negative");
  if (reader.set(op, "its_machining_strategy") || reader.set(op, "feed_on_retract"))
    return report.not_implemented(reader.name(op) + " with a drilling strategy or feed_on_retract");
  return true;
}

}  // namespace

bool read_thread_drilling(Reader& reader, ThreadSpec& spec) {
  Report& report = reader.report();
  const Instance& thread = reader.feature();
  const Instance& op = reader.operation();
  if (reader.boolean(op, "helical_movement_on_forward").value_or(false))
    return report.not_implemented(reader.name(op) +
                                  " with helical_movement_on_forward .T. (milling the "
                                  "hole and the thread on the way in) on " +
                                  reader.name(thread));
  if (!reader.is(&thread, "thread"))
    return report.bad(reader.subject(thread),
                      reader.name(op) + " on " + reader.name(thread) +
                          ": a thread drilling needs a THREAD feature, which gives the pitch, "
                          "the major diameter and the hand (and names its hole)");
  if (!reader.boolean(thread, "inner_or_outer_thread").value_or(false))
    return report.bad(reader.subject(thread),
                      reader.name(thread) +
                          " is an outer thread (inner_or_outer_thread .F.), which " +
                          reader.name(op) + " cannot make");
  const Instance* hole = read_thread_hole(reader);
  double major = 0;
  if (hole == nullptr || !read_thread(reader, major, spec)) return false;
  const auto hole_data = read_hole_data(reader, *hole, major, spec);
  if (!hole_data) return false;
  const auto tool = reader.read_tool();
  if (!tool || !check_tool(reader, *tool, *hole, hole_data->diameter)) return false;
  const auto bottom_z = read_drill_bottom(reader, *hole, *hole_data->bottom, hole_data->depth,
                                          *tool, true, reader.name(op) + " in ");
  if (!bottom_z || !check_drill_edge(reader, *tool, *bottom_z, *hole)) return false;
  spec.bottom_z = *bottom_z;
  spec.offset = major / 2 - tool->radius;
  return read_drilling(reader, spec);
}

}  // namespace ncpost::stepnc::features
