%
(PROJECT #1 INTEROP)
G21 G17 G90 G94 G40 G49 G80 G91.1
(WORKPLAN #2 MAIN)
(SETUP #8 SETUP)
(WS #12 DRILL THROUGH)
(TOOL DRILL 8)
T213
T213 M6
G43 H213
F240.
S1200
M3
M8
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
implicit-depths.stp:36:1: warning: EXP-062: #222 ROUND_HOLE.depth: '$' but the attribute is not OPTIONAL (tolerated; an error follows where machining needs the value; --strict reports each instance as an error)
implicit-depths.stp:36:1: note: INTEROP-003: #222 (ROUND_HOLE): depth taken as 20 mm (its depth is unset and its bottom THROUGH_BOTTOM_CONDITION: it goes through #4 (WORKPIECE), whose bounding #5 (BLOCK) ends 20 mm below the hole's top)
implicit-depths.stp:37:1: note: INTEROP-004: #224 (DRILLING): cutting_depth taken as 23.4034 mm (unset: the depth of #222 (ROUND_HOLE) and its bottom)
implicit-depths.stp:47:1: note: INTEROP-004: #234 (DRILLING): cutting_depth taken as 14.4034 mm (unset: the depth of #232 (ROUND_HOLE) and its bottom)
