&ACCESS RVP
&REL 1
DEF EXECUTABLES()
DECL REAL V_RAPID, V_FEED
; PROJECT #1 EXECUTABLES
; ncpost profile kuka-krl - save as EXECUTABLES.src
;FOLD INI
BAS(#INITMOV, 0)
;ENDFOLD (INI)
$BASE = BASE_DATA[1]
$TOOL = TOOL_DATA[1]
$ORI_TYPE = #CONSTANT
$CIRC_TYPE = #BASE
$APO.CDIS = 0.05
V_RAPID = 0.5
; WORKPLAN #2 MAIN
; SETUP #8 SETUP
; MSG Clamp the blank
; TOOL END MILL 10
; TOOL CHANGE T901 - fit the tool, then start
HALT
$TOOL = TOOL_DATA[1]:{X 0, Y 0, Z 70, A 0, B 0, C 0}
; WORKPLAN #42 NESTED
; WS #10 CUT
V_FEED = 0.02 ; 1200 mm/min
$ANOUT[1] = 0.125 ; S3000 rpm
$OUT[2] = FALSE
$OUT[1] = TRUE ; spindle clockwise
$OUT[3] = TRUE ; flood coolant
PTP {X 0, Y 0, Z 50, A 0, B 0, C 180}
$VEL.CP = V_RAPID
LIN {X 0, Y 0, Z 1, A 0, B 0, C 180} C_DIS
$VEL.CP = V_FEED
LIN {X 10, Y 0, Z 1, A 0, B 0, C 180} C_DIS
; WS #43 UP AND OVER
$VEL.CP = V_RAPID
LIN {X 10, Y 0, Z 20, A 0, B 0, C 180} C_DIS
; OPTIONAL STOP  not available in KRL
; SET_MARK MARK 1
; WAIT_FOR_MARK WAIT 1
; MSG EXCHANGE_PALLET
HALT
; MSG INDEX_TABLE 2
HALT
HALT
; TOOL CHANGE T0 - unload the tool
LIN {X 10, Y 0, Z 50, A 0, B 0, C 180} C_DIS
$OUT[1] = FALSE
$OUT[2] = FALSE ; spindle stop
$OUT[3] = FALSE
$OUT[4] = FALSE ; coolant off
; PROGRAM END
END
