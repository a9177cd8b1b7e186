#include "ext_math.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <numbers>

namespace ncpost::xslt::detail {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kTwoPi = 2 * std::numbers::pi;
// Angles closer than this (radians) count as equal: start == end is a full circle, a point on
// a quadrant boundary is on it.
constexpr double kAngleTolerance = 1e-9;

double degrees(double radians) {
  return radians * 180.0 / kPi;
}

// Length in bytes of the UTF-8 sequence at `s` (1 for an invalid byte).
std::size_t sequence_length(std::string_view s) {
  const auto lead = static_cast<unsigned char>(s[0]);
  std::size_t n = 1;
  if (lead >= 0xC2 && lead <= 0xDF)
    n = 2;
  else if (lead >= 0xE0 && lead <= 0xEF)
    n = 3;
  else if (lead >= 0xF0 && lead <= 0xF4)
    n = 4;
  if (n == 1 || s.size() < n) return 1;
  for (std::size_t k = 1; k < n; ++k) {
    if ((static_cast<unsigned char>(s[k]) & 0xC0) != 0x80) return 1;
  }
  return n;
}

}  // namespace

namespace {

constexpr double kPowers[] = {1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12};

// |value| * 10^decimals rounded as printf rounds the exact binary value, when integers can
// tell. Below 1e12 the product is within 2^-14 of the exact one (powers of ten up to 1e22 are
// exact doubles; one rounding of at most half an ulp, which is 2^-13 there), and truncation and
// the subtraction are exact. So when the fraction is further than 1e-3 from one half, the exact
// value rounds the same way. Nothing near a tie, or for huge or non-finite values.
std::optional<std::uint64_t> rounded_scaled(double value, int decimals) {
  const double scaled = std::abs(value) * kPowers[decimals];
  if (!(scaled < 1e12)) return std::nullopt;              // also NaN
  const auto whole = static_cast<std::uint64_t>(scaled);  // floor: scaled is not negative
  const double fraction = scaled - static_cast<double>(whole);
  if (std::abs(fraction - 0.5) <= 1e-3) return std::nullopt;
  return whole + (fraction > 0.5 ? 1 : 0);
}

// Two digits per division: "00", "01", ... "99".
constexpr char kDigitPairs[] =
    "0001020304050607080910111213141516171819202122232425262728293031323334353637383940414243444546"
    "4748495051525354555657585960616263646566676869707172737475767778798081828384858687888990919293"
    "949596979899";

// The lowest `count` decimal digits of `n` written leftwards, ending just before `p`; they are
// taken off `n`. Returns where they begin.
char* low_digits_backwards(char* p, std::uint64_t& n, int count) {
  for (; count >= 2; count -= 2) {
    p -= 2;
    std::memcpy(p, kDigitPairs + 2 * (n % 100), 2);
    n /= 100;
  }
  if (count == 1) {
    *--p = static_cast<char>('0' + n % 10);
    n /= 10;
  }
  return p;
}

// All the digits of `n` ("0" for zero), likewise.
char* all_digits_backwards(char* p, std::uint64_t n) {
  while (n >= 100) {
    p -= 2;
    std::memcpy(p, kDigitPairs + 2 * (n % 100), 2);
    n /= 100;
  }
  if (n >= 10) {
    p -= 2;
    std::memcpy(p, kDigitPairs + 2 * n, 2);
    return p;
  }
  *--p = static_cast<char>('0' + n);
  return p;
}

char* write_bytes(char* at, const char* bytes, std::size_t length) {
  std::memcpy(at, bytes, length);
  return at + length;
}

// The format's rules applied to printf-style fixed text ("-12.500"), written at `at`.
char* write_trimmed(char* at, char* buffer, std::size_t end, const NumberFormat& format) {
  std::size_t begin = 0;
  const std::string_view text(buffer, end);
  // Anything that rounds to zero is "0", never "-0".
  if (buffer[0] == '-' && text.find_first_not_of("0.", 1) == std::string_view::npos) begin = 1;
  const std::size_t point = text.find('.', begin);
  bool has_point = point != std::string_view::npos;
  if (has_point && !format.trailing_zeros) {
    while (buffer[end - 1] == '0') --end;
  }
  if (has_point && point + 1 == end) {
    if (!format.decimal_point) {
      --end;
      has_point = false;
    }
  } else if (!has_point && format.decimal_point) {
    buffer[end++] = '.';
    has_point = true;
  }
  const bool negative = buffer[begin] == '-';
  const std::size_t first = begin + (negative ? 1 : 0);
  if (!format.leading_zero && has_point && buffer[first] == '0' && buffer[first + 1] == '.' &&
      first + 2 < end) {
    // "0.5" -> ".5", "-0.5" -> "-.5"
    if (negative) *at++ = '-';
    return write_bytes(at, buffer + first + 1, end - first - 1);
  }
  return write_bytes(at, buffer + begin, end - begin);
}

}  // namespace

