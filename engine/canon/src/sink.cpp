#include "ncpost/canon/sink.hpp"

namespace ncpost::canon {
namespace {

bool is_workingstep(const Call& call, bool begin) {
  if (begin) {
    const auto* b = std::get_if<Begin>(&call);
    return b != nullptr && b->scope == Scope::Workingstep;
  }
  const auto* e = std::get_if<End>(&call);
  return e != nullptr && e->scope == Scope::Workingstep;
}

}  // namespace

Chunker::Chunker(ChunkSink& out, ChunkLimits limits) : out_(out), limits_(limits) {
  if (limits_.max_calls == 0) limits_.max_calls = 1;
}

void Chunker::call(const Call& call) {
  if (is_workingstep(call, true) || pending_.size() >= limits_.max_calls) flush();
  pending_.push_back(call);
  if (is_workingstep(call, false)) flush();
}

void Chunker::finish() {
  flush();
}

void Chunker::flush() {
  if (pending_.empty()) return;
  out_.chunk(ChunkView{next_seq_++, pending_});
  // clear() keeps the capacity: the buffer grows to the largest chunk and stays there.
  pending_.clear();
}

}  // namespace ncpost::canon
