#pragma once
// Each `ncpost` verb is one function in its own file. A verb wires engine stages together; it
// holds no domain logic. Exit codes: 0 ok, 1 input rejected (diagnostics on stderr), 2 usage.

#include <span>
#include <string_view>

namespace ncpost::cli {

inline constexpr int kExitOk = 0;
inline constexpr int kExitRejected = 1;
inline constexpr int kExitUsage = 2;

using Args = std::span<const std::string_view>;

int run_inspect(Args args);
int run_convert(Args args);
int run_schema(Args args);
int run_trace(Args args);
int run_post(Args args);
int run_profiles(Args args);
int run_verify(Args args);
int run_nc(Args args);

}  // namespace ncpost::cli