char* write_number(char* at, double value, const NumberFormat& format) {
  const int decimals = std::clamp(format.decimals, 0, 12);
  const std::optional<std::uint64_t> rounded = rounded_scaled(value, decimals);
  if (!rounded) {
    // Near a rounding tie, or too large for the integer: std::to_chars rounds the exact binary
    // value, as printf does; its text is then trimmed by the same rules.
    char buffer[kNumberRoom];
    const auto done = std::to_chars(buffer, buffer + sizeof buffer - 1, value,
                                    std::chars_format::fixed, decimals);
    if (done.ec != std::errc()) return at;
    return write_trimmed(at, buffer, static_cast<std::size_t>(done.ptr - buffer), format);
  }
  // The same rules on the integer, its digits written from the right (this runs for every
  // coordinate of every block): the fraction without its trailing zeros unless the format
  // keeps them, the point, the whole part unless the format drops a lone leading zero, the
  // sign unless the value rounds to zero.
  std::uint64_t n = *rounded;
  int fraction_digits = decimals;
  if (!format.trailing_zeros) {
    while (fraction_digits > 0 && n % 10 == 0) {
      n /= 10;
      --fraction_digits;
    }
  }
  char text[32];  // below 1e12: 13 digits, the point and the sign at most
  char* const end = text + sizeof text;
  char* p = end;
  if (fraction_digits == 0 && format.decimal_point) *--p = '.';
  p = low_digits_backwards(p, n, fraction_digits);
  if (fraction_digits > 0) *--p = '.';
  if (n != 0 || format.leading_zero || fraction_digits == 0) p = all_digits_backwards(p, n);
  if (*rounded != 0 && std::signbit(value)) *--p = '-';
  return write_bytes(at, p, static_cast<std::size_t>(end - p));
}

void append_number(std::string& out, double value, const NumberFormat& format) {
  char text[kNumberRoom];
  const char* end = write_number(text, value, format);
  out.append(text, static_cast<std::size_t>(end - text));  // (pointer, length): no replace()
}

std::string format_number(double value, const NumberFormat& format) {
  std::string s;
  append_number(s, value, format);
  return s;
}

std::optional<Quantity> quantity_named(std::string_view name) {
  if (name == "length") return Quantity::Length;
  if (name == "angle") return Quantity::Angle;
  if (name == "feed") return Quantity::Feed;
  if (name == "speed") return Quantity::Speed;
  if (name == "dwell") return Quantity::Dwell;
  return std::nullopt;
}

ScaledQuantity scale_quantity(const JobConfig& config, double program_unit_mm, Quantity quantity,
                              double value) {
  const NumberFormat* format = nullptr;
  double scale = 1.0;
  switch (quantity) {
    case Quantity::Length:
    case Quantity::Feed:
      format = quantity == Quantity::Length ? &config.length : &config.feed;
      scale = program_unit_mm / (config.units == Units::Inch ? 25.4 : 1.0);
      break;
    case Quantity::Angle:
      format = &config.angle;
      break;
    case Quantity::Speed:
      format = &config.speed;
      break;
    case Quantity::Dwell:
      format = &config.dwell;
      break;
  }
  return {value * scale * format->scale, format};
}

bool append_quantity(std::string& out, const JobConfig& config, double program_unit_mm,
                     Quantity quantity, double value) {
  const ScaledQuantity scaled = scale_quantity(config, program_unit_mm, quantity, value);
  if (!std::isfinite(scaled.value)) return false;
  append_number(out, scaled.value, *scaled.format);
  return true;
}

std::string shortest(double value) {
  if (value == 0) return "0";
  char buffer[64];
  const auto done = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, done.ptr);
}

