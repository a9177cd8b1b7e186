// detail::Line, the normalised line the block reader works on: a copy (the interpreter's line
// cache hands lines on by copying) owns its text, whichever form the text has.

#include "lexer.hpp"

#include <gtest/gtest.h>

#include <cctype>
#include <string>

#include "gcode_support.hpp"

namespace ncpost::gcode::detail {
namespace {

// Whether `view` lies inside `owner`'s characters.
bool inside(std::string_view view, const std::string& owner) {
  return view.data() >= owner.data() && view.data() + view.size() <= owner.data() + owner.size();
}

TEST(GcodeLine, ACopyOfANormalisedLineViewsItsOwnBuffer) {
  const Lexing lexing(*test::dialect("linuxcnc"));
  Line line;
  normalise("g1 x1 (cut) y2", lexing, line);
  line.number = 7;
  ASSERT_FALSE(line.text_is_raw);
  const std::string text(line.text);
  const Line copy(line);
  Line assigned;
  assigned = line;
  // The original goes on to another line, as the interpreter's lines do.
  normalise("g0 z50 (retract) x0 y0 (home)", lexing, line);
  for (const Line* l : {&copy, static_cast<const Line*>(&assigned)}) {
    EXPECT_EQ(l->text, text);
    EXPECT_TRUE(inside(l->text, l->buffer));
    EXPECT_EQ(l->number, 7u);
    EXPECT_EQ(l->raw, "g1 x1 (cut) y2");
    ASSERT_EQ(l->comments.size(), 1u);
    EXPECT_EQ(l->comments[0].text, "cut");
    // Every column still names the original line's character.
    for (std::size_t i = 0; i < l->text.size(); ++i)
      EXPECT_EQ(std::toupper(static_cast<unsigned char>(l->raw[l->column(i) - 1])), l->text[i])
          << i;
  }
}

TEST(GcodeLine, ACopyOfAPlainLineViewsTheSameSource) {
  const Lexing lexing(*test::dialect("linuxcnc"));
  const std::string source = "G1 X1 Y2";
  Line line;
  normalise(source, lexing, line);
  ASSERT_TRUE(line.text_is_raw);
  Line copy;
  copy = line;
  normalise("g0 z50", lexing, line);
  EXPECT_TRUE(copy.text_is_raw);
  EXPECT_EQ(copy.text, source);
  EXPECT_TRUE(inside(copy.text, source));
}

}  // namespace
}  // namespace ncpost::gcode::detail
