#pragma once
// Model → ISO 10303-21 text. Literals that came from a P21 file are written as they were read
// (they are already valid P21), so reading, writing and reading again gives an equal model.
// Output goes to a sink in pieces of bounded size, so a large model streams without a second
// copy in memory.

#include <functional>
#include <string>
#include <string_view>

#include "ncpost/p21/model.hpp"

namespace ncpost::p21 {

using TextSink = std::function<void(std::string_view)>;

void write(const Model& model, const TextSink& sink);
[[nodiscard]] std::string write_to_string(const Model& model);

// Appends one value in P21 syntax (used by the writer, and by tools that print values).
void append_value(const Model& model, Value value, std::string& out);

}  // namespace ncpost::p21
