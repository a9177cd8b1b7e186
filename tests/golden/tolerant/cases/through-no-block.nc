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
(ERROR: INTEROP-008 #222  ROUND_HOLE  has no depth and goes through its workpiece #4  WORKPIECE , but the workpiece has no bounding BLOCK, so the depth of the hole is unknown - the program is incomplete)
through-no-block.stp:36:1: warning: EXP-062: #222 ROUND_HOLE.depth: '$' but the attribute is not OPTIONAL (tolerated; an error follows where machining needs the value; --strict reports each instance as an error)
through-no-block.stp:36:1: error: INTEROP-008: #222 (ROUND_HOLE) has no depth and goes through its workpiece #4 (WORKPIECE), but the workpiece has no bounding BLOCK, so the depth of the hole is unknown
