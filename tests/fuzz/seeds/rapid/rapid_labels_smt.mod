MODULE smt
  PROC empty()
    <SMT>
  ENDPROC
  PROC main()
  lbl: MoveL [[150,0,284],[0,1,0,0],[0,0,0,0],[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]],v100,fine,tool0;
  lbl_end:
  ENDPROC
ENDMODULE
