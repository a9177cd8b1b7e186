// Chunking: where the boundaries fall, the size limit, bounded storage, and traces written
// chunk by chunk.

#include <gtest/gtest.h>

#include "canon_support.hpp"
#include "ncpost/canon/sink.hpp"
#include "ncpost/canon/trace.hpp"

namespace ncpost::canon {
namespace {

std::vector<std::string> names(const std::vector<Call>& calls) {
  std::vector<std::string> out;
  for (const auto& c : calls) out.emplace_back(name(c));
  return out;
}

std::vector<std::vector<Call>> chunk(const std::vector<Call>& calls, ChunkLimits limits = {}) {
  ChunkBuffer buffer;
  Chunker chunker(buffer, limits);
  for (const auto& c : calls) chunker.call(c);
  chunker.finish();
  return buffer.chunks();
}

TEST(CanonChunks, StartWorkingstepsBetweenAndEnd) {
  const auto chunks = chunk(test::sample_program());
  ASSERT_EQ(chunks.size(), 5u);
  EXPECT_EQ(names(chunks[0]),
            (std::vector<std::string>{"PROJECT_BEGIN", "USE_LENGTH_UNITS", "SET_ORIGIN_OFFSETS",
                                      "SET_FEED_REFERENCE", "SELECT_PLANE", "SETUP_BEGIN",
                                      "WORKPLAN_BEGIN"}));
  EXPECT_EQ(names(chunks[1]).front(), "WORKINGSTEP_BEGIN");
  EXPECT_EQ(names(chunks[1]).back(), "WORKINGSTEP_END");
  EXPECT_EQ(names(chunks[2]), (std::vector<std::string>{"COMMENT", "OPTIONAL_PROGRAM_STOP"}));
  EXPECT_EQ(names(chunks[3]).front(), "WORKINGSTEP_BEGIN");
  EXPECT_EQ(names(chunks[3]).back(), "WORKINGSTEP_END");
  EXPECT_EQ(names(chunks[4]),
            (std::vector<std::string>{"WORKPLAN_END", "SETUP_END", "PROGRAM_END", "PROJECT_END"}));
  // Nothing lost, nothing reordered.
  std::vector<Call> joined;
  for (const auto& c : chunks) joined.insert(joined.end(), c.begin(), c.end());
  EXPECT_EQ(joined, test::sample_program());
}

TEST(CanonChunks, EachChunkArrivesAsSoonAsItIsComplete) {
  struct Recorder final : ChunkSink {
    std::vector<std::uint64_t> seqs;
    void chunk(const ChunkView& c) override { seqs.push_back(c.seq); }
  } recorder;
  Chunker chunker(recorder);
  const Entity ws{10, "MACHINING_WORKINGSTEP", "a"};
  chunker.call(Begin{Scope::Project, {1, "PROJECT", "p"}});
  EXPECT_TRUE(recorder.seqs.empty());
  chunker.call(Begin{Scope::Workingstep, ws});
  EXPECT_EQ(recorder.seqs, (std::vector<std::uint64_t>{0}));  // the start chunk
  chunker.call(StraightFeed{});
  chunker.call(End{Scope::Workingstep, ws});
  EXPECT_EQ(recorder.seqs, (std::vector<std::uint64_t>{0, 1}));  // the workingstep
  chunker.call(End{Scope::Project, {1, "PROJECT", "p"}});
  EXPECT_EQ(recorder.seqs.size(), 2u);
  chunker.finish();
  EXPECT_EQ(recorder.seqs, (std::vector<std::uint64_t>{0, 1, 2}));
  chunker.finish();  // nothing pending: no empty chunk
  EXPECT_EQ(chunker.chunks_emitted(), 3u);
}

TEST(CanonChunks, SizeLimitSplitsLongWorkingsteps) {
  const Entity ws{10, "MACHINING_WORKINGSTEP", "a"};
  std::vector<Call> calls = {Begin{Scope::Workingstep, ws}};
  for (int n = 0; n < 10; ++n) calls.push_back(StraightFeed{{double(n), 0, 0, {}, {}}});
  calls.push_back(End{Scope::Workingstep, ws});
  const auto chunks = chunk(calls, ChunkLimits{4});
  ASSERT_EQ(chunks.size(), 3u);
  EXPECT_EQ(chunks[0].size(), 4u);
  EXPECT_EQ(chunks[1].size(), 4u);
  EXPECT_EQ(chunks[2].size(), 4u);
  for (const auto& c : chunks) EXPECT_LE(c.size(), 4u);
  // A limit of 0 would never make progress; it behaves as 1.
  EXPECT_EQ(chunk(calls, ChunkLimits{0}).size(), calls.size());
}

TEST(CanonChunks, EmptyProgramHasNoChunks) {
  EXPECT_TRUE(chunk({}).empty());
}

TEST(CanonChunks, TraceChunkByChunkEqualsWholeTrace) {
  const auto calls = test::sample_program();
  std::string chunked;
  TraceWriter writer([&chunked](std::string_view line) { chunked += line; });
  for (const auto& c : chunk(calls, ChunkLimits{5})) writer.write(c);
  EXPECT_EQ(chunked, trace(calls));
}

TEST(CanonChunks, ProgramBufferRecords) {
  ProgramBuffer buffer;
  Sink& sink = buffer;
  sink.call(FloodOn{});
  sink.call(Comment{"x"});
  EXPECT_EQ(buffer.calls(), (std::vector<Call>{FloodOn{}, Comment{"x"}}));
  auto taken = std::move(buffer).take();
  EXPECT_EQ(taken.size(), 2u);
}

}  // namespace
}  // namespace ncpost::canon
