// Makes the same milling program twice, as an ISO 14649 (ARM) file and as an AP238 AIM file,
// for the AP238 benchmark (docs/benchmarks.md): workingsteps of one milling operation each,
// whose toolpaths are polylines of POINTS points and, every fourth, a quarter circle; the
// first toolpath of each workingstep is a rapid approach. The AIM file spells it the way CAM
// exporters do (one MACHINING_TOOLPATH per toolpath with its sequence relationship, technology
// and functions relationships and 'priority', 'trajectory type' and 'basic curve' properties),
// and the writing stops when the AIM file reaches SIZE_MB. Both files give the same motions.
//
//   make_ap238_program SIZE_MB POINTS OUT_ARM.stp OUT_AIM.stp

#include <cstdio>
#include <fstream>
#include <iostream>
#include <string>

namespace {

constexpr int kPathsPerWorkingstep = 40;

std::string num(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.4f", v);
  return buffer;
}

std::string point(std::uint64_t id, double x, double y, double z) {
  return "#" + std::to_string(id) + "=CARTESIAN_POINT('',(" + num(x) + "," + num(y) + "," + num(z) +
         "));\n";
}

struct Writer {
  std::string arm;
  std::string aim;
  std::uint64_t next = 1000;  // ids past the fixed preamble of both files
  std::uint64_t id() { return next++; }
};

const char* kHeader =
    "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION(('ncpost AP238 benchmark program'),'2;1');\n"
    "FILE_NAME('bench','2026-11-26T00:00:00',('ncpost'),(''),'','make_ap238_program','');\n";

// The ARM preamble: project, main workplan (its element list is written last), tool,
// technologies, functions, security plane, the placement every circle uses.
std::string arm_preamble() {
  return std::string(kHeader) +
         "FILE_SCHEMA(('MACHINING_SCHEMA','MILLING_SCHEMA'));\nENDSEC;\nDATA;\n"
         "#1=PROJECT('BENCH',#2,(#3),$,$,$);\n#3=WORKPIECE('BLANK',$,$,$,$,$,());\n"
         "#10=MILLING_CUTTING_TOOL('5',#11,(#13),60.,$,$);\n"
         "#11=ENDMILL(#12,3,.RIGHT.,.F.,$);\n#12=MILLING_TOOL_DIMENSION(10.,$,$,25.,$,$,$);\n"
         "#13=CUTTING_COMPONENT(60.,$,$,$,$);\n"
         "#20=MILLING_TECHNOLOGY(0.02,.TCP.,$,-50.,$,.F.,.F.,.F.,$);\n"
         "#21=MILLING_TECHNOLOGY(0.01,.TCP.,$,-50.,$,.F.,.F.,.F.,$);\n"
         "#22=MILLING_MACHINE_FUNCTIONS(.T.,$,$,.F.,$,(),.F.,$,$,());\n"
         "#30=PLANE('SECURITY',#31);\n#31=AXIS2_PLACEMENT_3D('',#32,$,$);\n"
         "#32=CARTESIAN_POINT('',(0.,0.,50.));\n"
         "#40=PLANAR_FACE('FACE',#3,(),#41,#42,#43,#46,$,());\n"
         "#41=AXIS2_PLACEMENT_3D('',#47,$,$);\n#42=PLANE('DEPTH',#41);\n"
         "#43=LINEAR_PATH($,#44,#48);\n#44=TOLERANCED_LENGTH_MEASURE(100.,#45);\n"
         "#45=PLUS_MINUS_VALUE(0.1,0.1,2);\n#46=LINEAR_PROFILE($,#49);\n"
         "#47=CARTESIAN_POINT('',(0.,0.,0.));\n#48=DIRECTION('',(1.,0.,0.));\n"
         "#49=NUMERIC_PARAMETER('WIDTH',100.,'MM');\n";
}

// The AIM preamble: units, contexts, the project and its main workplan, the tool's kind, the
// technologies (1200 and 600 mm/min, 3000 rpm clockwise), the functions, the shared
// property representations.
std::string aim_preamble() {
  return std::string(kHeader) +
         "FILE_SCHEMA(('INTEGRATED_CNC_SCHEMA'));\nENDSEC;\nDATA;\n"
         "#500=REPRESENTATION_CONTEXT('','none');\n"
         "#501=(LENGTH_UNIT()NAMED_UNIT(*)SI_UNIT(.MILLI.,.METRE.));\n"
         "#502=(NAMED_UNIT(*)PLANE_ANGLE_UNIT()SI_UNIT($,.RADIAN.));\n"
         "#503=(GEOMETRIC_REPRESENTATION_CONTEXT(3)GLOBAL_UNIT_ASSIGNED_CONTEXT((#501,#502))"
         "REPRESENTATION_CONTEXT('','3D'));\n"
         "#504=(NAMED_UNIT(*)SI_UNIT($,.SECOND.)TIME_UNIT());\n"
         "#505=TIME_MEASURE_WITH_UNIT(TIME_MEASURE(60.),#504);\n"
         "#506=DIMENSIONAL_EXPONENTS(0.,0.,1.,0.,0.,0.,0.);\n"
         "#507=(CONVERSION_BASED_UNIT('minute',#505)NAMED_UNIT(#506)TIME_UNIT());\n"
         "#508=DIMENSIONAL_EXPONENTS(0.,0.,0.,0.,0.,0.,0.);\n"
         "#509=CONTEXT_DEPENDENT_UNIT(#508,'revolution');\n"
         "#510=DERIVED_UNIT_ELEMENT(#509,1.);\n#511=DERIVED_UNIT_ELEMENT(#507,-1.);\n"
         "#512=DERIVED_UNIT((#510,#511));\n#513=DERIVED_UNIT_ELEMENT(#501,1.);\n"
         "#514=DERIVED_UNIT((#513,#511));\n"
         "#520=APPLICATION_CONTEXT('cnc');\n#521=PRODUCT_CONTEXT('',#520,'');\n"
         "#522=PRODUCT_DEFINITION_CONTEXT('',#520,'');\n"
         "#1=MACHINING_PROJECT('BENCH','BENCH',$,(#521));\n"
         "#523=PRODUCT_DEFINITION_FORMATION('','',#1);\n"
         "#524=PRODUCT_DEFINITION('','',#523,#522);\n#2=MACHINING_WORKPLAN('MAIN','','','');\n"
         "#525=PRODUCT_DEFINITION_PROCESS('machining','',#2,'');\n"
         "#526=PROCESS_PRODUCT_ASSOCIATION('','',#524,#525);\n"
         "#527=ACTION_RESOURCE_TYPE('milling cutting tool');\n"
         "#20=MACHINING_TECHNOLOGY('','milling','','');\n"
         "#530=MEASURE_REPRESENTATION_ITEM('feed speed',NUMERIC_MEASURE(1200.),#514);\n"
         "#531=MACHINING_FEED_SPEED_REPRESENTATION('feed speed',(#530),#500);\n"
         "#532=ACTION_PROPERTY('feedrate','',#20);\n"
         "#533=ACTION_PROPERTY_REPRESENTATION('','',#532,#531);\n"
         "#534=MEASURE_REPRESENTATION_ITEM('rotational speed',NUMERIC_MEASURE(-3000.),#512);\n"
         "#535=MACHINING_SPINDLE_SPEED_REPRESENTATION('spindle speed',(#534),#500);\n"
         "#536=ACTION_PROPERTY('spindle','',#20);\n"
         "#537=ACTION_PROPERTY_REPRESENTATION('','',#536,#535);\n"
         "#21=MACHINING_TECHNOLOGY('','milling','','');\n"
         "#540=MEASURE_REPRESENTATION_ITEM('feed speed',NUMERIC_MEASURE(600.),#514);\n"
         "#541=MACHINING_FEED_SPEED_REPRESENTATION('feed speed',(#540),#500);\n"
         "#542=ACTION_PROPERTY('feedrate','',#21);\n"
         "#543=ACTION_PROPERTY_REPRESENTATION('','',#542,#541);\n"
         "#544=ACTION_PROPERTY('spindle','',#21);\n"
         "#545=ACTION_PROPERTY_REPRESENTATION('','',#544,#535);\n"
         "#22=MACHINING_FUNCTIONS('','milling','','');\n"
         "#550=DESCRIPTIVE_REPRESENTATION_ITEM('coolant','coolant on');\n"
         "#551=REPRESENTATION('',(#550),#500);\n#552=ACTION_PROPERTY('coolant','',#22);\n"
         "#553=ACTION_PROPERTY_REPRESENTATION('','',#552,#551);\n"
         "#30=PLANE('SECURITY',#31);\n#31=AXIS2_PLACEMENT_3D('',#32,$,$);\n"
         "#32=CARTESIAN_POINT('',(0.,0.,50.));\n#560=REPRESENTATION('',(#30),#503);\n"
         "#561=DESCRIPTIVE_REPRESENTATION_ITEM('priority','required');\n"
         "#562=REPRESENTATION('',(#561),#500);\n"
         "#563=DESCRIPTIVE_REPRESENTATION_ITEM('trajectory type','trajectory path');\n"
         "#564=REPRESENTATION('',(#563),#500);\n"
         "#565=DESCRIPTIVE_REPRESENTATION_ITEM('trajectory type','non-contact');\n"
         "#566=REPRESENTATION('',(#565),#500);\n";
}

void aim_property(Writer& w, std::uint64_t owner, const char* name, std::uint64_t rep) {
  const std::uint64_t p = w.id();
  w.aim += "#" + std::to_string(p) + "=ACTION_PROPERTY('" + name + "',''," + "#" +
           std::to_string(owner) + ");\n#" + std::to_string(w.id()) +
           "=ACTION_PROPERTY_REPRESENTATION('',''," + "#" + std::to_string(p) + ",#" +
           std::to_string(rep) + ");\n";
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 5) {
    std::cerr << "usage: make_ap238_program SIZE_MB POINTS OUT_ARM.stp OUT_AIM.stp\n";
    return 2;
  }
  const double target = std::stod(argv[1]) * 1e6;
  const int points = std::max(2, std::stoi(argv[2]));
  Writer w;
  w.arm = arm_preamble();
  w.aim = aim_preamble();
  std::string arm_elements;
  std::string operations;  // the one tool's usage
  double x = 0;            // the tool's position along X; each workingstep moves on
  std::size_t workingsteps = 0;
  std::size_t motions = 0;
  while (static_cast<double>(w.aim.size()) < target) {
    ++workingsteps;
    const std::uint64_t ws = w.id();
    const std::uint64_t op = w.id();
    const std::uint64_t list = w.id();
    const std::string WS = "#" + std::to_string(ws);
    const std::string OP = "#" + std::to_string(op);
    arm_elements += arm_elements.empty() ? "" : ",";
    arm_elements += WS;
    operations += operations.empty() ? "" : ",";
    operations += OP;
    w.arm += WS + "=MACHINING_WORKINGSTEP('WS " + std::to_string(workingsteps) + "',#30,#40," + OP +
             ",$);\n" + OP + "=FREEFORM_OPERATION(#" + std::to_string(list) + ",$,'OP " +
             std::to_string(workingsteps) + "',$,$,#10,#20,#22,$,$,$,$);\n";
    w.aim += WS + "=MACHINING_WORKINGSTEP('WS " + std::to_string(workingsteps) +
             "','machining','','');\n#" + std::to_string(w.id()) +
             "=MACHINING_PROCESS_SEQUENCE_RELATIONSHIP('','',#2," + WS + "," +
             std::to_string(workingsteps) + ".);\n" + OP + "=MILLING_TYPE_OPERATION('OP " +
             std::to_string(workingsteps) + "','','','');\n#" + std::to_string(w.id()) +
             "=MACHINING_OPERATION_RELATIONSHIP('',''," + WS + "," + OP + ");\n#" +
             std::to_string(w.id()) + "=MACHINING_TECHNOLOGY_RELATIONSHIP('',''," + OP +
             ",#20);\n#" + std::to_string(w.id()) + "=MACHINING_FUNCTIONS_RELATIONSHIP('',''," +
             OP + ",#22);\n";
    aim_property(w, ws, "security plane", 560);
    std::string arm_paths;
    double y = 0;
    double z = 20;
    for (int k = 0; k < kPathsPerWorkingstep; ++k) {
      const std::uint64_t path = w.id();
      const std::uint64_t curve = w.id();
      const std::string PATH = "#" + std::to_string(path);
      const std::string CURVE = "#" + std::to_string(curve);
      arm_paths += arm_paths.empty() ? "" : ",";
      arm_paths += PATH;
      const bool rapid = k == 0;
      const bool arc = !rapid && k % 4 == 3;
      std::string geometry;  // points and curve, the same in both files
      if (arc) {
        // A quarter circle of radius 5 counter-clockwise from (x, y) about (x, y + 5).
        const std::uint64_t a = w.id(), b = w.id(), c = w.id(), pl = w.id(), cp = w.id();
        geometry = point(a, x, y, z) + point(b, x + 5, y + 5, z) + point(cp, x, y + 5, z) + "#" +
                   std::to_string(pl) + "=AXIS2_PLACEMENT_3D('',#" + std::to_string(cp) +
                   ",$,$);\n#" + std::to_string(c) + "=CIRCLE(''," + "#" + std::to_string(pl) +
                   ",5.);\n" + CURVE + "=TRIMMED_CURVE('',#" + std::to_string(c) + ",(#" +
                   std::to_string(a) + "),(#" + std::to_string(b) + "),.T.,.CARTESIAN.);\n";
        x += 5;
        y += 5;
        motions += 1;
      } else {
        std::string refs;
        for (int p = 0; p < points; ++p) {
          const std::uint64_t pt = w.id();
          refs += refs.empty() ? "#" : ",#";
          refs += std::to_string(pt);
          geometry += point(pt, x, y, z);
          if (p + 1 < points) {
            if (rapid)
              z = 0;
            else
              x += 1, y += (p % 2 == 0 ? 0.5 : -0.5);
          }
        }
        geometry += CURVE + "=POLYLINE('',(" + refs + "));\n";
        motions += static_cast<std::size_t>(points - 1);
      }
      w.arm += geometry + PATH + "=CUTTER_LOCATION_TRAJECTORY(.T.," +
               (rapid ? ".NON_CONTACT." : ".TRAJECTORY_PATH.") + ",$," +
               (k % 2 == 1 ? "#21" : "$") + ",$,$," + CURVE + ",$,$);\n";
      w.aim += geometry + PATH + "=MACHINING_TOOLPATH('P','cutter location trajectory','','');\n#" +
               std::to_string(w.id()) + "=MACHINING_TOOLPATH_SEQUENCE_RELATIONSHIP('',''," + OP +
               "," + PATH + "," + std::to_string(k + 1) + ".);\n";
      if (k % 2 == 1)
        w.aim += "#" + std::to_string(w.id()) + "=MACHINING_TECHNOLOGY_RELATIONSHIP('',''," + PATH +
                 ",#21);\n";
      w.aim += "#" + std::to_string(w.id()) + "=MACHINING_FUNCTIONS_RELATIONSHIP('',''," + PATH +
               ",#22);\n";
      aim_property(w, path, "priority", 562);
      aim_property(w, path, "trajectory type", rapid ? 566 : 564);
      const std::uint64_t rep = w.id();
      w.aim += "#" + std::to_string(rep) + "=REPRESENTATION('',(" + CURVE + "),#503);\n";
      aim_property(w, path, "basic curve", rep);
    }
    w.arm += "#" + std::to_string(list) + "=TOOLPATH_LIST((" + arm_paths + "));\n";
    x += 10;
  }
  w.arm += "#2=WORKPLAN('MAIN',(" + arm_elements + "),$,$,$);\nENDSEC;\nEND-ISO-10303-21;\n";
  w.aim += "#10=MACHINING_TOOL('5','',(" + operations + "),#527);\nENDSEC;\nEND-ISO-10303-21;\n";
  std::ofstream(argv[3], std::ios::binary) << w.arm;
  std::ofstream(argv[4], std::ios::binary) << w.aim;
  std::cout << "workingsteps=" << workingsteps << " motions=" << motions
            << " arm_mb=" << static_cast<double>(w.arm.size()) / 1e6
            << " aim_mb=" << static_cast<double>(w.aim.size()) / 1e6 << '\n';
  return 0;
}