std::optional<double> arc_sweep(const PlaneArc& a) {
  if (a.turns == 0) return std::nullopt;
  const double r = std::hypot(a.sx - a.cx, a.sy - a.cy);
  if (!(r > 0) || !std::isfinite(r)) return std::nullopt;
  const double a0 = std::atan2(a.sy - a.cy, a.sx - a.cx);
  const double a1 = std::atan2(a.ey - a.cy, a.ex - a.cx);
  double d = a.turns > 0 ? a1 - a0 : a0 - a1;
  while (d <= kAngleTolerance) d += kTwoPi;
  while (d > kTwoPi + kAngleTolerance) d -= kTwoPi;
  const double sweep = d + kTwoPi * (std::abs(a.turns) - 1);
  return degrees(a.turns > 0 ? sweep : -sweep);
}

std::optional<double> arc_radius(const PlaneArc& a) {
  const std::optional<double> sweep = arc_sweep(a);
  if (!sweep || std::abs(*sweep) >= 360.0 - 1e-7) return std::nullopt;
  const double r = std::hypot(a.sx - a.cx, a.sy - a.cy);
  return std::abs(*sweep) > 180.0 + 1e-7 ? -r : r;
}

std::optional<std::array<double, 2>> arc_centre(double sx, double sy, double ex, double ey,
                                                double r, bool clockwise) {
  const double dx = ex - sx;
  const double dy = ey - sy;
  const double chord = std::hypot(dx, dy);
  const double radius = std::abs(r);
  if (!(chord > 0) || !(radius > 0) || !std::isfinite(chord) || !std::isfinite(radius))
    return std::nullopt;
  const double half = chord / 2;
  const double tolerance = 1e-9 * std::max(1.0, radius);
  if (half > radius + tolerance) return std::nullopt;
  const double h = std::sqrt(std::max(0.0, radius * radius - half * half));
  // Left of the chord direction: the centre of a counter-clockwise arc under 180 degrees.
  const double nx = -dy / chord;
  const double ny = dx / chord;
  const double side = (clockwise ? -1.0 : 1.0) * (r < 0 ? -1.0 : 1.0);
  return std::array<double, 2>{sx + dx / 2 + side * h * nx, sy + dy / 2 + side * h * ny};
}

std::optional<std::vector<Point3>> arc_split(const PlaneArc& a, double sz, double ez,
                                             double max_sweep_degrees, std::size_t max_pieces) {
  const std::optional<double> sweep = arc_sweep(a);
  if (!sweep || !(max_sweep_degrees > 0) || !std::isfinite(sz) || !std::isfinite(ez))
    return std::nullopt;
  const double pieces_real = std::ceil(std::abs(*sweep) / max_sweep_degrees - 1e-9);
  if (!(pieces_real >= 1) || pieces_real > static_cast<double>(max_pieces)) return std::nullopt;
  const auto pieces = static_cast<std::size_t>(pieces_real);
  const double r = std::hypot(a.sx - a.cx, a.sy - a.cy);
  const double a0 = std::atan2(a.sy - a.cy, a.sx - a.cx);
  const double step = *sweep / static_cast<double>(pieces) * kPi / 180.0;
  std::vector<Point3> points;
  points.reserve(pieces);
  for (std::size_t n = 1; n < pieces; ++n) {
    const double angle = a0 + step * static_cast<double>(n);
    const double t = static_cast<double>(n) / static_cast<double>(pieces);
    points.push_back({a.cx + r * std::cos(angle), a.cy + r * std::sin(angle), sz + (ez - sz) * t});
  }
  points.push_back({a.ex, a.ey, ez});
  return points;
}

