// Writes a generated NX CLSF file of about SIZE_MB megabytes for the CL reader's benchmark
// (bench/cls_read_bench.cpp): operations with a tool each, a rapid approach, a feed, then
// zig-zag passes of GOTO/ lines with a CIRCLE/ turn at each end, PAINT/ records, END-OF-PATH.
// Numbers are written as NX writes them (4 decimals, axes with 7). Usage: make_large_cl SIZE_MB OUT

#include <cstdio>
#include <cstdlib>
#include <string>

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: make_large_cl SIZE_MB OUT\n");
    return 2;
  }
  const double target = std::atof(argv[1]) * 1024 * 1024;
  std::FILE* out = std::fopen(argv[2], "wb");
  if (!out) {
    std::perror(argv[2]);
    return 1;
  }
  std::string block;
  double written = 0;
  int operation = 0;
  std::fputs("UNITS/MM\n", out);
  while (written < target) {
    ++operation;
    block.clear();
    char line[1024];
    std::snprintf(
        line, sizeof line,
        "TOOL PATH/ZLEVEL_%d,TOOL,T%d-D10-CR1\nTLDATA/MILL,10.0000,1.0000,75.0000,0.0000,"
        "0.0000\nMSYS/0.0000,0.0000,0.0000,1.0000000,0.0000000,0.0000000,0.0000000,1."
        "0000000,0.0000000\n$$ centerline data\nSPINDL/RPM,6000,CLW\nPAINT/PATH\nRAPID\n"
        "GOTO/0.0000,0.0000,50.0000,0.0000000,0.0000000,1.0000000\nFEDRAT/MMPM,1200.0000\n",
        operation, 1 + operation % 20);
    block += line;
    for (int pass = 0; pass < 200; ++pass) {
      const double y = pass * 2.0;
      const double z = -0.5 * (operation % 40);
      for (int i = 0; i <= 100; ++i) {
        const double x = (pass % 2 == 0) ? i * 1.5 : 150.0 - i * 1.5;
        std::snprintf(line, sizeof line, "GOTO/%.4f,%.4f,%.4f\n", x, y + 0.0001 * i, z);
        block += line;
      }
      // A half circle of radius 1 to the next pass.
      const double x_end = (pass % 2 == 0) ? 150.0 : 0.0;
      const double nz = (pass % 2 == 0) ? -1.0 : 1.0;  // counter-clockwise, then clockwise
      std::snprintf(line, sizeof line,
                    "CIRCLE/%.4f,%.4f,%.4f,0.0000000,0.0000000,%.7f,1.0000,0.0100,0.5000,10.0000,"
                    "1.0000\nGOTO/%.4f,%.4f,%.4f\nPAINT/COLOR,31\n",
                    x_end, y + 0.0100 + 1.0, z, nz, x_end, y + 2.0100, z);
      // The last pass point is (x_end, y + 0.01): the circle's centre is 1 above it in Y.
      block += line;
    }
    block += "RAPID\nGOTO/0.0000,0.0000,50.0000\nEND-OF-PATH\n";
    std::fwrite(block.data(), 1, block.size(), out);
    written += static_cast<double>(block.size());
  }
  std::fputs("FINI\n", out);
  std::fclose(out);
  std::printf("%s: %.1f MB, %d operations\n", argv[2], written / 1024 / 1024, operation);
  return 0;
}
