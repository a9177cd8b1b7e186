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
(ERROR: INTEROP-007 #113  MILLING_TECHNOLOGY : spindle -40  2400 rpm as rev/s, 40 as rpm  on a tool of diameter 10 mm cuts at 1.2566 or 0.0209 m/s, but cutspeed is 10  m/s, or m/min : no reading of the units makes them agree - the program is incomplete)
units-conflict.stp:30:1: error: INTEROP-007: #113 (MILLING_TECHNOLOGY): spindle -40 (2400 rpm as rev/s, 40 as rpm) on a tool of diameter 10 mm cuts at 1.2566 or 0.0209 m/s, but cutspeed is 10 (m/s, or m/min): no reading of the units makes them agree
