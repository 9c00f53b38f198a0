/PROG  BOHR_01	  Macro
/ATTR
OWNER		= MNEDITOR;
COMMENT		= "Bohren Platte";
PROG_SIZE	= 2103;
CREATE		= DATE 24-07-15  TIME 10:11:12;
MODIFIED	= DATE 24-07-15  TIME 10:11:12;
FILE_NAME	= ;
VERSION		= 0;
LINE_COUNT	= 14;
MEMORY_SIZE	= 2471;
PROTECT		= READ_WRITE;
TCD:  STACK_SIZE	= 0,
      TASK_PRIORITY	= 50,
      TIME_SLICE	= 0,
      BUSY_LAMP_OFF	= 0,
      ABORT_REQUEST	= 0,
      PAUSE_REQUEST	= 0;
DEFAULT_GROUP	= 1,*,*,*,*;
CONTROL_CODE	= 00000000 00000000;
/APPL

  AUTO_SINGULARITY_HEADER;
    ENABLE_SINGULARITY_AVOIDANCE   : TRUE;
/MN
   1:  !Bohrzyklus für Platte ° ;
   2:  UFRAME_NUM=9 ;
   3:  UTOOL_NUM=1 ;
   4:J P[1:"anfahrt"] 100% CNT50 ACC80    ;
   5:L P[2] 500mm/sec CNT10    ;
   6:L P[3] 40mm/sec FINE    ;
   7:  WAIT    .25(sec) ;
   8:L P[2] 500mm/sec FINE    ;
   9:J PR[73:DRILL CALIB] 10% FINE Tool_Offset,PR[72:SURF-drill off]    ;
  10:  CALL DRILL_20_3    ;
  11:C P[4]    
    :  P[5] 200mm/sec FINE    ;
  12:  //L P[3] 40mm/sec FINE    ;
  13:  WKZ_NUM=1 ;
  14:L P[6] 1200cm/min CNT100    ;
/POS
P[1:"anfahrt"]{
   GP1:
	UF : 9, UT : 1,		CONFIG : 'N U T, 0, 0, 0',
	X =  9300.620  mm,	Y =  1562.720  mm,	Z =  3712.120  mm,
	W =   175.724 deg,	P =   -45.994 deg,	R =  -170.781 deg,
	E1=  1545.000  mm
};
P[2]{
   GP1:
	UF : 9, UT : 1,		CONFIG : 'N U T, 0, 0, 0',
	X =  1000.000  mm,	Y =   200.000  mm,	Z =    50.000  mm,
	W =  -180.000 deg,	P =      .000 deg,	R =      .044 deg,
	E1=  1545.000  mm
};
P[3]{
   GP1:
	UF : 9, UT : 1,		CONFIG : 'N U T, 0, 0, 0',
	X =  1000.000  mm,	Y =   200.000  mm,	Z =    -8.500  mm,
	W =  -180.000 deg,	P =      .000 deg,	R =      .044 deg,
	E1=  1545.000  mm
};
P[4]{
   GP1:
	UF : 9, UT : 1,
	J1=    25.000 deg,	J2=   -12.500 deg,	J3=    -.242 deg,
	J4=      .000 deg,	J5=   -51.975 deg,	J6=   180.000 deg,
	E1=  1545.000  mm
};
P[5]{
   GP1:
	UF : 9, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  1100.000  mm,	Y =   250.000  mm,	Z =    50.000  mm,
	W =  -180.000 deg,	P =      .000 deg,	R =    90.000 deg,
	E1=  1545.000  mm
};
P[6]{
   GP1:
	UF : 9, UT : 1,		CONFIG : 'N D B, 0, -1, 0',
	X =  -700.000  mm,	Y =   250.000  mm,	Z =   150.000  mm,
	W =   180.000 deg,	P =   -89.999 deg,	R =     0.000 deg,
	E1=  1545.000  mm
};
/END
