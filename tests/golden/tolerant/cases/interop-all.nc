%
(PROJECT #1)
G21 G17 G90 G94 G40 G49 G80 G91.1
(WORKPLAN #2)
(SETUP #8)
(WS #10 POCKET)
(TOOL)
T112
T112 M6
G43 H112
F480.
S2400
M3
M8
(ASSUMED #112  CUTTING_TOOL : the ABSTRACT CUTTING_TOOL read as a MILLING_CUTTING_TOOL  no spindle orientation   its tool body says what kind of tool it is  tool #112  CUTTING_TOOL     of diameter 10 mm)
(ASSUMED #109  TOOL_DIMENSION : a generic TOOL_DIMENSION read as a MILLING_TOOL_DIMENSION  diameter, tip half angle, circumference angle, cutting edge length, edge radius, edge centre   tool #112  CUTTING_TOOL     of diameter 10 mm)
(ASSUMED #113  MILLING_TECHNOLOGY : spindle -2400 read as rpm  2400 rpm , not rev/s  144000 rpm : at 2400 rpm on a tool of diameter 10 mm the cutting speed is 1.2567 m/s)
(ASSUMED #113  MILLING_TECHNOLOGY : cutspeed 75.4 read as m/min  1.2567 m/s , not m/s: at 2400 rpm on a tool of diameter 10 mm the cutting speed is 1.2567 m/s)
(ASSUMED #113  MILLING_TECHNOLOGY : feedrate 480 read as mm/min  480 mm/min , not m/s  28800000 mm/min : feedrate_per_tooth 0.1 mm   2 teeth   2400 rpm = 480 mm/min)
G0 X61. Y40. Z50.
G0 X61. Y40. Z5.
G0 X61. Y40. Z2.
G3 X61. Y40. Z-5. I-4. J0. P2
G1 X57. Y40. Z-5.
G1 X67. Y40. Z-5.
G1 X72. Y40. Z-5.
G1 X72. Y45. Z-5.
G1 X52. Y45. Z-5.
G1 X52. Y35. Z-5.
G1 X72. Y35. Z-5.
G1 X72. Y40. Z-5.
G1 X77. Y40. Z-5.
G1 X77. Y49. Z-5.
G3 X76. Y50. Z-5. I-1. J0.
G1 X48. Y50. Z-5.
G3 X47. Y49. Z-5. I0. J-1.
G1 X47. Y31. Z-5.
G3 X48. Y30. Z-5. I1. J0.
G1 X76. Y30. Z-5.
G3 X77. Y31. Z-5. I0. J1.
G1 X77. Y40. Z-5.
G0 X77. Y40. Z5.
(WS #11 L POCKET)
(ASSUMED #156  POLYLINE  of #157  GENERAL_CLOSED_PROFILE : closed with a straight line of 40 mm back to its first point  a closed profile s polyline that does not repeat its first point)
G0 X77. Y40. Z50.
G0 X20.6227 Y17.1614 Z50.
G0 X20.6227 Y17.1614 Z5.
G0 X20.6227 Y17.1614 Z2.
G3 X20.6227 Y17.1614 Z-4. I-4. J0. P2
G1 X16.6227 Y17.1614 Z-4.
G1 X16.4727 Y17.326 Z-4.
G1 X16.4727 Y16.4727 Z-4.
G1 X17.326 Y16.4727 Z-4.
G1 X17.2693 Y16.5231 Z-4.
G2 X16.6227 Y17.1614 Z-4. I7.6439 J8.3899
G1 X18.9956 Y19.3519 Z-4.
G2 X16.7641 Y24.6343 Z-4. I5.999 J5.6467
G1 X16.756 Y25. Z-4.
G1 X16.756 Y36.756 Z-4.
G1 X13.244 Y36.756 Z-4.
G1 X13.244 Y13.244 Z-4.
G1 X36.756 Y13.244 Z-4.
G1 X36.756 Y16.756 Z-4.
G1 X25. Y16.756 Z-4.
G2 X18.9956 Y19.3519 Z-4. I-0.0009 J8.24
G1 X21.3622 Y21.5632 Z-4.
G2 X19.9946 Y25. Z-4. I3.6305 J3.4352
G1 X19.9946 Y38.9563 Z-4.
G3 X19.918 Y39.3806 Z-4. I-1.033 J0.0326
G3 X19.0344 Y39.9932 Z-4. I-0.9181 J-0.3807
G1 X18.9563 Y39.9946 Z-4.
G1 X11.0437 Y39.9946 Z-4.
G3 X10.6194 Y39.918 Z-4. I-0.0326 J-1.033
G3 X10.0068 Y39.0344 Z-4. I0.3807 J-0.9181
G1 X10.0054 Y38.9563 Z-4.
G1 X10.0054 Y11.0437 Z-4.
G3 X10.082 Y10.6194 Z-4. I1.033 J-0.0326
G3 X10.9656 Y10.0068 Z-4. I0.9181 J0.3807
G1 X11.0437 Y10.0054 Z-4.
G1 X38.9563 Y10.0054 Z-4.
G3 X39.3806 Y10.082 Z-4. I0.0326 J1.033
G3 X39.9932 Y10.9656 Z-4. I-0.3807 J0.9181
G1 X39.9946 Y11.0437 Z-4.
G1 X39.9946 Y18.9563 Z-4.
G3 X39.918 Y19.3806 Z-4. I-1.033 J0.0326
G3 X39.0344 Y19.9932 Z-4. I-0.9181 J-0.3807
G1 X38.9563 Y19.9946 Z-4.
G1 X25. Y19.9946 Z-4.
G2 X21.3622 Y21.5632 Z-4. I-0.0011 J5.
G0 X21.3622 Y21.5632 Z5.
(WS #12 DRILL THROUGH)
G0 X21.3622 Y21.5632 Z50.
M5
(TOOL)
T213
T213 M6
G43 H213
F240.
S1200
M3
(ASSUMED #213  CUTTING_TOOL : the ABSTRACT CUTTING_TOOL read as a MILLING_CUTTING_TOOL  no spindle orientation   its tool body says what kind of tool it is  tool #213  CUTTING_TOOL     of diameter 8 mm)
(ASSUMED #209  TOOL_DIMENSION : a generic TOOL_DIMENSION read as a MILLING_TOOL_DIMENSION  diameter, tip half angle, circumference angle, cutting edge length, edge radius, edge centre   tool #213  CUTTING_TOOL     of diameter 8 mm)
(ASSUMED #214  MILLING_TECHNOLOGY : spindle -1200 read as rpm  1200 rpm , not rev/s: 72000 rpm on a tool of diameter 8 mm would cut at 30.1593 m/s)
(ASSUMED #222  ROUND_HOLE : depth taken as 20 mm  its depth is unset and its bottom THROUGH_BOTTOM_CONDITION: it goes through #4  WORKPIECE , whose bounding #5  BLOCK  ends 20 mm below the hole s top)
(ASSUMED #224  DRILLING : cutting_depth taken as 23.4034 mm  unset: the depth of #222  ROUND_HOLE  and its bottom)
G0 X85. Y12. Z50.
F240.
G0 X85. Y12. Z50.
G0 X85. Y12. Z3.
G1 X85. Y12. Z-23.4034
G0 X85. Y12. Z50.
(WS #13 DRILL BLIND)
(ASSUMED #234  DRILLING : cutting_depth taken as 14.4034 mm  unset: the depth of #232  ROUND_HOLE  and its bottom)
G0 X85. Y65. Z50.
F240.
G0 X85. Y65. Z50.
G0 X85. Y65. Z3.
G1 X85. Y65. Z-14.4034
G0 X85. Y65. Z50.
M5
M9
M2
%
interop-all.stp:5:1: note: INTEROP-001: FILE_SCHEMA 'COMBINED_SCHEMA' is read as 'machining_schema', the ISO 14649 schema under another name (docs/interoperability.md, "Variants"): the file is checked against '<built-in>'
interop-all.stp:8:1: warning: EXP-062: #1 PROJECT.its_id: '$' but the attribute is not OPTIONAL (tolerated; an error follows where machining needs the value; --strict reports each instance as an error)
interop-all.stp:9:1: warning: EXP-062: #2 WORKPLAN.its_id: '$' but the attribute is not OPTIONAL (tolerated; an error follows where machining needs the value; --strict reports each instance as an error)
interop-all.stp:14:1: warning: EXP-062: #8 SETUP.its_id: '$' but the attribute is not OPTIONAL (tolerated; an error follows where machining needs the value; --strict reports each instance as an error)
interop-all.stp:29:1: warning: EXP-059: ×2, first #112 CUTTING_TOOL: cutting_tool is ABSTRACT; only its subtypes (or a complex instance) can be instantiated (tolerated; an error follows where machining needs the value; --strict reports each instance as an error)
interop-all.stp:29:1: warning: EXP-062: ×2, first #112 CUTTING_TOOL.its_id: '$' but the attribute is not OPTIONAL (tolerated; an error follows where machining needs the value; --strict reports each instance as an error)
interop-all.stp:74:1: warning: EXP-062: #222 ROUND_HOLE.depth: '$' but the attribute is not OPTIONAL (tolerated; an error follows where machining needs the value; --strict reports each instance as an error)
interop-all.stp:29:1: note: INTEROP-002: #112 (CUTTING_TOOL): the ABSTRACT CUTTING_TOOL read as a MILLING_CUTTING_TOOL (no spindle orientation); its tool body says what kind of tool it is; tool #112 (CUTTING_TOOL) '' of diameter 10 mm
interop-all.stp:26:1: note: INTEROP-002: #109 (TOOL_DIMENSION): a generic TOOL_DIMENSION read as a MILLING_TOOL_DIMENSION (diameter, tip half angle, circumference angle, cutting edge length, edge radius, edge centre); tool #112 (CUTTING_TOOL) '' of diameter 10 mm
interop-all.stp:34:1: note: INTEROP-006: #113 (MILLING_TECHNOLOGY): spindle -2400 read as rpm (2400 rpm), not rev/s (144000 rpm): at 2400 rpm on a tool of diameter 10 mm the cutting speed is 1.2567 m/s
interop-all.stp:34:1: note: INTEROP-006: #113 (MILLING_TECHNOLOGY): cutspeed 75.4 read as m/min (1.2567 m/s), not m/s: at 2400 rpm on a tool of diameter 10 mm the cutting speed is 1.2567 m/s
interop-all.stp:34:1: note: INTEROP-006: #113 (MILLING_TECHNOLOGY): feedrate 480 read as mm/min (480 mm/min), not m/s (28800000 mm/min): feedrate_per_tooth 0.1 mm × 2 teeth × 2400 rpm = 480 mm/min
interop-all.stp:57:1: note: INTEROP-005: #156 (POLYLINE) of #157 (GENERAL_CLOSED_PROFILE): closed with a straight line of 40 mm back to its first point (a closed profile's polyline that does not repeat its first point)
interop-all.stp:33:1: note: INTEROP-002: #213 (CUTTING_TOOL): the ABSTRACT CUTTING_TOOL read as a MILLING_CUTTING_TOOL (no spindle orientation); its tool body says what kind of tool it is; tool #213 (CUTTING_TOOL) '' of diameter 8 mm
interop-all.stp:30:1: note: INTEROP-002: #209 (TOOL_DIMENSION): a generic TOOL_DIMENSION read as a MILLING_TOOL_DIMENSION (diameter, tip half angle, circumference angle, cutting edge length, edge radius, edge centre); tool #213 (CUTTING_TOOL) '' of diameter 8 mm
interop-all.stp:35:1: note: INTEROP-006: #214 (MILLING_TECHNOLOGY): spindle -1200 read as rpm (1200 rpm), not rev/s: 72000 rpm on a tool of diameter 8 mm would cut at 30.1593 m/s
interop-all.stp:74:1: note: INTEROP-003: #222 (ROUND_HOLE): depth taken as 20 mm (its depth is unset and its bottom THROUGH_BOTTOM_CONDITION: it goes through #4 (WORKPIECE), whose bounding #5 (BLOCK) ends 20 mm below the hole's top)
interop-all.stp:75:1: note: INTEROP-004: #224 (DRILLING): cutting_depth taken as 23.4034 mm (unset: the depth of #222 (ROUND_HOLE) and its bottom)
interop-all.stp:85:1: note: INTEROP-004: #234 (DRILLING): cutting_depth taken as 14.4034 mm (unset: the depth of #232 (ROUND_HOLE) and its bottom)
