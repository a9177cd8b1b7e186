#pragma once
// ISO 10303-21 read while the file is still arriving (a large HTTP upload).
//
// In:  the file's size up front, then its bytes in order (append), from one producer thread.
// Out: finish() gives exactly what p21::read() gives for the whole text: the same model and the
//      same diagnostics, whatever the pieces were.
//
// Between appends, read_more() — on another thread if the caller wants — reads every instance
// that lies wholly in what has arrived, so that when the last byte comes only the rest and the
// reference resolution are left. Reading stops only just after a ';' outside any literal or
// comment (detail::CutFinder). Any diagnostic before the end makes the stream reader give up
// (diagnostics need the whole text for their line numbers, and a malformed file can mislead
// the cut): finish() then reads the whole text again with p21::read(). So a clean file is read
// once, while it arrives, and a broken one is read the ordinary way.
//
// Threads: append() may run on one thread while read_more() runs on another, provided the
// `available` bytes handed to read_more() were appended before (the caller orders the two, for
// example through a mutex). Everything else is called by one thread at a time.

#include <cstddef>
#include <memory>
#include <string>
#include <string_view>

#include "ncpost/p21/reader.hpp"

namespace ncpost::p21 {

class StreamReader {
 public:
  explicit StreamReader(std::size_t size, const ReadOptions& options = {});
  ~StreamReader();
  StreamReader(const StreamReader&) = delete;
  StreamReader& operator=(const StreamReader&) = delete;

  [[nodiscard]] std::size_t size() const;
  // Producer: the next bytes. False, and nothing stored, when they would exceed size().
  bool append(std::string_view bytes);
  // Producer: how many bytes have been appended.
  [[nodiscard]] std::size_t appended() const;

  // Consumer: reads the complete instances among the first `available` bytes.
  void read_more(std::size_t available);
  // Consumer: the first `available` bytes, as appended (for sniffing the format).
  [[nodiscard]] std::string_view arrived(std::size_t available) const;
  // How far reading has got, in bytes of text; 0 once it gave up.
  [[nodiscard]] std::size_t read_through() const;
  [[nodiscard]] bool gave_up() const;

  // Once every byte has been appended and no read_more() runs: the rest is read and the
  // references resolved. Call once.
  [[nodiscard]] ReadResult finish();
  // The text instead of a result (an upload that is not P21 after all). Call once, instead
  // of finish().
  [[nodiscard]] std::string take_text();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace ncpost::p21
