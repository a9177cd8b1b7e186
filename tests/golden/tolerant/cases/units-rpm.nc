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
(WS #13 DRILL BLIND)
G0 X77. Y40. Z50.
M5
(TOOL DRILL 8)
T213
T213 M6
G43 H213
F240.
S1000
M3
(ASSUMED #214  MILLING_TECHNOLOGY : spindle -1000 read as rpm  1000 rpm , not rev/s: 60000 rpm on a tool of diameter 8 mm would cut at 25.1327 m/s)
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
units-rpm.stp:34:1: note: INTEROP-006: #113 (MILLING_TECHNOLOGY): spindle -2400 read as rpm (2400 rpm), not rev/s (144000 rpm): at 2400 rpm on a tool of diameter 10 mm the cutting speed is 1.2567 m/s
units-rpm.stp:34:1: note: INTEROP-006: #113 (MILLING_TECHNOLOGY): cutspeed 75.4 read as m/min (1.2567 m/s), not m/s: at 2400 rpm on a tool of diameter 10 mm the cutting speed is 1.2567 m/s
units-rpm.stp:34:1: note: INTEROP-006: #113 (MILLING_TECHNOLOGY): feedrate 480 read as mm/min (480 mm/min), not m/s (28800000 mm/min): feedrate_per_tooth 0.1 mm × 2 teeth × 2400 rpm = 480 mm/min
units-rpm.stp:35:1: note: INTEROP-006: #214 (MILLING_TECHNOLOGY): spindle -1000 read as rpm (1000 rpm), not rev/s: 60000 rpm on a tool of diameter 8 mm would cut at 25.1327 m/s
units-rpm.stp:59:1: note: INTEROP-004: #234 (DRILLING): cutting_depth taken as 14.4034 mm (unset: the depth of #232 (ROUND_HOLE) and its bottom)
