#pragma once
// Message building without `"literal" + std::string(...)` chains: besides allocating at every
// step, those trip GCC 12's -Wrestrict false positive (GCC bug 105651) under -Werror.

#include <string>
#include <string_view>

namespace ncpost::express::detail {

template <typename... Parts>
[[nodiscard]] std::string cat(const Parts&... parts) {
  std::string out;
  out.reserve((std::string_view(parts).size() + ... + 0));
  (out.append(std::string_view(parts)), ...);
  return out;
}

}  // namespace ncpost::express::detail
