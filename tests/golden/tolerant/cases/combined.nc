%
(PROJECT #1)
G21 G17 G90 G94 G40 G49 G80 G91.1
(WORKPLAN #2 MAIN)
(SETUP #8)
(WS #10 WS FACE)
(TOOL)
T70
T70 M6
G43 H70
F1200.
S1200
M3
(ASSUMED #70  CUTTING_TOOL : the ABSTRACT CUTTING_TOOL read as a MILLING_CUTTING_TOOL  no spindle orientation   its tool body says what kind of tool it is  tool #70  CUTTING_TOOL     of diameter 50 mm)
(ASSUMED #90  MILLING_MACHINE_FUNCTIONS  attribute coolant is unset, which ISO 14649 does not allow: it is left as it was  off at the start of the program)
G0 X10. Y-30. Z20.
G0 X10. Y-30. Z7.
G1 X10. Y-30. Z0.
G1 X10. Y110. Z0.
G1 X50. Y110. Z0.
G1 X50. Y-30. Z0.
G1 X90. Y-30. Z0.
G1 X90. Y110. Z0.
G1 X90. Y110. Z7.
(WS #11 WS POCKET)
G0 X90. Y110. Z20.
M5
(TOOL END MILL 10)
T71
T71 M6
G43 H71
F600.
S3000
M3
(ASSUMED #71  CUTTING_TOOL : the ABSTRACT CUTTING_TOOL read as a MILLING_CUTTING_TOOL  no spindle orientation   its tool body says what kind of tool it is  tool #71  CUTTING_TOOL   END MILL 10  of diameter 10 mm)
(ASSUMED #90  MILLING_MACHINE_FUNCTIONS  attribute coolant is unset, which ISO 14649 does not allow: it is left as it was  off at the start of the program)
G0 X38. Y40. Z20.
G0 X38. Y40. Z2.
G1 X62. Y40. Z-4.
G1 X38. Y40. Z-10.
G1 X43. Y40. Z-10.
G1 X43. Y38. Z-10.
G1 X57. Y38. Z-10.
G1 X57. Y42. Z-10.
G1 X43. Y42. Z-10.
G1 X43. Y40. Z-10.
G1 X39. Y40. Z-10.
G1 X39. Y34. Z-10.
G1 X61. Y34. Z-10.
G1 X61. Y46. Z-10.
G1 X39. Y46. Z-10.
G1 X39. Y40. Z-10.
G1 X35. Y40. Z-10.
G1 X35. Y31. Z-10.
G1 X35.0192 Y30.8049 Z-10.
G1 X35.0761 Y30.6173 Z-10.
G1 X35.1685 Y30.4444 Z-10.
G1 X35.2929 Y30.2929 Z-10.
G1 X35.4444 Y30.1685 Z-10.
G1 X35.6173 Y30.0761 Z-10.
G1 X35.8049 Y30.0192 Z-10.
G1 X36. Y30. Z-10.
G1 X64. Y30. Z-10.
G1 X64.1951 Y30.0192 Z-10.
G1 X64.3827 Y30.0761 Z-10.
G1 X64.5556 Y30.1685 Z-10.
G1 X64.7071 Y30.2929 Z-10.
G1 X64.8315 Y30.4444 Z-10.
G1 X64.9239 Y30.6173 Z-10.
G1 X64.9808 Y30.8049 Z-10.
G1 X65. Y31. Z-10.
G1 X65. Y31. Z-10.
G1 X65. Y49. Z-10.
G1 X64.9808 Y49.1951 Z-10.
G1 X64.9239 Y49.3827 Z-10.
G1 X64.8315 Y49.5556 Z-10.
G1 X64.7071 Y49.7071 Z-10.
G1 X64.5556 Y49.8315 Z-10.
G1 X64.3827 Y49.9239 Z-10.
G1 X64.1951 Y49.9808 Z-10.
G1 X64. Y50. Z-10.
G1 X36. Y50. Z-10.
G1 X35.8049 Y49.9808 Z-10.
G1 X35.6173 Y49.9239 Z-10.
G1 X35.4444 Y49.8315 Z-10.
G1 X35.2929 Y49.7071 Z-10.
G1 X35.1685 Y49.5556 Z-10.
G1 X35.0761 Y49.3827 Z-10.
G1 X35.0192 Y49.1951 Z-10.
G1 X35. Y49. Z-10.
G1 X35. Y40. Z-10.
G1 X35. Y40. Z2.
(WS #12 WS DRILL)
G0 X35. Y40. Z20.
M5
(TOOL DRILL 10)
T72
T72 M6
G43 H72
F300.
S1800
M3
(ASSUMED #72  CUTTING_TOOL : the ABSTRACT CUTTING_TOOL read as a MILLING_CUTTING_TOOL  no spindle orientation   its tool body says what kind of tool it is  tool #72  CUTTING_TOOL   DRILL 10  of diameter 10 mm)
(ASSUMED #90  MILLING_MACHINE_FUNCTIONS  attribute coolant is unset, which ISO 14649 does not allow: it is left as it was  off at the start of the program)
G0 X20. Y20. Z20.
G0 X20. Y20. Z5.
G1 X20. Y20. Z-15.
G1 X20. Y20. Z5.
G0 X20. Y20. Z20.
M5
M2
%
combined.stp:8:1: warning: EXP-062: #1 PROJECT.its_id: '$' but the attribute is not OPTIONAL (tolerated; an error follows where machining needs the value; --strict reports each instance as an error)
combined.stp:10:1: warning: EXP-062: #8 SETUP.its_id: '$' but the attribute is not OPTIONAL (tolerated; an error follows where machining needs the value; --strict reports each instance as an error)
combined.stp:26:1: warning: EXP-059: ×3, first #70 CUTTING_TOOL: cutting_tool is ABSTRACT; only its subtypes (or a complex instance) can be instantiated (tolerated; an error follows where machining needs the value; --strict reports each instance as an error)
combined.stp:26:1: warning: EXP-062: #70 CUTTING_TOOL.its_id: '$' but the attribute is not OPTIONAL (tolerated; an error follows where machining needs the value; --strict reports each instance as an error)
combined.stp:33:1: warning: EXP-062: #90 MILLING_MACHINE_FUNCTIONS.coolant: '$' but the attribute is not OPTIONAL (tolerated; an error follows where machining needs the value; --strict reports each instance as an error)
combined.stp:33:1: warning: EXP-062: #90 MILLING_MACHINE_FUNCTIONS.through_spindle_coolant: '$' but the attribute is not OPTIONAL (tolerated; an error follows where machining needs the value; --strict reports each instance as an error)
combined.stp:33:1: warning: EXP-062: #90 MILLING_MACHINE_FUNCTIONS.chip_removal: '$' but the attribute is not OPTIONAL (tolerated; an error follows where machining needs the value; --strict reports each instance as an error)
combined.stp:44:1: warning: EXP-062: #901 BLOCK.name: '$' but the attribute is not OPTIONAL (tolerated; an error follows where machining needs the value; --strict reports each instance as an error)
combined.stp:26:1: note: INTEROP-002: #70 (CUTTING_TOOL): the ABSTRACT CUTTING_TOOL read as a MILLING_CUTTING_TOOL (no spindle orientation); its tool body says what kind of tool it is; tool #70 (CUTTING_TOOL) '' of diameter 50 mm
combined.stp:33:1: note: INTEROP-009: #90 (MILLING_MACHINE_FUNCTIONS) attribute coolant is unset, which ISO 14649 does not allow: it is left as it was (off at the start of the program)
combined.stp:27:1: note: INTEROP-002: #71 (CUTTING_TOOL): the ABSTRACT CUTTING_TOOL read as a MILLING_CUTTING_TOOL (no spindle orientation); its tool body says what kind of tool it is; tool #71 (CUTTING_TOOL) 'END MILL 10' of diameter 10 mm
combined.stp:33:1: note: INTEROP-009: #90 (MILLING_MACHINE_FUNCTIONS) attribute coolant is unset, which ISO 14649 does not allow: it is left as it was (off at the start of the program)
combined.stp:28:1: note: INTEROP-002: #72 (CUTTING_TOOL): the ABSTRACT CUTTING_TOOL read as a MILLING_CUTTING_TOOL (no spindle orientation); its tool body says what kind of tool it is; tool #72 (CUTTING_TOOL) 'DRILL 10' of diameter 10 mm
combined.stp:33:1: note: INTEROP-009: #90 (MILLING_MACHINE_FUNCTIONS) attribute coolant is unset, which ISO 14649 does not allow: it is left as it was (off at the start of the program)
