// A feature-based (conformance class 3) ISO 14649 program of N rectangular pockets and N round
// holes for feature_bench: no toolpaths, so every motion is generated. Sizes vary
// deterministically (a fixed linear congruential sequence), so runs are comparable. With
// --general the pockets are GENERAL_CLOSED_PROFILE polylines instead (offset by the polygon
// offsetter): L shapes and irregular hexagons, in turn, with orthogonal_radius 6..12.
//
//   make_feature_program N [--general] > program.stp

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <iostream>
#include <string>

namespace {

std::uint64_t state = 12345;
double uniform(double lo, double hi) {
  state = state * 6364136223846793005ULL + 1442695040888963407ULL;
  return lo + (hi - lo) * static_cast<double>(state >> 11) / 9007199254740992.0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || (argc > 2 && std::string(argv[2]) != "--general")) {
    std::cerr << "usage: make_feature_program N [--general] > program.stp\n";
    return 2;
  }
  const bool general = argc > 2;
  const long n = std::stol(argv[1]);
  if (n < 1 || n > 1000000) {
    std::cerr << "N must be between 1 and 1000000\n";
    return 2;
  }
  std::string out;
  char line[512];
  const auto add = [&](const char* format, auto... args) {
    std::snprintf(line, sizeof line, format, args...);
    out += line;
    out += '\n';
  };
  out +=
      "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION(('ncpost feature benchmark'),'2;1');\n"
      "FILE_NAME('features.stp','2026-11-22T00:00:00',('ncpost'),('ncpost project'),'',"
      "'make_feature_program','');\nFILE_SCHEMA(('MACHINING_SCHEMA','MILLING_SCHEMA'));\n"
      "ENDSEC;\nDATA;\n";
  // Fixed part: ids below 100.
  std::string elements;
  for (long i = 0; i < 2 * n; ++i) {
    elements += i ? ",#" : "#";
    elements += std::to_string(1000 + i);
  }
  add("#1=PROJECT('FEATURE BENCH',#2,(#4),$,$,$);");
  out += "#2=WORKPLAN('MAIN',(" + elements + "),$,#8,$);\n";  // longer than `line`
  add("#4=WORKPIECE('PLATE',$,0.01,$,$,$,());");
  add("#8=SETUP('SETUP',#20,#30,(#9));");
  add("#9=WORKPIECE_SETUP(#4,#20,$,$,());");
  add("#10=CARTESIAN_POINT('',(0.,0.,0.));");
  add("#11=DIRECTION('',(0.,0.,1.));");
  add("#12=DIRECTION('',(1.,0.,0.));");
  add("#20=AXIS2_PLACEMENT_3D('',#10,#11,#12);");
  add("#21=CARTESIAN_POINT('',(0.,0.,50.));");
  add("#22=AXIS2_PLACEMENT_3D('',#21,#11,#12);");
  add("#30=PLANE('SECURITY',#22);");
  add("#31=PLUS_MINUS_VALUE(0.1,0.1,3);");
  add("#40=MILLING_TOOL_DIMENSION(10.,$,$,30.,$,$,$);");
  add("#41=ENDMILL(#40,3,.RIGHT.,.F.,$);");
  add("#42=CUTTING_COMPONENT(80.,$,$,$,$);");
  add("#43=MILLING_CUTTING_TOOL('ENDMILL 10',#41,(#42),80.,$,$);");
  add("#44=MILLING_TOOL_DIMENSION(8.,31.,$,40.,$,$,$);");
  add("#45=TWIST_DRILL(#44,2,.RIGHT.,.F.,$);");
  add("#46=MILLING_CUTTING_TOOL('DRILL 8',#45,(#42),80.,$,$);");
  add("#50=MILLING_TECHNOLOGY(0.03,.TCP.,$,-40.,$,.F.,.F.,.F.,$);");
  add("#51=MILLING_TECHNOLOGY(0.01,.TCP.,$,-20.,$,.F.,.F.,.F.,$);");
  add("#52=MILLING_MACHINE_FUNCTIONS(.T.,$,$,.F.,$,(),.T.,$,$,());");
  add("#53=CONTOUR_PARALLEL(0.4,.T.,.CW.,$);");
  add("#54=PLANAR_POCKET_BOTTOM_CONDITION();");
  add("#55=THROUGH_BOTTOM_CONDITION();");
  add("#56=BOTTOM_AND_SIDE_ROUGH_MILLING($,$,'ROUGH',5.,$,#43,#50,#52,$,$,$,#53,4.,4.5,0.5,0.3);");
  add("#57=DRILLING($,$,'DRILL',3.,$,#46,#51,#52,$,$,$,$,$,$);");
  add("#58=TOLERANCED_LENGTH_MEASURE(8.,#31);");
  // Pockets on a grid of 100 mm, then holes; each feature has its own placement and sizes.
  long id = 100000;
  for (long i = 0; i < n; ++i) {
    const double x = 100.0 * static_cast<double>(i % 100);
    const double y = 100.0 * static_cast<double>(i / 100);
    const long p = id, a = id + 1, d = id + 2, dp = id + 3, w = id + 4, l = id + 5, c = id + 6,
               prof = id + 7, feat = id + 8;
    id += 9;
    add("#%ld=CARTESIAN_POINT('',(%.3f,%.3f,0.));", p, x, y);
    add("#%ld=AXIS2_PLACEMENT_3D('',#%ld,#11,#12);", a, p);
    add("#%ld=CARTESIAN_POINT('',(0.,0.,%.3f));", d, -uniform(8, 20));
    add("#%ld=PLANE('DEPTH',#%ld);", dp, id);
    add("#%ld=AXIS2_PLACEMENT_3D('',#%ld,#11,#12);", id++, d);
    add("#%ld=TOLERANCED_LENGTH_MEASURE(%.3f,#31);", w, uniform(30, 60));
    add("#%ld=TOLERANCED_LENGTH_MEASURE(%.3f,#31);", l, uniform(40, 80));
    add("#%ld=TOLERANCED_LENGTH_MEASURE(%.3f,#31);", c, uniform(6, 12));
    if (!general) {
      add("#%ld=RECTANGULAR_CLOSED_PROFILE($,#%ld,#%ld);", prof, w, l);
    } else {
      // The outline about the pocket's placement: an L, or a hexagon with jittered corners.
      double xy[6][2];
      if (i % 2 == 0) {
        const double length = uniform(60, 80);
        const double height = uniform(50, 70);
        const double arm = uniform(26, 34);  // room for two corners of 12
        const double x0 = -length / 2;
        const double y0 = -height / 2;
        const double corners[6][2] = {{x0, y0},
                                      {x0 + length, y0},
                                      {x0 + length, y0 + arm},
                                      {x0 + arm, y0 + arm},
                                      {x0 + arm, y0 + height},
                                      {x0, y0 + height}};
        std::copy(&corners[0][0], &corners[0][0] + 12, &xy[0][0]);
      } else {
        for (int k = 0; k < 6; ++k) {
          const double t = (60.0 * k + uniform(-10, 10)) * 3.14159265358979 / 180;
          const double r = uniform(28, 38);
          xy[k][0] = r * std::cos(t);
          xy[k][1] = r * std::sin(t);
        }
      }
      const long first = id;
      id += 7;
      for (int k = 0; k < 6; ++k)
        add("#%ld=CARTESIAN_POINT('',(%.3f,%.3f,0.));", first + k, xy[k][0], xy[k][1]);
      add("#%ld=POLYLINE('',(#%ld,#%ld,#%ld,#%ld,#%ld,#%ld,#%ld));", first + 6, first, first + 1,
          first + 2, first + 3, first + 4, first + 5, first);
      add("#%ld=GENERAL_CLOSED_PROFILE($,#%ld);", prof, first + 6);
    }
    add("#%ld=CLOSED_POCKET('POCKET %ld',#4,(),#%ld,#%ld,(),$,#54,$,#%ld,#%ld);", feat, i, a, dp, c,
        prof);
    add("#%ld=MACHINING_WORKINGSTEP('POCKET %ld',#30,#%ld,#56,$);", 1000 + i, i, feat);
  }
  for (long i = 0; i < n; ++i) {
    const double x = 100.0 * static_cast<double>(i % 100) + 50;
    const double y = 100.0 * static_cast<double>(i / 100) + 50;
    const long p = id, a = id + 1, d = id + 2, da = id + 3, dp = id + 4, feat = id + 5;
    id += 6;
    add("#%ld=CARTESIAN_POINT('',(%.3f,%.3f,0.));", p, x, y);
    add("#%ld=AXIS2_PLACEMENT_3D('',#%ld,#11,#12);", a, p);
    add("#%ld=CARTESIAN_POINT('',(0.,0.,%.3f));", d, -uniform(10, 30));
    add("#%ld=AXIS2_PLACEMENT_3D('',#%ld,#11,#12);", da, d);
    add("#%ld=PLANE('DEPTH',#%ld);", dp, da);
    add("#%ld=ROUND_HOLE('HOLE %ld',#4,(),#%ld,#%ld,#58,$,#55);", feat, i, a, dp);
    add("#%ld=MACHINING_WORKINGSTEP('HOLE %ld',#30,#%ld,#57,$);", 1000 + n + i, i, feat);
  }
  out += "ENDSEC;\nEND-ISO-10303-21;\n";
  std::cout << out;
  return 0;
}
