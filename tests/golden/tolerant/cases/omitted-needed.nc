%
(PROJECT #1 POCKET-CIRCLE-RAMP)
G21 G17 G90 G94 G40 G49 G80 G91.1
(WORKPLAN #2 MAIN)
(SETUP #8 SETUP)
(WS #10 ROUND POCKET)
(TOOL ENDMILL 12)
T112
T112 M6
G43 H112
F1800.
S2100
M3
M8
(ERROR: STEPNC-103 #125  PLUNGE_RAMP  attribute angle is    , but ISO 14649 requires it and the toolpath depends on it: nothing is assumed in its place - the program is incomplete)
omitted-needed.stp:39:1: warning: EXP-062: #125 PLUNGE_RAMP.angle: '$' but the attribute is not OPTIONAL (tolerated; an error follows where machining needs the value; --strict reports each instance as an error)
omitted-needed.stp:39:1: error: STEPNC-103: #125 (PLUNGE_RAMP) attribute angle is '$', but ISO 14649 requires it and the toolpath depends on it: nothing is assumed in its place
omitted-needed.stp:39:1: error: STEPNC-103: #125 (PLUNGE_RAMP) angle must be between 0 and 90 degrees
