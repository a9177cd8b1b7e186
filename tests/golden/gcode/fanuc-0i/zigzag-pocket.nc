%
O2000 (ZIGZAG FACING WITH SPACED EXPRESSIONS)
#1 = 60.     (WIDTH X)
#2 = 40.     (HEIGHT Y)
#3 = 8.      (STEP OVER)
#4 = -1.5    (DEPTH)
#5 = 0       (PASS)
#6 = 10.     (TOOL DIAMETER)
G21 G90 G17
T2 M6
S3000 M3
G0 X [ - #6 / 2. ] Y0 Z5.
G1 Z#4 F300.
WH [ #5 * #3 LE #2 ] DO1
  #7 = #5 * #3
  IF [ [ #5 AND 1 ] EQ 1 ] GOTO 20
  G1 X [ #1 + #6 / 2 ] Y#7
  GOTO 30
N20 G1 X [ - #6 / 2. ] Y#7
N30 #5 = #5 + 1
END1
G0 Z5.
IF [ FUP [ #2 / #3 ] NE 5 ] GOTO 99
G0 X0 Y0
N99 M5
M30
%
