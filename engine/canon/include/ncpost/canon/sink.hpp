#pragma once
// Where canonical calls go. In: calls, one at a time, from an interpreter. Out: whatever the
// sink does with them — record them (ProgramBuffer), cut them into chunks for rendering
// (Chunker → ChunkSink), print them (TraceWriter in trace.hpp).
//
// One virtual `call(const Call&)` rather than one virtual per canonical function: adapters
// (buffer, chunker, tee, filters) are then a few lines each instead of forty overrides, and a
// sink that must understand every call does so with std::visit, where a forgotten case fails
// to compile. The cost — one variant construction per call — is small next to rendering.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "ncpost/canon/call.hpp"

namespace ncpost::canon {

class Sink {
 public:
  Sink() = default;
  Sink(const Sink&) = delete;
  Sink& operator=(const Sink&) = delete;
  virtual ~Sink() = default;

  virtual void call(const Call& call) = 0;
};

// Records every call (tests, small programs, the `trace` of a whole program).
class ProgramBuffer final : public Sink {
 public:
  void call(const Call& call) override { calls_.push_back(call); }

  [[nodiscard]] const std::vector<Call>& calls() const noexcept { return calls_; }
  [[nodiscard]] std::vector<Call> take() && { return std::move(calls_); }
  void clear() noexcept { calls_.clear(); }

 private:
  std::vector<Call> calls_;
};

// ---- Chunks ---------------------------------------------------------------------------------

// One complete chunk. `calls` is valid only during ChunkSink::chunk (the chunker reuses its
// storage, which is what bounds memory by the largest chunk).
struct ChunkView {
  std::uint64_t seq = 0;  // 0, 1, 2, ... in program order
  std::span<const Call> calls;
};

class ChunkSink {
 public:
  ChunkSink() = default;
  ChunkSink(const ChunkSink&) = delete;
  ChunkSink& operator=(const ChunkSink&) = delete;
  virtual ~ChunkSink() = default;

  virtual void chunk(const ChunkView& chunk) = 0;
};

struct ChunkLimits {
  // A chunk never holds more calls than this: a longer workingstep (a dense explicit
  // toolpath) is split into several chunks, the later ones marked as continuations in the
  // XML form. At about 200 bytes a call, the default bounds a chunk near 13 MB.
  std::size_t max_calls = 65536;
};

// Cuts the call stream into chunks and hands each to `out` as soon as it is complete:
// - before WORKINGSTEP_BEGIN, the calls gathered so far (if any) form a chunk;
// - after WORKINGSTEP_END, the calls gathered so far (the workingstep) form a chunk;
// - a chunk that reaches ChunkLimits::max_calls is handed on at once;
// - finish() hands on whatever is left.
// A program therefore comes as: a start chunk (PROJECT_BEGIN, set-up, SETUP_BEGIN,
// WORKPLAN_BEGIN, ... up to the first workingstep), one chunk per workingstep, a chunk for
// whatever stands between two workingsteps (NC functions, nested workplan markers) when
// something does, and an end chunk (WORKPLAN_END, ..., PROGRAM_END, PROJECT_END).
class Chunker final : public Sink {
 public:
  explicit Chunker(ChunkSink& out, ChunkLimits limits = {});

  void call(const Call& call) override;
  // Hands on the last chunk. Further calls start a new chunk; finish() again flushes it.
  void finish();

  [[nodiscard]] std::uint64_t chunks_emitted() const noexcept { return next_seq_; }

 private:
  void flush();

  ChunkSink& out_;
  ChunkLimits limits_;
  std::vector<Call> pending_;
  std::uint64_t next_seq_ = 0;
};

// Collects chunks as vectors (tests, and callers that want them all).
class ChunkBuffer final : public ChunkSink {
 public:
  void chunk(const ChunkView& chunk) override {
    chunks_.emplace_back(chunk.calls.begin(), chunk.calls.end());
  }
  [[nodiscard]] const std::vector<std::vector<Call>>& chunks() const noexcept { return chunks_; }

 private:
  std::vector<std::vector<Call>> chunks_;
};

}  // namespace ncpost::canon
