// A five-axis ISO 14649 program for render_bench: W workingsteps, each one toolpath of P points
// whose tool-axis curve (a polyline of directions) wobbles 35 degrees off Z while turning round
// it, so that the rotary axes move on every motion, cross +-180 and pass the pole now and then.
// Deterministic, so runs are comparable (docs/benchmarks.md, "Multi-axis output").
//
//   make_five_axis_program WORKINGSTEPS POINTS > program.stp

#include <cmath>
#include <cstdio>
#include <iostream>
#include <numbers>
#include <string>

namespace {

// "#first,#first+step,..." (count ids).
void append_ids(std::string& out, long first, long step, long count) {
  for (long i = 0; i < count; ++i) {
    if (i) out += ',';
    out += '#';
    out += std::to_string(first + i * step);
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: make_five_axis_program WORKINGSTEPS POINTS > program.stp\n";
    return 2;
  }
  const long workingsteps = std::stol(argv[1]);
  const long points = std::stol(argv[2]);
  if (workingsteps < 1 || workingsteps > 100000 || points < 2 || points > 100000) {
    std::cerr << "WORKINGSTEPS must be 1..100000 and POINTS 2..100000\n";
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
      "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION(('ncpost five-axis benchmark'),'2;1');\n"
      "FILE_NAME('five-axis.stp','2026-11-27T00:00:00',('ncpost'),('ncpost project'),'',"
      "'make_five_axis_program','');\nFILE_SCHEMA(('MACHINING_SCHEMA','MILLING_SCHEMA'));\n"
      "ENDSEC;\nDATA;\n";
  // Fixed part (ids below 100): project, setup, tool, technology, security plane, placement.
  add("#1=PROJECT('FIVE AXIS BENCH',#2,(#50),$,$,$);");
  // Appended directly: an id list can be longer than `line`.
  out += "#2=WORKPLAN('MAIN',(";
  append_ids(out, 1000, 10, workingsteps);
  out += "),$,#8,$);\n";
  out +=
      "#8=SETUP('SETUP',#63,#60,(#9));\n#9=WORKPIECE_SETUP(#50,#63,$,$,());\n"
      "#50=WORKPIECE('BLANK',$,$,$,$,$,());\n"
      "#51=MILLING_CUTTING_TOOL('BALL 6',#52,(#54),70.,$,$);\n"
      "#52=BALL_ENDMILL(#53,2,.RIGHT.,.F.,$);\n#53=MILLING_TOOL_DIMENSION(6.,$,$,20.,3.,$,$);\n"
      "#54=CUTTING_COMPONENT(70.,$,$,$,$);\n"
      "#55=MILLING_TECHNOLOGY(0.02,.TCP.,$,-50.,$,.F.,.F.,.F.,$);\n"
      "#56=MILLING_MACHINE_FUNCTIONS(.T.,$,$,.F.,$,(),.F.,$,$,());\n"
      "#60=PLANE('SECURITY PLANE',#61);\n#61=AXIS2_PLACEMENT_3D('SECURITY',#62,$,$);\n"
      "#62=CARTESIAN_POINT('',(0.,0.,50.));\n#63=AXIS2_PLACEMENT_3D('IDENTITY',#64,#65,#66);\n"
      "#64=CARTESIAN_POINT('',(0.,0.,0.));\n#65=DIRECTION('Z',(0.,0.,1.));\n"
      "#66=DIRECTION('X',(1.,0.,0.));\n#67=PLANE('DEPTH',#63);\n"
      "#68=LINEAR_PATH($,#69,#66);\n#69=TOLERANCED_LENGTH_MEASURE(100.,#70);\n"
      "#70=PLUS_MINUS_VALUE(0.1,0.1,2);\n#71=LINEAR_PROFILE($,#72);\n"
      "#72=NUMERIC_PARAMETER('WIDTH',100.,'MM');\n";
  long id = 10000000;  // points and directions, above the workingsteps' ids
  const double tilt = 35 * std::numbers::pi / 180;
  for (long w = 0; w < workingsteps; ++w) {
    const long base = 1000 + w * 10;
    add("#%ld=MACHINING_WORKINGSTEP('WS %ld',#60,#%ld,#%ld,$);", base, w + 1, base + 1, base + 2);
    add("#%ld=PLANAR_FACE('FACE',#50,(#%ld),#63,#67,#68,#71,$,());", base + 1, base + 2);
    add("#%ld=FREEFORM_OPERATION(#%ld,$,'5X OP',5.,$,#51,#55,#56,$,$,$,$);", base + 2, base + 3);
    add("#%ld=TOOLPATH_LIST((#%ld));", base + 3, base + 4);
    add("#%ld=CUTTER_LOCATION_TRAJECTORY(.T.,.TRAJECTORY_PATH.,$,$,$,$,#%ld,#%ld,$);", base + 4,
        base + 5, base + 6);
    const long first_point = id;
    for (long p = 0; p < points; ++p) {
      const double t = static_cast<double>(p) / static_cast<double>(points);
      const double x = 100 * std::cos(2 * std::numbers::pi * t);
      const double y = 100 * std::sin(2 * std::numbers::pi * t);
      add("#%ld=CARTESIAN_POINT('',(%.4f,%.4f,%.4f));", id++, x, y,
          -0.01 * static_cast<double>(p % 100));
    }
    const long first_axis = id;
    for (long p = 0; p < points; ++p) {
      // The tilt breathes between 0 (the pole) and 35 degrees while turning round Z 3 times.
      const double t = static_cast<double>(p) / static_cast<double>(points);
      const double a = tilt * std::abs(std::sin(5 * std::numbers::pi * t));
      const double c = 6 * std::numbers::pi * t;
      add("#%ld=CARTESIAN_POINT('',(%.9f,%.9f,%.9f));", id++, std::sin(a) * std::cos(c),
          std::sin(a) * std::sin(c), std::cos(a));
    }
    add("#%ld=POLYLINE('PATH',(", base + 5);
    out.pop_back();  // the newline add() wrote
    append_ids(out, first_point, 1, points);
    out += "));\n";
    add("#%ld=POLYLINE('AXES',(", base + 6);
    out.pop_back();
    append_ids(out, first_axis, 1, points);
    out += "));\n";
  }
  out += "ENDSEC;\nEND-ISO-10303-21;\n";
  std::fwrite(out.data(), 1, out.size(), stdout);
  return 0;
}
