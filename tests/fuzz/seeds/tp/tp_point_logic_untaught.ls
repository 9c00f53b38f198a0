/PROG  LOGIC
/ATTR
DEFAULT_GROUP	= 1,*,*,*,*;
/MN
   1:J P[1] 50% CNT100 TB    .50sec,CALL SPINDLE_ON ;
      1:  DO[3]=ON ;
       ------ ;
   2:L P[102:it's 2] 20mm/sec FINE DB   10.0mm,CALL DRILL_START ;
       ------ ;
   3:L P[3] 250mm/sec FINE ;
   4:J P[4] 10% FINE ;
/POS
P[1]{
   GP1:
	UF : 0, UT : 1,		CONFIG : 'N U T, 0, 0, 0',
	X =   150.000  mm,	Y =     0.000  mm,	Z =   284.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[102:it's 2]{
   GP1:
	UF : 0, UT : 1,		CONFIG : 'N U T, 0, 0, 0',
	X =   150.000  mm,	Y =     0.000  mm,	Z =   234.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[3]{
   GP1:
	UF : F, UT : F,		CONFIG : '',
	X = ********  mm,	Y = ********  mm,	Z = ********  mm,
	W = ******** deg,	P = ******** deg,	R = ******** deg
};
P[4]{
   GP1:
	UF : 0, UT : 1,		CONFIG : 'L, 0, 0, 0',
	X =   150.000  mm,	Y =     0.000  mm,	Z =   84.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
/END
