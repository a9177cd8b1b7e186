#pragma once
// The XML form of the canonical program, which profile stylesheets read. In: chunks of calls
// (sink.hpp). Out: XML text, streamed (no DOM), well-formed whatever the calls hold.
// The grammar is engine/canon/canon.rng (RELAX NG); docs/canon.md explains it.
//
// Each chunk is one standalone element, `<chunk seq="N">...</chunk>`, that an XSLT can
// transform on its own. The whole program is
//     <?xml version="1.0" encoding="UTF-8"?>\n<program format="ncpost-canon" version="1">\n
//     ...the chunks, byte for byte as XmlChunkWriter writes them...
//     </program>\n
// Calls are elements named as in the trace (`<STRAIGHT_FEED x="1" y="2" z="-0.5"/>`), with
// numbers as attributes in the shortest form that reads back to the same double. A
// workingstep is a container, `<workingstep id="10" type="MACHINING_WORKINGSTEP" name="..">`
// holding its calls; program, setup and workplan markers are empty begin/end elements
// (`<WORKPLAN_BEGIN .../>`), because their begin and end lie in different chunks.

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "ncpost/canon/call.hpp"
#include "ncpost/canon/sink.hpp"
#include "ncpost/canon/trace.hpp"

namespace ncpost::canon {

inline constexpr std::string_view kXmlPrologue =
    "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<program format=\"ncpost-canon\" version=\"1\">\n";
inline constexpr std::string_view kXmlEpilogue = "</program>\n";

// A number as the XML form writes it: std::to_chars shortest round-trip form, C locale,
// -0 as "0", NaN and infinities as xsd:double spells them ("NaN", "INF", "-INF").
void append_xml_number(std::string& out, double value);

// The XML form as a stream of events instead of text, for a consumer that builds a document
// tree directly (the renderer does, so that no text is written and parsed again for its
// stylesheet). Attribute values and text are the characters written, not escaped. The text
// target below escapes them; a tree target stores what a parser would read back from that
// text (xmltext::append_characters), so the tree equals the parsed text, whitespace text
// between elements included.
class XmlEvents {
 public:
  virtual ~XmlEvents() = default;
  virtual void start_element(std::string_view name) = 0;
  virtual void attribute(std::string_view name, std::string_view value) = 0;
  virtual void text(std::string_view characters) = 0;
  virtual void end_element(std::string_view name) = 0;
};

// The events as XML text, appended to `out`: an element without children is written
// `<name .../>`. Everything the writer below starts it also finishes within the same call, so
// a short-lived XmlText per call writes the same bytes as one long-lived one.
class XmlText final : public XmlEvents {
 public:
  explicit XmlText(std::string& out) : out_(out) {}
  void start_element(std::string_view name) override;
  void attribute(std::string_view name, std::string_view value) override;
  void text(std::string_view characters) override;
  void end_element(std::string_view name) override;

 private:
  std::string& out_;
  bool start_tag_open_ = false;
};

// Lets a consumer take consecutive motions out of the XML: each maximal sequence of calls it
// takes is written as one `<motions first="F" count="N"/>` element, F being the index take()
// returned for the sequence's first call, and the consumer renders them from its own memory
// (the renderer does, for profiles that ask for it: docs/render.md, "Motion runs").
class MotionRuns {
 public:
  virtual ~MotionRuns() = default;
  // The call's index in the consumer's memory when it joins a run; nothing when it is written
  // as an element.
  virtual std::optional<std::size_t> take(const Call& call) = 0;
};

// Writes chunks one by one. It remembers one thing between chunks: a workingstep split over
// several chunks (ChunkLimits::max_calls) is closed at the end of each and reopened, with
// continued="true", at the start of the next, so every chunk stays well-formed on its own.
//
// The same element can also be written piece by piece, open() + append()... + close(): the
// calls of several consecutive chunks then form one `<chunk>`, byte for byte what
// append_chunk() writes for one chunk holding all of them. The renderer uses this to run one
// transform over a batch of chunks. The writer is a small value: copy it to remember its state
// (the renderer does, to re-render a failed batch chunk by chunk).
//
// Each function writes text to a string, or the same XML as events.
class XmlChunkWriter {
 public:
  // Appends `<chunk seq="N">\n ... </chunk>\n`.
  void append_chunk(std::string& out, const ChunkView& chunk);
  void append_chunk(XmlEvents& out, const ChunkView& chunk, MotionRuns* runs = nullptr);

  // Starts `<chunk seq="N">`; reopens a workingstep left open by the previous chunk.
  void open(std::string& out, std::uint64_t seq);
  void open(XmlEvents& out, std::uint64_t seq);
  // Appends the calls, inside the element that open() started.
  void append(std::string& out, std::span<const Call> calls);
  void append(XmlEvents& out, std::span<const Call> calls, MotionRuns* runs = nullptr);
  // Closes an open workingstep (remembered for the next chunk) and the element.
  void close(std::string& out);
  void close(XmlEvents& out);

 private:
  std::optional<Begin> open_workingstep_;  // its entity and output options
  bool open_here_ = false;                 // a <workingstep> element is open in the current chunk
};

// A ChunkSink that hands the XML text of each chunk to a callback (for rendering chunk by
// chunk). The string_view is valid during the callback only.
class XmlChunkSink final : public ChunkSink {
 public:
  using Callback = std::function<void(std::uint64_t seq, std::string_view xml)>;
  explicit XmlChunkSink(Callback out) : out_(std::move(out)) {}
  void chunk(const ChunkView& chunk) override;

 private:
  Callback out_;
  XmlChunkWriter writer_;
  std::string text_;
};

// A ChunkSink that streams the whole program as one document to `out`: the prologue before
// the first chunk, each chunk as it comes, the epilogue on finish().
class XmlDocumentWriter final : public ChunkSink {
 public:
  explicit XmlDocumentWriter(TextSink out) : out_(std::move(out)) {}
  void chunk(const ChunkView& chunk) override;
  // Writes the epilogue (and the prologue, for a program without chunks). Once only.
  void finish();

 private:
  void start();
  TextSink out_;
  XmlChunkWriter writer_;
  std::string text_;
  bool started_ = false;
  bool finished_ = false;
};

// The whole program as one document, chunked as Chunker cuts it.
[[nodiscard]] std::string to_xml_document(std::span<const Call> calls, ChunkLimits limits = {});

}  // namespace ncpost::canon
