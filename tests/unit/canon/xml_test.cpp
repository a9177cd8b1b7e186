// The XML form: exact elements, numbers, escaping, well-formedness, validity against
// engine/canon/canon.rng, and chunked output equal to the whole document.

#include "ncpost/canon/xml.hpp"

#include <gtest/gtest.h>

#include <charconv>
#include <cmath>
#include <limits>

#include "canon_support.hpp"

namespace ncpost::canon {
namespace {

using test::entity;
using test::rng_errors;
using test::well_formed;

std::string xml_number(double v) {
  std::string s;
  append_xml_number(s, v);
  return s;
}

// The XML of one chunk holding `calls`, written by a fresh writer.
std::string chunk_xml(std::vector<Call> calls, std::uint64_t seq = 0) {
  std::string out;
  XmlChunkWriter writer;
  writer.append_chunk(out, ChunkView{seq, calls});
  return out;
}

// Each chunk's XML as XmlChunkSink hands it on.
std::vector<std::string> chunk_texts(const std::vector<Call>& calls, ChunkLimits limits = {}) {
  std::vector<std::string> texts;
  XmlChunkSink sink([&texts](std::uint64_t seq, std::string_view xml) {
    EXPECT_EQ(seq, texts.size());
    texts.emplace_back(xml);
  });
  Chunker chunker(sink, limits);
  for (const auto& c : calls) chunker.call(c);
  chunker.finish();
  return texts;
}

TEST(CanonXml, Numbers) {
  EXPECT_EQ(xml_number(0), "0");
  EXPECT_EQ(xml_number(-0.0), "0");
  EXPECT_EQ(xml_number(1), "1");
  EXPECT_EQ(xml_number(-13.5), "-13.5");
  EXPECT_EQ(xml_number(0.1), "0.1");
  EXPECT_EQ(xml_number(1e21), "1e+21");
  EXPECT_EQ(xml_number(std::numeric_limits<double>::quiet_NaN()), "NaN");
  EXPECT_EQ(xml_number(std::numeric_limits<double>::infinity()), "INF");
  EXPECT_EQ(xml_number(-std::numeric_limits<double>::infinity()), "-INF");
  // Shortest form that reads back to the same double.
  for (const double v :
       {1.0 / 3.0, 91.9, 2.5e-7, -123456.789012345678, 0.30000000000000004,
        std::numeric_limits<double>::max(), std::numeric_limits<double>::denorm_min()}) {
    const std::string s = xml_number(v);
    double back = 0;
    const auto r = std::from_chars(s.data(), s.data() + s.size(), back);
    ASSERT_EQ(r.ec, std::errc()) << s;
    EXPECT_EQ(back, v) << s;
  }
  EXPECT_EQ(xml_number(1.0 / 3.0), "0.3333333333333333");
}

TEST(CanonXml, ExactElements) {
  const std::string xml = chunk_xml(
      {
          UseLengthUnits{Units::Inches},
          SetOriginOffsets{{0, 0, -14.7}, Rotary{0, 0, 90}},
          SetFeedReference{FeedReference::Workpiece},
          SelectPlane{Plane::Xz},
          StraightTraverse{{1, -0.0, 0.1, {}, {}}},
          StraightFeed{{1, 2, 3, Rotary{10, 20, 30}, Direction{0, 0, 1}}},
          ArcFeed{{20, 2, 3, {}, {}}, {15, 2, 3}, {0, 0, 1}, -1},
          ArcFeed{{1, 1, 1, {}, {}}, {0, 0, 0}, {0, 1, 1}, 2},
          SetFeedRate{250},
          SetSpindleSpeed{1200},
          SelectTool{3},
          ChangeTool{3},
          UseToolLengthOffset{12.5},
          Dwell{0.5},
          StartSpindleClockwise{},
          Comment{"a < b & \"c\""},
          Message{"m"},
          Begin{Scope::Workplan, entity(3, "WORKPLAN", "main")},
          End{Scope::Project, entity(0, "", "")},
      },
      7);
  EXPECT_EQ(xml,
            "<chunk seq=\"7\">\n"
            "  <USE_LENGTH_UNITS units=\"inch\"/>\n"
            "  <SET_ORIGIN_OFFSETS x=\"0\" y=\"0\" z=\"-14.7\" a=\"0\" b=\"0\" c=\"90\"/>\n"
            "  <SET_FEED_REFERENCE reference=\"workpiece\"/>\n"
            "  <SELECT_PLANE plane=\"xz\"/>\n"
            "  <STRAIGHT_TRAVERSE x=\"1\" y=\"0\" z=\"0.1\"/>\n"
            "  <STRAIGHT_FEED x=\"1\" y=\"2\" z=\"3\" a=\"10\" b=\"20\" c=\"30\" i=\"0\" j=\"0\" "
            "k=\"1\"/>\n"
            "  <ARC_FEED x=\"20\" y=\"2\" z=\"3\" cx=\"15\" cy=\"2\" cz=\"3\" ni=\"0\" nj=\"0\" "
            "nk=\"1\" turns=\"-1\" plane=\"xy\" first_end=\"20\" second_end=\"2\" "
            "first_axis=\"15\" second_axis=\"2\" rotation=\"-1\" axis_end_point=\"3\"/>\n"
            "  <ARC_FEED x=\"1\" y=\"1\" z=\"1\" cx=\"0\" cy=\"0\" cz=\"0\" ni=\"0\" nj=\"1\" "
            "nk=\"1\" turns=\"2\"/>\n"
            "  <SET_FEED_RATE rate=\"250\"/>\n"
            "  <SET_SPINDLE_SPEED rpm=\"1200\"/>\n"
            "  <SELECT_TOOL slot=\"3\"/>\n"
            "  <CHANGE_TOOL slot=\"3\"/>\n"
            "  <USE_TOOL_LENGTH_OFFSET length=\"12.5\"/>\n"
            "  <DWELL seconds=\"0.5\"/>\n"
            "  <START_SPINDLE_CLOCKWISE/>\n"
            "  <COMMENT>a &lt; b &amp; \"c\"</COMMENT>\n"
            "  <MESSAGE>m</MESSAGE>\n"
            "  <WORKPLAN_BEGIN id=\"3\" type=\"WORKPLAN\" name=\"main\"/>\n"
            "  <PROJECT_END name=\"\"/>\n"
            "</chunk>\n");
  EXPECT_EQ(rng_errors(xml), "");
}

TEST(CanonXml, NurbsAndCycles) {
  Cycle tap{.kind = CycleKind::Tap,
            .x = 1,
            .y = 2,
            .safe_z = 10,
            .r_z = 2,
            .bottom_z = -8,
            .feed = 500,
            .pitch = 1.25,
            .spindle_speed = 400};
  Cycle peck{.kind = CycleKind::PeckDrill,
             .x = 1,
             .y = 2,
             .safe_z = 10,
             .r_z = 2,
             .bottom_z = -8,
             .feed = 80,
             .dwell = 0.25,
             .peck = 3,
             .peck_clearance = 0.5};
  Cycle bore{
      .kind = CycleKind::Bore, .x = 1, .y = 2, .safe_z = 10, .r_z = 2, .bottom_z = -8, .feed = 60};
  const std::string xml = chunk_xml({
      NurbsFeed{.degree = 1,
                .points = {{0, 0, 0, 1}, {1, 0, 0, 1}},
                .knots = {0, 0, 1, 1},
                .rotary = {},
                .tool_axis = Direction{0, 0, 1}},
      tap,
      peck,
      bore,
  });
  EXPECT_EQ(xml,
            "<chunk seq=\"0\">\n"
            "  <NURBS_FEED degree=\"1\" i=\"0\" j=\"0\" k=\"1\">\n"
            "    <point x=\"0\" y=\"0\" z=\"0\" w=\"1\"/>\n"
            "    <point x=\"1\" y=\"0\" z=\"0\" w=\"1\"/>\n"
            "    <knot value=\"0\"/>\n"
            "    <knot value=\"0\"/>\n"
            "    <knot value=\"1\"/>\n"
            "    <knot value=\"1\"/>\n"
            "  </NURBS_FEED>\n"
            "  <TAP_CYCLE x=\"1\" y=\"2\" safe_z=\"10\" r_z=\"2\" bottom_z=\"-8\" feed=\"500\" "
            "dwell=\"0\" pitch=\"1.25\" spindle_speed=\"400\" hand=\"right\"/>\n"
            "  <PECK_DRILL_CYCLE x=\"1\" y=\"2\" safe_z=\"10\" r_z=\"2\" bottom_z=\"-8\" "
            "feed=\"80\" dwell=\"0.25\" peck=\"3\" peck_retract=\"0\" peck_clearance=\"0.5\"/>\n"
            "  <BORE_CYCLE x=\"1\" y=\"2\" safe_z=\"10\" r_z=\"2\" bottom_z=\"-8\" feed=\"60\" "
            "dwell=\"0\" spindle_stop=\"false\"/>\n"
            "</chunk>\n");
  EXPECT_EQ(rng_errors(xml), "");
}

TEST(CanonXml, WorkingstepIsAContainer) {
  const Entity ws = entity(10, "MACHINING_WORKINGSTEP", "WS \"1\" <face>");
  const std::string xml = chunk_xml({
      Begin{Scope::Workingstep, ws},
      StraightFeed{{1, 2, 3, {}, {}}},
      End{Scope::Workingstep, ws},
  });
  EXPECT_EQ(xml,
            "<chunk seq=\"0\">\n"
            "  <workingstep id=\"10\" type=\"MACHINING_WORKINGSTEP\" "
            "name=\"WS &quot;1&quot; &lt;face&gt;\">\n"
            "    <STRAIGHT_FEED x=\"1\" y=\"2\" z=\"3\"/>\n"
            "  </workingstep>\n"
            "</chunk>\n");
  EXPECT_EQ(rng_errors(xml), "");
}

TEST(CanonXml, UnmatchedWorkingstepMarkersStayWellFormed) {
  const Entity a = entity(10, "MACHINING_WORKINGSTEP", "a");
  const Entity b = entity(11, "MACHINING_WORKINGSTEP", "b");
  // An end without a begin, then a begin while one is open, then a chunk that ends open.
  const std::string xml = chunk_xml({
      End{Scope::Workingstep, a},
      Begin{Scope::Workingstep, a},
      Begin{Scope::Workingstep, b},
      FloodOn{},
  });
  EXPECT_EQ(xml,
            "<chunk seq=\"0\">\n"
            "  <WORKINGSTEP_END id=\"10\" type=\"MACHINING_WORKINGSTEP\" name=\"a\"/>\n"
            "  <workingstep id=\"10\" type=\"MACHINING_WORKINGSTEP\" name=\"a\">\n"
            "  </workingstep>\n"
            "  <workingstep id=\"11\" type=\"MACHINING_WORKINGSTEP\" name=\"b\">\n"
            "    <FLOOD_ON/>\n"
            "  </workingstep>\n"
            "</chunk>\n");
  EXPECT_EQ(rng_errors(xml), "");
}

TEST(CanonXml, HostileStringsStayWellFormed) {
  constexpr char kNasty[] = "]]> </chunk> <!-- \x01\x02 \xFF\xFE & &amp; \r\n\t \xC0\xAF \0 end";
  const std::string nasty(kNasty, sizeof kNasty - 1);
  const std::vector<Call> calls = {
      Begin{Scope::Project, entity(1, nasty, nasty)},
      Comment{nasty},
      Message{nasty},
      Begin{Scope::Workingstep, entity(2, nasty, nasty)},
      End{Scope::Workingstep, entity(2, nasty, nasty)},
      End{Scope::Project, entity(1, nasty, nasty)},
  };
  const std::string doc = to_xml_document(calls);
  EXPECT_TRUE(well_formed(doc)) << doc;
  EXPECT_EQ(rng_errors(doc), "");
  for (const auto& chunk : chunk_texts(calls)) EXPECT_TRUE(well_formed(chunk)) << chunk;
}

TEST(CanonXml, SampleProgramIsValid) {
  const std::string doc = to_xml_document(test::sample_program());
  EXPECT_TRUE(well_formed(doc));
  EXPECT_EQ(rng_errors(doc), "") << doc;
  EXPECT_EQ(doc.rfind(kXmlPrologue, 0), 0u);
}

TEST(CanonXml, EmptyProgram) {
  const std::string doc = to_xml_document({});
  EXPECT_EQ(doc, std::string(kXmlPrologue) + std::string(kXmlEpilogue));
  EXPECT_EQ(rng_errors(doc), "");
}

TEST(CanonXml, SchemaRejectsWhatTheWriterNeverWrites) {
  // The validation is real: these must fail.
  EXPECT_NE(rng_errors("<chunk seq=\"0\"><STRAIGHT_FEED x=\"1\" y=\"2\"/></chunk>"), "");
  EXPECT_NE(rng_errors("<chunk seq=\"0\"><STRAIGHT_FEED x=\"1\" y=\"2\" z=\"abc\"/></chunk>"), "");
  EXPECT_NE(rng_errors("<chunk seq=\"0\"><FLY_TO_MOON/></chunk>"), "");
  EXPECT_NE(rng_errors("<chunk seq=\"0\"><workingstep name=\"a\"><workingstep name=\"b\"/>"
                       "</workingstep></chunk>"),
            "");
  EXPECT_NE(rng_errors("<chunk seq=\"-1\"/>"), "");
  EXPECT_NE(rng_errors("<program format=\"ncpost-canon\" version=\"2\"/>"), "");
  EXPECT_NE(rng_errors("<chunk seq=\"0\"><STRAIGHT_FEED x=\"1\" y=\"2\" z=\"3\" a=\"1\"/></chunk>"),
            "");
}

TEST(CanonXml, ChunkedEqualsWholeByteForByte) {
  const auto calls = test::sample_program();
  for (const std::size_t max_calls :
       {std::size_t{65536}, std::size_t{1}, std::size_t{3}, std::size_t{7}}) {
    SCOPED_TRACE(max_calls);
    const ChunkLimits limits{max_calls};
    const auto chunks = chunk_texts(calls, limits);
    std::string joined(kXmlPrologue);
    for (const auto& chunk : chunks) {
      joined += chunk;
      EXPECT_TRUE(well_formed(chunk)) << chunk;
      EXPECT_EQ(rng_errors(chunk), "") << chunk;
    }
    joined += kXmlEpilogue;
    const std::string whole = to_xml_document(calls, limits);
    EXPECT_EQ(joined, whole);
    EXPECT_EQ(rng_errors(whole), "");

    // Streaming the document through XmlDocumentWriter gives the same bytes.
    std::string streamed;
    XmlDocumentWriter document([&streamed](std::string_view t) { streamed += t; });
    Chunker chunker(document, limits);
    for (const auto& c : calls) chunker.call(c);
    chunker.finish();
    document.finish();
    document.finish();  // once only
    EXPECT_EQ(streamed, whole);
  }
}

TEST(CanonXml, SplitWorkingstepIsReopenedAsContinued) {
  const Entity ws = entity(10, "MACHINING_WORKINGSTEP", "long");
  std::vector<Call> calls = {Begin{Scope::Workingstep, ws}};
  for (int n = 0; n < 4; ++n) calls.push_back(StraightFeed{{double(n), 0, 0, {}, {}}});
  calls.push_back(End{Scope::Workingstep, ws});
  const auto chunks = chunk_texts(calls, ChunkLimits{3});
  ASSERT_EQ(chunks.size(), 2u);
  EXPECT_EQ(chunks[0],
            "<chunk seq=\"0\">\n"
            "  <workingstep id=\"10\" type=\"MACHINING_WORKINGSTEP\" name=\"long\">\n"
            "    <STRAIGHT_FEED x=\"0\" y=\"0\" z=\"0\"/>\n"
            "    <STRAIGHT_FEED x=\"1\" y=\"0\" z=\"0\"/>\n"
            "  </workingstep>\n"
            "</chunk>\n");
  EXPECT_EQ(chunks[1],
            "<chunk seq=\"1\">\n"
            "  <workingstep id=\"10\" type=\"MACHINING_WORKINGSTEP\" name=\"long\" "
            "continued=\"true\">\n"
            "    <STRAIGHT_FEED x=\"2\" y=\"0\" z=\"0\"/>\n"
            "    <STRAIGHT_FEED x=\"3\" y=\"0\" z=\"0\"/>\n"
            "  </workingstep>\n"
            "</chunk>\n");
}

// The output options of a workingstep (canon/output_options.hpp) are attributes of its element,
// in the first chunk and in every continued one, and the grammar accepts them.
TEST(CanonXml, OutputOptionsAreWorkingstepAttributes) {
  const Entity ws = entity(7, "CL_OPERATION", "ROUGH_NONUM");
  OutputOptions options;
  ASSERT_EQ(set_output_option(options, "block_numbers", "off"), "");
  ASSERT_EQ(set_output_option(options, "subprogram", "on"), "");
  std::vector<Call> calls = {Begin{Scope::Workingstep, ws, options}};
  for (int n = 0; n < 4; ++n) calls.push_back(StraightFeed{{double(n), 0, 0, {}, {}}});
  calls.push_back(End{Scope::Workingstep, ws});
  const auto chunks = chunk_texts(calls, ChunkLimits{3});
  ASSERT_EQ(chunks.size(), 2u);
  EXPECT_NE(chunks[0].find("<workingstep id=\"7\" type=\"CL_OPERATION\" name=\"ROUGH_NONUM\" "
                           "block_numbers=\"off\" subprogram=\"on\">"),
            std::string::npos)
      << chunks[0];
  EXPECT_NE(chunks[1].find("name=\"ROUGH_NONUM\" continued=\"true\" block_numbers=\"off\" "
                           "subprogram=\"on\">"),
            std::string::npos)
      << chunks[1];
  for (const auto& chunk : chunks) EXPECT_EQ(rng_errors(chunk), "") << chunk;
  EXPECT_NE(rng_errors("<chunk seq=\"0\"><workingstep name=\"w\" block_numbers=\"maybe\"/>"
                       "</chunk>"),
            "");
  // Only what is set is written.
  const auto plain =
      chunk_texts({Begin{Scope::Workingstep, ws}, End{Scope::Workingstep, ws}}, ChunkLimits{3});
  EXPECT_EQ(plain.front().find("block_numbers"), std::string::npos);
}

}  // namespace
}  // namespace ncpost::canon
