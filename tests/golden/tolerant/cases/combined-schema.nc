%
(PROJECT #1)
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
G0 X77. Y40. Z50.
M5
M9
M2
%
combined-schema.stp:5:1: note: INTEROP-001: FILE_SCHEMA 'COMBINED_SCHEMA' is read as 'machining_schema', the ISO 14649 schema under another name (docs/interoperability.md, "Variants"): the file is checked against '<built-in>'
combined-schema.stp:8:1: warning: EXP-062: #1 PROJECT.its_id: '$' but the attribute is not OPTIONAL (tolerated; an error follows where machining needs the value; --strict reports each instance as an error)
