MODULE mDrill(SYSMODULE)
	! Hand-written drilling module, RW 5.15 number style  
	TASK PERS tooldata tSpindle:=[TRUE,[[0.5,-1.2,312.25],[0.707107,0,0.707107,0]],[25.8,[0,0,120],[1,0,0,0],0,0,0]];
	TASK PERS wobjdata wPanel:=[FALSE,TRUE,"",[[1400,0,400],[1,0,0,0]],[[0,0,0],[1,0,0,0]]];
	PERS wobjdata wUnknown;
	CONST robtarget pH1:=[[0,15.48,319],[0.000595015,-1,-9.43398E-06,-0.00058483],[-1,1,-1,0],[1000.01,9E+09,9E+09,9E+09,9E+09,9E+09]];
	LOCAL CONST robtarget pH2:=[[40,15.48,319],[0,1,0,0],[0,0,-2,0],[1000.01,9E+09,9E+09,9E+09,9E+09,9E+09]];
	VAR robtarget pTmp;
	CONST jointtarget jHome:=[[0,0,0,0,30,0],[9E9,9E9,9E9,9E9,9E9,9E9]];
	CONST speeddata vDrill:=[3,500,5000,1000];
	VAR num nCount:=0;

	PROC main()
		ConfL\Off;
		SingArea\Wrist;
		MoveAbsJ jHome,v1000,z50,tSpindle\WObj:=wPanel;
		! hole 1: approach, plunge, retract
		MoveJ RelTool(pH1,0,0,-50),v1000,z10,tSpindle\WObj:=wPanel;
		MoveL RelTool(pH1,0,0,-5),v200,z0,tSpindle\WObj:=wPanel;
		SpindleOn 12000;
		MoveL pH1,vDrill,fine,tSpindle\WObj:=wPanel;
		MoveL RelTool(pH1,0,0,12),vDrill,fine,tSpindle\WObj:=wPanel;
		WaitTime 0.5;
		MoveL RelTool(pH1,0,0,-50),v1000,z10,tSpindle\WObj:=wPanel;
		MoveL Offs(pH2,0,0,50),v500,z10,tSpindle\WObj:=wPanel;
		MoveL [[40,15.48,300],[0,1,0,0],[0,0,-2,0],[9E9,9E9,9E9,9E9,9E9,9E9]],v100,fine,tSpindle,\WObj:=wPanel;
		MoveC [[50,20,300],[0,1,0,0],[0,0,-2,0],[9E9,9E9,9E9,9E9,9E9,9E9]],
		      [[60,15.48,300],[0,1,0,0],[0,0,-2,0],[9E9,9E9,9E9,9E9,9E9,9E9]],v100,z1,tSpindle\WObj:=wPanel;
		MoveL pTmp,v100,fine,tool0;
		MyVendorInstr \Foo:=1, "text; with semicolon";
		nCount := nCount + 1;
	ENDPROC
ENDMODULE
