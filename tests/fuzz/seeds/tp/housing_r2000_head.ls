/PROG  HOUSING_R2000
/ATTR
OWNER		= MNEDITOR;
COMMENT		= "roprec sample";
PROG_SIZE	= 0;
FILE_NAME	= ;
VERSION		= 0;
LINE_COUNT	= 1226;
MEMORY_SIZE	= 0;
PROTECT		= READ_WRITE;
TCD:  STACK_SIZE	= 0,
      TASK_PRIORITY	= 50,
      TIME_SLICE	= 0,
      BUSY_LAMP_OFF	= 0,
      ABORT_REQUEST	= 0,
      PAUSE_REQUEST	= 0;
DEFAULT_GROUP	= 1,*,*,*,*;
CONTROL_CODE	= 00000000 00000000;
/MN
   1:  UFRAME_NUM=1 ;
   2:  UTOOL_NUM=1 ;
   3:  !T001 drill D6.8 ;
   4:J P[1] 50% CNT50 ;
   5:L P[2] 250mm/sec CNT10 ;
   6:L P[3] 20mm/sec FINE ;
   7:  WAIT   .30(sec) ;
   8:L P[1] 250mm/sec CNT50 ;
   9:  !T002 drill D6.8 ;
  10:J P[4] 50% CNT50 ;
  11:L P[5] 250mm/sec CNT10 ;
  12:L P[6] 20mm/sec FINE ;
  13:  WAIT   .30(sec) ;
/POS
P[1]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =   150.000  mm,	Y =     0.000  mm,	Z =   300.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[2]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =   150.000  mm,	Y =     0.000  mm,	Z =   252.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[3]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =   150.000  mm,	Y =     0.000  mm,	Z =   234.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[4]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   144.889  mm,	Y =    38.823  mm,	Z =   300.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[5]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   144.889  mm,	Y =    38.823  mm,	Z =   252.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[6]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   144.889  mm,	Y =    38.823  mm,	Z =   234.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[7]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   129.904  mm,	Y =    75.000  mm,	Z =   300.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[8]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   129.904  mm,	Y =    75.000  mm,	Z =   252.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[9]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   129.904  mm,	Y =    75.000  mm,	Z =   234.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[10]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   106.066  mm,	Y =   106.066  mm,	Z =   300.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
/END
