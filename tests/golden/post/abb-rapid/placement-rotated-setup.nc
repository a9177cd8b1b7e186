MODULE PLACEMENT_ROTATED_SETUP
  ! PROJECT #1 PLACEMENT-ROTATED-SETUP
  ! ncpost profile abb-rapid
  PERS tooldata tSpindle := [TRUE,[[0,0,150],[1,0,0,0]],[5,[0,0,75],[1,0,0,0],0,0,0]];
  TASK PERS wobjdata wobjPart := [FALSE,TRUE,"",[[0,0,0],[1,0,0,0]],[[0,0,0],[1,0,0,0]]];
  VAR speeddata vRapid := [500,500,5000,1000];
  VAR speeddata vFeed := [10,500,5000,1000];
  PROC main()
    ConfJ \Off;
    ConfL \Off;
    ! WORKPLAN #2 MAIN
    ! SETUP #8 SETUP
    ! WS #10 FACE
    ! TOOL END MILL 10
    ! TOOL CHANGE T901 - fit the tool, then start
    Stop;
    tSpindle.tframe.trans := [0,0,220];
    vFeed.v_tcp := 20; ! 1200 mm/min
    SetAO aoSpindleSpeed, 3000;
    SetDO doSpindleCCW, 0;
    SetDO doSpindleCW, 1;
    SetDO doFlood, 1;
    MoveJ [[0,15,35.3],[0,1,0,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]], vRapid, z1, tSpindle\WObj:=wobjPart;
    MoveL [[0,15,-4.7],[0,1,0,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]], vRapid, z1, tSpindle\WObj:=wobjPart;
    MoveL [[0,15,-15.7],[0,1,0,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]], vFeed, z1, tSpindle\WObj:=wobjPart;
    MoveL [[-20,15,-15.7],[0,1,0,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]], vFeed, z1, tSpindle\WObj:=wobjPart;
    MoveL [[-20,15,35.3],[0,1,0,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]], vRapid, z1, tSpindle\WObj:=wobjPart;
    SetDO doSpindleCW, 0;
    SetDO doSpindleCCW, 0;
    SetDO doFlood, 0;
    SetDO doMist, 0;
    ! PROGRAM END
  ENDPROC
ENDMODULE
