%
(PROJECT #1 INTEROP)
G21 G17 G90 G94 G40 G49 G80 G91.1
(WORKPLAN #2 MAIN)
(SETUP #8 SETUP)
(WS #10 POCKET)
(TOOL ENDMILL 10)
T112
T112 M6
G43 H112
F480.
S2400
M3
M8
(ASSUMED #109  TOOL_DIMENSION : a generic TOOL_DIMENSION read as a MILLING_TOOL_DIMENSION  diameter, tip half angle, circumference angle, cutting edge length, edge radius, edge centre   tool #112  MILLING_CUTTING_TOOL   ENDMILL 10  of diameter 10 mm)
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
(WS #13 DRILL BLIND)
G0 X77. Y40. Z50.
M5
(TOOL DRILL 8)
T213
T213 M6
G43 H213
F240.
S1200
M3
(ASSUMED #213  CUTTING_TOOL : the ABSTRACT CUTTING_TOOL read as a MILLING_CUTTING_TOOL  no spindle orientation   its tool body says what kind of tool it is  tool #213  CUTTING_TOOL   DRILL 8  of diameter 8 mm)
(ASSUMED #209  TOOL_DIMENSION : a generic TOOL_DIMENSION read as a MILLING_TOOL_DIMENSION  diameter, tip half angle, circumference angle, cutting edge length, edge radius, edge centre   tool #213  CUTTING_TOOL   DRILL 8  of diameter 8 mm)
G0 X85. Y65. Z50.
F240.
G0 X85. Y65. Z50.
G0 X85. Y65. Z3.
G1 X85. Y65. Z-12.
G0 X85. Y65. Z50.
M5
M9
M2
%
tool-dimension.stp:33:1: warning: EXP-059: #213 CUTTING_TOOL: cutting_tool is ABSTRACT; only its subtypes (or a complex instance) can be instantiated (tolerated; an error follows where machining needs the value; --strict reports each instance as an error)
tool-dimension.stp:26:1: note: INTEROP-002: #109 (TOOL_DIMENSION): a generic TOOL_DIMENSION read as a MILLING_TOOL_DIMENSION (diameter, tip half angle, circumference angle, cutting edge length, edge radius, edge centre); tool #112 (MILLING_CUTTING_TOOL) 'ENDMILL 10' of diameter 10 mm
tool-dimension.stp:33:1: note: INTEROP-002: #213 (CUTTING_TOOL): the ABSTRACT CUTTING_TOOL read as a MILLING_CUTTING_TOOL (no spindle orientation); its tool body says what kind of tool it is; tool #213 (CUTTING_TOOL) 'DRILL 8' of diameter 8 mm
tool-dimension.stp:30:1: note: INTEROP-002: #209 (TOOL_DIMENSION): a generic TOOL_DIMENSION read as a MILLING_TOOL_DIMENSION (diameter, tip half angle, circumference angle, cutting edge length, edge radius, edge centre); tool #213 (CUTTING_TOOL) 'DRILL 8' of diameter 8 mm
