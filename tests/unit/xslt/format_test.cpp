// Number formatting: write_number's integer path (every value it can round exactly below
// 1e12) gives exactly the digits of std::to_chars, which rounds the exact binary value as printf
// does, including ties, values next to ties, both sides of the integer path's range, and
// negatives; then the format rules, as first written on that text.

#include <gtest/gtest.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "ext_math.hpp"

namespace ncpost::xslt::detail {
namespace {

std::string reference(double value, int decimals) {
  char buffer[400];
  const auto done =
      std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::fixed, decimals);
  return std::string(buffer, done.ptr);
}

// Every digit kept (no trimming), so the digits themselves are compared; only "-0" becomes "0".
std::string every_digit(double value, int decimals) {
  return format_number(value, NumberFormat{decimals, false, true, true, 1.0});
}

// to_chars's text with the same "-0" rule.
std::string reference_digits(double value, int decimals) {
  std::string s = reference(value, decimals);
  if (!s.empty() && s[0] == '-' && s.find_first_not_of("0.", 1) == std::string::npos) s.erase(0, 1);
  return s;
}

TEST(WriteNumberDigits, AgreesWithToCharsOnRandomValues) {
  std::mt19937_64 random(20261125);
  std::uniform_real_distribution<double> magnitude(-3, 13);
  std::uniform_int_distribution<int> decimals(0, 12);
  for (int i = 0; i < 300000; ++i) {
    const double v = std::pow(10.0, magnitude(random)) * (random() % 2 ? 1 : -1);
    const int d = decimals(random);
    ASSERT_EQ(every_digit(v, d), reference_digits(v, d)) << v << " with " << d;
  }
}

TEST(WriteNumberDigits, AgreesWithToCharsAtAndNextToTies) {
  for (int d = 0; d <= 12; ++d) {
    const double unit = std::pow(10.0, -d);
    for (long k = -2000; k <= 2000; ++k) {
      // (k + 1/2) units: ties in decimal, usually not exact in binary; and their neighbours.
      const double tie = (static_cast<double>(k) + 0.5) * unit;
      for (double v : {tie, std::nextafter(tie, 1e300), std::nextafter(tie, -1e300)})
        ASSERT_EQ(every_digit(v, d), reference_digits(v, d)) << v << " with " << d;
    }
  }
  // Exact binary ties round to even, as printf does.
  EXPECT_EQ(every_digit(0.125, 2), "0.12");
  EXPECT_EQ(every_digit(0.375, 2), "0.38");
  EXPECT_EQ(every_digit(2.5, 0), "2");
  EXPECT_EQ(every_digit(-2.5, 0), "-2");
}

TEST(WriteNumberDigits, EdgesOfTheIntegerPath) {
  for (int d = 0; d <= 12; ++d) {
    const double edge = 1e12 / std::pow(10.0, d);
    for (double v : {edge, std::nextafter(edge, 0.0), std::nextafter(edge, 1e300), -edge, 0.0, -0.0,
                     1e-13, -1e-13, 0.4999999999, 999999.9995, 1.7976931348623157e308})
      ASSERT_EQ(every_digit(v, d), reference_digits(v, d)) << v << " with " << d;
  }
}

// The format rules as first written: std::to_chars's fixed text, trimmed as text.
std::string reference_format(double value, const NumberFormat& format) {
  std::string s = reference_digits(value, std::clamp(format.decimals, 0, 12));
  std::size_t dot = s.find('.');
  if (!format.trailing_zeros && dot != std::string::npos) {
    while (s.back() == '0') s.pop_back();
  }
  if (dot != std::string::npos && dot + 1 == s.size()) {
    if (!format.decimal_point) s.pop_back();
  } else if (dot == std::string::npos && format.decimal_point) {
    s += '.';
  }
  dot = s.find('.');
  if (!format.leading_zero && dot != std::string::npos && dot + 1 < s.size()) {
    const std::size_t first = s[0] == '-' ? 1 : 0;
    if (dot == first + 1 && s[first] == '0') s.erase(first, 1);
  }
  return s;
}

TEST(FormatNumber, IntegerPathAgreesWithTheTextRules) {
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> magnitude(-4, 12);
  std::vector<double> values{0.0, -0.0, 0.5, -0.5, 0.0004, -0.0004, 10, 100, 1e11, 0.125, 2.5};
  for (int i = 0; i < 20000; ++i)
    values.push_back(std::pow(10.0, magnitude(random)) * (random() % 2 ? 1 : -1));
  for (int flags = 0; flags < 8; ++flags) {
    for (int decimals = 0; decimals <= 12; ++decimals) {
      const NumberFormat format{decimals, (flags & 1) != 0, (flags & 2) != 0, (flags & 4) != 0,
                                1.0};
      for (const double v : values)
        ASSERT_EQ(format_number(v, format), reference_format(v, format))
            << v << " decimals " << decimals << " flags " << flags;
    }
  }
}

TEST(FormatNumber, ControllerStyles) {
  const NumberFormat fanuc{3, true, false, false, 1.0};
  EXPECT_EQ(format_number(10.0, fanuc), "10.");
  EXPECT_EQ(format_number(-0.5, fanuc), "-.5");
  EXPECT_EQ(format_number(0.0004, fanuc), "0.");
  EXPECT_EQ(format_number(-0.0004, fanuc), "0.");
  EXPECT_EQ(format_number(91.9, fanuc), "91.9");
  const NumberFormat fixed{3, true, true, true, 1.0};
  EXPECT_EQ(format_number(-13.5, fixed), "-13.500");
  const NumberFormat integer{0, false, true, false, 1.0};
  EXPECT_EQ(format_number(720.4, integer), "720");
  EXPECT_EQ(format_number(-0.4, integer), "0");
}

}  // namespace
}  // namespace ncpost::xslt::detail
