// Peer for the reader benchmark: Open CASCADE's STEP reader (STEPControl_Reader::ReadFile),
// which lexes and parses the whole file into its StepData model. Entities it does not know
// (all STEP-NC ones) become undefined entities, which still means a full parse of their
// parameters. Only ReadFile is timed, not any translation to shapes.
//
//   peer_occt_read FILE [RUNS]     MB/s (best and median)
//   peer_occt_read --rss FILE      one read, then peak RSS and its ratio to the file size

#include <IFSelect_ReturnStatus.hxx>
#include <Interface_InterfaceModel.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <STEPControl_Reader.hxx>
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <iostream>
#include <vector>

#include "bench_support.hpp"

namespace {

bool read_once(const char* path, std::size_t& entities) {
  STEPControl_Reader reader;
  const IFSelect_ReturnStatus status = reader.ReadFile(path);
  entities = static_cast<std::size_t>(reader.Model().IsNull() ? 0 : reader.Model()->NbEntities());
  return status == IFSelect_RetDone;
}

}  // namespace

int main(int argc, char** argv) {
  // OCCT reports each unknown entity type; that is not what is being measured.
  Message::DefaultMessenger()->RemovePrinters(STANDARD_TYPE(Message_Printer));
  if (argc >= 3 && std::string(argv[1]) == "--rss") {
    std::size_t entities = 0;
    const bool ok = read_once(argv[2], entities);
    const double mib = static_cast<double>(std::filesystem::file_size(argv[2])) / (1024.0 * 1024.0);
    const double rss_mib = ncpost::bench::peak_rss_mib();
    std::cout << "file_mib=" << mib << " entities=" << entities << " ok=" << ok
              << " peak_rss_mib=" << rss_mib << " rss_over_file=" << rss_mib / mib << '\n';
    return ok ? 0 : 1;
  }
  if (argc < 2) {
    std::cerr << "usage: peer_occt_read FILE [RUNS] | --rss FILE\n";
    return 2;
  }
  const int runs = argc > 2 ? std::stoi(argv[2]) : 3;
  const double mb = static_cast<double>(std::filesystem::file_size(argv[1])) / 1e6;
  std::vector<double> seconds;
  std::size_t entities = 0;
  for (int i = 0; i < runs; ++i) {
    const auto start = std::chrono::steady_clock::now();
    if (!read_once(argv[1], entities)) std::cerr << "ReadFile did not succeed\n";
    seconds.push_back(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  std::sort(seconds.begin(), seconds.end());
  std::cout << "file_mb=" << mb << " entities=" << entities << " runs=" << runs
            << " best_mb_s=" << mb / seconds.front()
            << " median_mb_s=" << mb / seconds[seconds.size() / 2] << '\n';
  return 0;
}
