// Runs a libFuzzer target over files without libFuzzer, so that every build (and ctest) checks
// the target on its seed corpus. Usage: <target>_replay FILE|DIR...

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace {

int run_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  const std::string s = bytes.str();
  LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(s.data()), s.size());
  return 1;
}

}  // namespace

int main(int argc, char** argv) {
  int files = 0;
  for (int i = 1; i < argc; ++i) {
    const std::filesystem::path arg(argv[i]);
    if (std::filesystem::is_directory(arg)) {
      for (const auto& entry : std::filesystem::recursive_directory_iterator(arg))
        if (entry.is_regular_file()) files += run_file(entry.path());
    } else if (std::filesystem::exists(arg)) {
      files += run_file(arg);
    }
  }
  std::cout << "replayed " << files << " inputs without a crash\n";
  return files > 0 ? 0 : 1;
}
