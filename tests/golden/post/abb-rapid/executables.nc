MODULE EXECUTABLES
  ! PROJECT #1 EXECUTABLES
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
    TPWrite "Clamp the blank";
    ! TOOL END MILL 10
    ! TOOL CHANGE T901 - fit the tool, then start
    Stop;
    tSpindle.tframe.trans := [0,0,220];
    ! WORKPLAN #42 NESTED
    ! WS #10 CUT
    vFeed.v_tcp := 20; ! 1200 mm/min
    SetAO aoSpindleSpeed, 3000;
    SetDO doSpindleCCW, 0;
    SetDO doSpindleCW, 1;
    SetDO doFlood, 1;
    MoveJ [[0,0,50],[0,1,0,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]], vRapid, z1, tSpindle\WObj:=wobjPart;
    MoveL [[0,0,1],[0,1,0,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]], vRapid, z1, tSpindle\WObj:=wobjPart;
    MoveL [[10,0,1],[0,1,0,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]], vFeed, z1, tSpindle\WObj:=wobjPart;
    ! WS #43 UP AND OVER
    MoveL [[10,0,20],[0,1,0,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]], vRapid, z1, tSpindle\WObj:=wobjPart;
    ! OPTIONAL STOP  no optional stop in RAPID
    ! SET_MARK MARK 1
    ! WAIT_FOR_MARK WAIT 1
    TPWrite "EXCHANGE_PALLET";
    Stop;
    TPWrite "INDEX_TABLE 2";
    Stop;
    Stop;
    ! TOOL CHANGE T0 - unload the tool
    MoveL [[10,0,50],[0,1,0,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]], vRapid, z1, tSpindle\WObj:=wobjPart;
    SetDO doSpindleCW, 0;
    SetDO doSpindleCCW, 0;
    SetDO doFlood, 0;
    SetDO doMist, 0;
    ! PROGRAM END
  ENDPROC
ENDMODULE