std::optional<std::vector<Point3>> arc_split_quadrants(const PlaneArc& a, double sz, double ez,
                                                       std::size_t max_pieces) {
  const std::optional<double> sweep_degrees = arc_sweep(a);
  if (!sweep_degrees || !std::isfinite(sz) || !std::isfinite(ez)) return std::nullopt;
  const double sweep = *sweep_degrees * kPi / 180.0;
  const double r = std::hypot(a.sx - a.cx, a.sy - a.cy);
  const double a0 = std::atan2(a.sy - a.cy, a.sx - a.cx);
  const double direction = sweep > 0 ? 1.0 : -1.0;
  const double total = std::abs(sweep);
  std::vector<Point3> points;
  // The first boundary strictly after the start in the direction of travel.
  const double quarter = kPi / 2;
  double k = direction > 0 ? std::floor(a0 / quarter + kAngleTolerance) + 1
                           : std::ceil(a0 / quarter - kAngleTolerance) - 1;
  for (;;) {
    const double boundary = k * quarter;
    const double travelled = (boundary - a0) * direction;
    if (travelled >= total - kAngleTolerance) break;
    if (points.size() + 1 >= max_pieces) return std::nullopt;
    const double t = travelled / total;
    // Exact axis points: cos/sin of multiples of 90 degrees, without rounding noise.
    const long q = std::lround(k) % 4;
    const long quadrant = q < 0 ? q + 4 : q;
    const double ux = quadrant == 0 ? 1 : quadrant == 2 ? -1 : 0;
    const double uy = quadrant == 1 ? 1 : quadrant == 3 ? -1 : 0;
    points.push_back({a.cx + r * ux, a.cy + r * uy, sz + (ez - sz) * t});
    k += direction;
  }
  points.push_back({a.ex, a.ey, ez});
  return points;
}

std::optional<Rotary> rotary_angles(double i, double j, double k, std::string_view kinematics,
                                    double previous_c) {
  const double length = std::sqrt(i * i + j * j + k * k);
  if (!(length > 0) || !std::isfinite(length)) return std::nullopt;
  i /= length;
  j /= length;
  k /= length;
  Rotary r{degrees(std::acos(std::clamp(k, -1.0, 1.0))), previous_c, false};
  const double horizontal = std::hypot(i, j);
  if (horizontal < 1e-9) {
    r.singular = true;
    return r;
  }
  if (kinematics == "AC") {
    r.c = degrees(std::atan2(i, -j));  // v = Rz(C) Rx(A) (0, 0, 1) = (sinA sinC, -sinA cosC, cosA)
  } else if (kinematics == "BC") {
    r.c = degrees(std::atan2(j, i));  // v = Rz(C) Ry(B) (0, 0, 1) = (sinB cosC, sinB sinC, cosB)
  } else {
    return std::nullopt;
  }
  if (r.c <= -180.0) r.c += 360.0;
  if (r.c == 0) r.c = 0;  // no -0
  return r;
}

std::string sanitize_comment(std::string_view text, const CommentRules& rules) {
  // Looked up once per character below; `rules.allowed` is a list of ASCII characters.
  std::array<bool, 128> allowed{};
  for (const char ch : rules.allowed) {
    const auto byte = static_cast<unsigned char>(ch);
    if (byte < allowed.size()) allowed[byte] = true;
  }
  // The replacement itself must not be able to close a comment either.
  std::string replacement = rules.replacement;
  std::erase_if(replacement, [](char ch) {
    const auto byte = static_cast<unsigned char>(ch);
    return ch == '(' || ch == ')' || byte < 0x20 || byte == 0x7F;
  });
  const std::size_t replacement_characters = characters(replacement);
  std::string out;
  out.reserve(text.size());
  std::size_t count = 0;
  while (!text.empty()) {
    const std::size_t n = sequence_length(text);
    char ch = text[0];
    text.remove_prefix(n);
    if (rules.max_length != 0 && count >= rules.max_length) break;
    bool keep = false;
    if (n == 1) {
      if (rules.upper_case && ch >= 'a' && ch <= 'z') ch = static_cast<char>(ch - 'a' + 'A');
      const auto byte = static_cast<unsigned char>(ch);
      keep = byte >= 0x20 && byte < 0x7F && ch != '(' && ch != ')' && allowed[byte];
    }
    if (keep) {
      out += ch;
      ++count;
    } else if (!replacement.empty()) {
      out += replacement;
      count += replacement_characters;
    }
  }
  // A replacement could be longer than one character; cut again, on a character boundary.
  if (rules.max_length != 0 && characters(out) > rules.max_length) {
    std::size_t bytes = 0;
    for (std::size_t c = 0; c < rules.max_length; ++c)
      bytes += sequence_length(std::string_view(out).substr(bytes));
    out.resize(bytes);
  }
  const std::size_t first = out.find_first_not_of(' ');
  if (first == std::string::npos) return {};
  const std::size_t last = out.find_last_not_of(' ');
  return out.substr(first, last - first + 1);
}

std::size_t characters(std::string_view text) {
  std::size_t count = 0;
  while (!text.empty()) {
    text.remove_prefix(sequence_length(text));
    ++count;
  }
  return count;
}

}  // namespace ncpost::xslt::detail
