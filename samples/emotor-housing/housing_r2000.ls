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
  14:L P[4] 250mm/sec CNT50 ;
  15:  !T003 drill D6.8 ;
  16:J P[7] 50% CNT50 ;
  17:L P[8] 250mm/sec CNT10 ;
  18:L P[9] 20mm/sec FINE ;
  19:  WAIT   .30(sec) ;
  20:L P[7] 250mm/sec CNT50 ;
  21:  !T004 drill D6.8 ;
  22:J P[10] 50% CNT50 ;
  23:L P[11] 250mm/sec CNT10 ;
  24:L P[12] 20mm/sec FINE ;
  25:  WAIT   .30(sec) ;
  26:L P[10] 250mm/sec CNT50 ;
  27:  !T005 drill D6.8 ;
  28:J P[13] 50% CNT50 ;
  29:L P[14] 250mm/sec CNT10 ;
  30:L P[15] 20mm/sec FINE ;
  31:  WAIT   .30(sec) ;
  32:L P[13] 250mm/sec CNT50 ;
  33:  !T006 drill D6.8 ;
  34:J P[16] 50% CNT50 ;
  35:L P[17] 250mm/sec CNT10 ;
  36:L P[18] 20mm/sec FINE ;
  37:  WAIT   .30(sec) ;
  38:L P[16] 250mm/sec CNT50 ;
  39:  !T007 drill D6.8 ;
  40:J P[19] 50% CNT50 ;
  41:L P[20] 250mm/sec CNT10 ;
  42:L P[21] 20mm/sec FINE ;
  43:  WAIT   .30(sec) ;
  44:L P[19] 250mm/sec CNT50 ;
  45:  !T008 drill D6.8 ;
  46:J P[22] 50% CNT50 ;
  47:L P[23] 250mm/sec CNT10 ;
  48:L P[24] 20mm/sec FINE ;
  49:  WAIT   .30(sec) ;
  50:L P[22] 250mm/sec CNT50 ;
  51:  !T009 drill D6.8 ;
  52:J P[25] 50% CNT50 ;
  53:L P[26] 250mm/sec CNT10 ;
  54:L P[27] 20mm/sec FINE ;
  55:  WAIT   .30(sec) ;
  56:L P[25] 250mm/sec CNT50 ;
  57:  !T010 drill D6.8 ;
  58:J P[28] 50% CNT50 ;
  59:L P[29] 250mm/sec CNT10 ;
  60:L P[30] 20mm/sec FINE ;
  61:  WAIT   .30(sec) ;
  62:L P[28] 250mm/sec CNT50 ;
  63:  !T011 drill D6.8 ;
  64:J P[31] 50% CNT50 ;
  65:L P[32] 250mm/sec CNT10 ;
  66:L P[33] 20mm/sec FINE ;
  67:  WAIT   .30(sec) ;
  68:L P[31] 250mm/sec CNT50 ;
  69:  !T012 drill D6.8 ;
  70:J P[34] 50% CNT50 ;
  71:L P[35] 250mm/sec CNT10 ;
  72:L P[36] 20mm/sec FINE ;
  73:  WAIT   .30(sec) ;
  74:L P[34] 250mm/sec CNT50 ;
  75:  !T013 drill D6.8 ;
  76:J P[37] 50% CNT50 ;
  77:L P[38] 250mm/sec CNT10 ;
  78:L P[39] 20mm/sec FINE ;
  79:  WAIT   .30(sec) ;
  80:L P[37] 250mm/sec CNT50 ;
  81:  !T014 drill D6.8 ;
  82:J P[40] 50% CNT50 ;
  83:L P[41] 250mm/sec CNT10 ;
  84:L P[42] 20mm/sec FINE ;
  85:  WAIT   .30(sec) ;
  86:L P[40] 250mm/sec CNT50 ;
  87:  !T015 drill D6.8 ;
  88:J P[43] 50% CNT50 ;
  89:L P[44] 250mm/sec CNT10 ;
  90:L P[45] 20mm/sec FINE ;
  91:  WAIT   .30(sec) ;
  92:L P[43] 250mm/sec CNT50 ;
  93:  !T016 drill D6.8 ;
  94:J P[46] 50% CNT50 ;
  95:L P[47] 250mm/sec CNT10 ;
  96:L P[48] 20mm/sec FINE ;
  97:  WAIT   .30(sec) ;
  98:L P[46] 250mm/sec CNT50 ;
  99:  !T017 drill D6.8 ;
 100:J P[49] 50% CNT50 ;
 101:L P[50] 250mm/sec CNT10 ;
 102:L P[51] 20mm/sec FINE ;
 103:  WAIT   .30(sec) ;
 104:L P[49] 250mm/sec CNT50 ;
 105:  !T018 drill D6.8 ;
 106:J P[52] 50% CNT50 ;
 107:L P[53] 250mm/sec CNT10 ;
 108:L P[54] 20mm/sec FINE ;
 109:  WAIT   .30(sec) ;
 110:L P[52] 250mm/sec CNT50 ;
 111:  !T019 drill D6.8 ;
 112:J P[55] 50% CNT50 ;
 113:L P[56] 250mm/sec CNT10 ;
 114:L P[57] 20mm/sec FINE ;
 115:  WAIT   .30(sec) ;
 116:L P[55] 250mm/sec CNT50 ;
 117:  !T020 drill D6.8 ;
 118:J P[58] 50% CNT50 ;
 119:L P[59] 250mm/sec CNT10 ;
 120:L P[60] 20mm/sec FINE ;
 121:  WAIT   .30(sec) ;
 122:L P[58] 250mm/sec CNT50 ;
 123:  !T021 drill D6.8 ;
 124:J P[61] 50% CNT50 ;
 125:L P[62] 250mm/sec CNT10 ;
 126:L P[63] 20mm/sec FINE ;
 127:  WAIT   .30(sec) ;
 128:L P[61] 250mm/sec CNT50 ;
 129:  !T022 drill D6.8 ;
 130:J P[64] 50% CNT50 ;
 131:L P[65] 250mm/sec CNT10 ;
 132:L P[66] 20mm/sec FINE ;
 133:  WAIT   .30(sec) ;
 134:L P[64] 250mm/sec CNT50 ;
 135:  !T023 drill D6.8 ;
 136:J P[67] 50% CNT50 ;
 137:L P[68] 250mm/sec CNT10 ;
 138:L P[69] 20mm/sec FINE ;
 139:  WAIT   .30(sec) ;
 140:L P[67] 250mm/sec CNT50 ;
 141:  !T024 drill D6.8 ;
 142:J P[70] 50% CNT50 ;
 143:L P[71] 250mm/sec CNT10 ;
 144:L P[72] 20mm/sec FINE ;
 145:  WAIT   .30(sec) ;
 146:L P[70] 250mm/sec CNT50 ;
 147:  !T025 drill D10.2 ;
 148:J P[73] 50% CNT50 ;
 149:L P[74] 250mm/sec CNT10 ;
 150:L P[75] 20mm/sec FINE ;
 151:  WAIT   .30(sec) ;
 152:L P[73] 250mm/sec CNT50 ;
 153:  !T026 drill D10.2 ;
 154:J P[76] 50% CNT50 ;
 155:L P[77] 250mm/sec CNT10 ;
 156:L P[78] 20mm/sec FINE ;
 157:  WAIT   .30(sec) ;
 158:L P[76] 250mm/sec CNT50 ;
 159:  !T027 drill D10.2 ;
 160:J P[79] 50% CNT50 ;
 161:L P[80] 250mm/sec CNT10 ;
 162:L P[81] 20mm/sec FINE ;
 163:  WAIT   .30(sec) ;
 164:L P[79] 250mm/sec CNT50 ;
 165:  !T028 drill D10.2 ;
 166:J P[82] 50% CNT50 ;
 167:L P[83] 250mm/sec CNT10 ;
 168:L P[84] 20mm/sec FINE ;
 169:  WAIT   .30(sec) ;
 170:L P[82] 250mm/sec CNT50 ;
 171:  !T029 drill D10.2 ;
 172:J P[85] 50% CNT50 ;
 173:L P[86] 250mm/sec CNT10 ;
 174:L P[87] 20mm/sec FINE ;
 175:  WAIT   .30(sec) ;
 176:L P[85] 250mm/sec CNT50 ;
 177:  !T030 drill D10.2 ;
 178:J P[88] 50% CNT50 ;
 179:L P[89] 250mm/sec CNT10 ;
 180:L P[90] 20mm/sec FINE ;
 181:  WAIT   .30(sec) ;
 182:L P[88] 250mm/sec CNT50 ;
 183:  !T031 drill D10.2 ;
 184:J P[91] 50% CNT50 ;
 185:L P[92] 250mm/sec CNT10 ;
 186:L P[93] 20mm/sec FINE ;
 187:  WAIT   .30(sec) ;
 188:L P[91] 250mm/sec CNT50 ;
 189:  !T032 drill D10.2 ;
 190:J P[94] 50% CNT50 ;
 191:L P[95] 250mm/sec CNT10 ;
 192:L P[96] 20mm/sec FINE ;
 193:  WAIT   .30(sec) ;
 194:L P[94] 250mm/sec CNT50 ;
 195:  !T033 drill D10.2 ;
 196:J P[97] 50% CNT50 ;
 197:L P[98] 250mm/sec CNT10 ;
 198:L P[99] 20mm/sec FINE ;
 199:  WAIT   .30(sec) ;
 200:L P[97] 250mm/sec CNT50 ;
 201:  !T034 drill D10.2 ;
 202:J P[100] 50% CNT50 ;
 203:L P[101] 250mm/sec CNT10 ;
 204:L P[102] 20mm/sec FINE ;
 205:  WAIT   .30(sec) ;
 206:L P[100] 250mm/sec CNT50 ;
 207:  !T035 drill D10.2 ;
 208:J P[103] 50% CNT50 ;
 209:L P[104] 250mm/sec CNT10 ;
 210:L P[105] 20mm/sec FINE ;
 211:  WAIT   .30(sec) ;
 212:L P[103] 250mm/sec CNT50 ;
 213:  !T036 drill D10.2 ;
 214:J P[106] 50% CNT50 ;
 215:L P[107] 250mm/sec CNT10 ;
 216:L P[108] 20mm/sec FINE ;
 217:  WAIT   .30(sec) ;
 218:L P[106] 250mm/sec CNT50 ;
 219:  !T037 drill D8.5 ;
 220:J P[109] 50% CNT50 ;
 221:L P[110] 250mm/sec CNT10 ;
 222:L P[111] 20mm/sec FINE ;
 223:  WAIT   .30(sec) ;
 224:L P[109] 250mm/sec CNT50 ;
 225:  !T038 drill D8.5 ;
 226:J P[112] 50% CNT50 ;
 227:L P[113] 250mm/sec CNT10 ;
 228:L P[114] 20mm/sec FINE ;
 229:  WAIT   .30(sec) ;
 230:L P[112] 250mm/sec CNT50 ;
 231:  !T039 drill D8.5 ;
 232:J P[115] 50% CNT50 ;
 233:L P[116] 250mm/sec CNT10 ;
 234:L P[117] 20mm/sec FINE ;
 235:  WAIT   .30(sec) ;
 236:L P[115] 250mm/sec CNT50 ;
 237:  !T040 drill D8.5 ;
 238:J P[118] 50% CNT50 ;
 239:L P[119] 250mm/sec CNT10 ;
 240:L P[120] 20mm/sec FINE ;
 241:  WAIT   .30(sec) ;
 242:L P[118] 250mm/sec CNT50 ;
 243:  !T041 drill D8.5 ;
 244:J P[121] 50% CNT50 ;
 245:L P[122] 250mm/sec CNT10 ;
 246:L P[123] 20mm/sec FINE ;
 247:  WAIT   .30(sec) ;
 248:L P[121] 250mm/sec CNT50 ;
 249:  !T042 drill D8.5 ;
 250:J P[124] 50% CNT50 ;
 251:L P[125] 250mm/sec CNT10 ;
 252:L P[126] 20mm/sec FINE ;
 253:  WAIT   .30(sec) ;
 254:L P[124] 250mm/sec CNT50 ;
 255:  !T043 drill D8.5 ;
 256:J P[127] 50% CNT50 ;
 257:L P[128] 250mm/sec CNT10 ;
 258:L P[129] 20mm/sec FINE ;
 259:  WAIT   .30(sec) ;
 260:L P[127] 250mm/sec CNT50 ;
 261:  !T044 drill D8.5 ;
 262:J P[130] 50% CNT50 ;
 263:L P[131] 250mm/sec CNT10 ;
 264:L P[132] 20mm/sec FINE ;
 265:  WAIT   .30(sec) ;
 266:L P[130] 250mm/sec CNT50 ;
 267:  !T045 drill D8.5 ;
 268:J P[133] 50% CNT50 ;
 269:L P[134] 250mm/sec CNT10 ;
 270:L P[135] 20mm/sec FINE ;
 271:  WAIT   .30(sec) ;
 272:L P[133] 250mm/sec CNT50 ;
 273:  !T046 drill D8.5 ;
 274:J P[136] 50% CNT50 ;
 275:L P[137] 250mm/sec CNT10 ;
 276:L P[138] 20mm/sec FINE ;
 277:  WAIT   .30(sec) ;
 278:L P[136] 250mm/sec CNT50 ;
 279:  !T047 drill D8.5 ;
 280:J P[139] 50% CNT50 ;
 281:L P[140] 250mm/sec CNT10 ;
 282:L P[141] 20mm/sec FINE ;
 283:  WAIT   .30(sec) ;
 284:L P[139] 250mm/sec CNT50 ;
 285:  !T048 drill D8.5 ;
 286:J P[142] 50% CNT50 ;
 287:L P[143] 250mm/sec CNT10 ;
 288:L P[144] 20mm/sec FINE ;
 289:  WAIT   .30(sec) ;
 290:L P[142] 250mm/sec CNT50 ;
 291:  !T049 drill D6.8 ;
 292:J P[145] 50% CNT50 ;
 293:L P[146] 250mm/sec CNT10 ;
 294:L P[147] 20mm/sec FINE ;
 295:  WAIT   .30(sec) ;
 296:L P[145] 250mm/sec CNT50 ;
 297:  !T050 drill D6.8 ;
 298:J P[148] 50% CNT50 ;
 299:L P[149] 250mm/sec CNT10 ;
 300:L P[150] 20mm/sec FINE ;
 301:  WAIT   .30(sec) ;
 302:L P[148] 250mm/sec CNT50 ;
 303:  !T051 drill D6.8 ;
 304:J P[151] 50% CNT50 ;
 305:L P[152] 250mm/sec CNT10 ;
 306:L P[153] 20mm/sec FINE ;
 307:  WAIT   .30(sec) ;
 308:L P[151] 250mm/sec CNT50 ;
 309:  !T052 drill D6.8 ;
 310:J P[154] 50% CNT50 ;
 311:L P[155] 250mm/sec CNT10 ;
 312:L P[156] 20mm/sec FINE ;
 313:  WAIT   .30(sec) ;
 314:L P[154] 250mm/sec CNT50 ;
 315:  !T053 drill D6.8 ;
 316:J P[157] 50% CNT50 ;
 317:L P[158] 250mm/sec CNT10 ;
 318:L P[159] 20mm/sec FINE ;
 319:  WAIT   .30(sec) ;
 320:L P[157] 250mm/sec CNT50 ;
 321:  !T054 drill D6.8 ;
 322:J P[160] 50% CNT50 ;
 323:L P[161] 250mm/sec CNT10 ;
 324:L P[162] 20mm/sec FINE ;
 325:  WAIT   .30(sec) ;
 326:L P[160] 250mm/sec CNT50 ;
 327:  !T055 drill D6.8 ;
 328:J P[163] 50% CNT50 ;
 329:L P[164] 250mm/sec CNT10 ;
 330:L P[165] 20mm/sec FINE ;
 331:  WAIT   .30(sec) ;
 332:L P[163] 250mm/sec CNT50 ;
 333:  !T056 drill D6.8 ;
 334:J P[166] 50% CNT50 ;
 335:L P[167] 250mm/sec CNT10 ;
 336:L P[168] 20mm/sec FINE ;
 337:  WAIT   .30(sec) ;
 338:L P[166] 250mm/sec CNT50 ;
 339:  !T057 drill D6.8 ;
 340:J P[169] 50% CNT50 ;
 341:L P[170] 250mm/sec CNT10 ;
 342:L P[171] 20mm/sec FINE ;
 343:  WAIT   .30(sec) ;
 344:L P[169] 250mm/sec CNT50 ;
 345:  !T058 drill D6.8 ;
 346:J P[172] 50% CNT50 ;
 347:L P[173] 250mm/sec CNT10 ;
 348:L P[174] 20mm/sec FINE ;
 349:  WAIT   .30(sec) ;
 350:L P[172] 250mm/sec CNT50 ;
 351:  !T059 drill D6.8 ;
 352:J P[175] 50% CNT50 ;
 353:L P[176] 250mm/sec CNT10 ;
 354:L P[177] 20mm/sec FINE ;
 355:  WAIT   .30(sec) ;
 356:L P[175] 250mm/sec CNT50 ;
 357:  !T060 drill D6.8 ;
 358:J P[178] 50% CNT50 ;
 359:L P[179] 250mm/sec CNT10 ;
 360:L P[180] 20mm/sec FINE ;
 361:  WAIT   .30(sec) ;
 362:L P[178] 250mm/sec CNT50 ;
 363:  !F001 drill D12.0 ;
 364:J P[181] 50% CNT50 ;
 365:L P[182] 250mm/sec CNT10 ;
 366:L P[183] 20mm/sec FINE ;
 367:  WAIT   .30(sec) ;
 368:L P[181] 250mm/sec CNT50 ;
 369:  !F002 drill D8.5 ;
 370:J P[184] 50% CNT50 ;
 371:L P[185] 250mm/sec CNT10 ;
 372:L P[186] 20mm/sec FINE ;
 373:  WAIT   .30(sec) ;
 374:L P[184] 250mm/sec CNT50 ;
 375:  !F003 drill D8.5 ;
 376:J P[187] 50% CNT50 ;
 377:L P[188] 250mm/sec CNT10 ;
 378:L P[189] 20mm/sec FINE ;
 379:  WAIT   .30(sec) ;
 380:L P[187] 250mm/sec CNT50 ;
 381:  !F004 drill D8.5 ;
 382:J P[190] 50% CNT50 ;
 383:L P[191] 250mm/sec CNT10 ;
 384:L P[192] 20mm/sec FINE ;
 385:  WAIT   .30(sec) ;
 386:L P[190] 250mm/sec CNT50 ;
 387:  !F005 drill D8.5 ;
 388:J P[193] 50% CNT50 ;
 389:L P[194] 250mm/sec CNT10 ;
 390:L P[195] 20mm/sec FINE ;
 391:  WAIT   .30(sec) ;
 392:L P[193] 250mm/sec CNT50 ;
 393:  !F006 drill D8.5 ;
 394:J P[196] 50% CNT50 ;
 395:L P[197] 250mm/sec CNT10 ;
 396:L P[198] 20mm/sec FINE ;
 397:  WAIT   .30(sec) ;
 398:L P[196] 250mm/sec CNT50 ;
 399:  !F007 drill D8.5 ;
 400:J P[199] 50% CNT50 ;
 401:L P[200] 250mm/sec CNT10 ;
 402:L P[201] 20mm/sec FINE ;
 403:  WAIT   .30(sec) ;
 404:L P[199] 250mm/sec CNT50 ;
 405:  !F008 drill D12.0 ;
 406:J P[202] 50% CNT50 ;
 407:L P[203] 250mm/sec CNT10 ;
 408:L P[204] 20mm/sec FINE ;
 409:  WAIT   .30(sec) ;
 410:L P[202] 250mm/sec CNT50 ;
 411:  !F009 drill D8.5 ;
 412:J P[205] 50% CNT50 ;
 413:L P[206] 250mm/sec CNT10 ;
 414:L P[207] 20mm/sec FINE ;
 415:  WAIT   .30(sec) ;
 416:L P[205] 250mm/sec CNT50 ;
 417:  !F010 drill D8.5 ;
 418:J P[208] 50% CNT50 ;
 419:L P[209] 250mm/sec CNT10 ;
 420:L P[210] 20mm/sec FINE ;
 421:  WAIT   .30(sec) ;
 422:L P[208] 250mm/sec CNT50 ;
 423:  !F011 drill D8.5 ;
 424:J P[211] 50% CNT50 ;
 425:L P[212] 250mm/sec CNT10 ;
 426:L P[213] 20mm/sec FINE ;
 427:  WAIT   .30(sec) ;
 428:L P[211] 250mm/sec CNT50 ;
 429:  !F012 drill D8.5 ;
 430:J P[214] 50% CNT50 ;
 431:L P[215] 250mm/sec CNT10 ;
 432:L P[216] 20mm/sec FINE ;
 433:  WAIT   .30(sec) ;
 434:L P[214] 250mm/sec CNT50 ;
 435:  !F013 drill D8.5 ;
 436:J P[217] 50% CNT50 ;
 437:L P[218] 250mm/sec CNT10 ;
 438:L P[219] 20mm/sec FINE ;
 439:  WAIT   .30(sec) ;
 440:L P[217] 250mm/sec CNT50 ;
 441:  !F014 drill D8.5 ;
 442:J P[220] 50% CNT50 ;
 443:L P[221] 250mm/sec CNT10 ;
 444:L P[222] 20mm/sec FINE ;
 445:  WAIT   .30(sec) ;
 446:L P[220] 250mm/sec CNT50 ;
 447:  !F015 drill D8.5 ;
 448:J P[223] 50% CNT50 ;
 449:L P[224] 250mm/sec CNT10 ;
 450:L P[225] 20mm/sec FINE ;
 451:  WAIT   .30(sec) ;
 452:L P[223] 250mm/sec CNT50 ;
 453:  !F016 drill D8.5 ;
 454:J P[226] 50% CNT50 ;
 455:L P[227] 250mm/sec CNT10 ;
 456:L P[228] 20mm/sec FINE ;
 457:  WAIT   .30(sec) ;
 458:L P[226] 250mm/sec CNT50 ;
 459:  !F017 drill D8.5 ;
 460:J P[229] 50% CNT50 ;
 461:L P[230] 250mm/sec CNT10 ;
 462:L P[231] 20mm/sec FINE ;
 463:  WAIT   .30(sec) ;
 464:L P[229] 250mm/sec CNT50 ;
 465:  !F018 drill D8.5 ;
 466:J P[232] 50% CNT50 ;
 467:L P[233] 250mm/sec CNT10 ;
 468:L P[234] 20mm/sec FINE ;
 469:  WAIT   .30(sec) ;
 470:L P[232] 250mm/sec CNT50 ;
 471:  !F019 drill D8.5 ;
 472:J P[235] 50% CNT50 ;
 473:L P[236] 250mm/sec CNT10 ;
 474:L P[237] 20mm/sec FINE ;
 475:  WAIT   .30(sec) ;
 476:L P[235] 250mm/sec CNT50 ;
 477:  !F020 drill D8.5 ;
 478:J P[238] 50% CNT50 ;
 479:L P[239] 250mm/sec CNT10 ;
 480:L P[240] 20mm/sec FINE ;
 481:  WAIT   .30(sec) ;
 482:L P[238] 250mm/sec CNT50 ;
 483:  !F021 drill D8.5 ;
 484:J P[241] 50% CNT50 ;
 485:L P[242] 250mm/sec CNT10 ;
 486:L P[243] 20mm/sec FINE ;
 487:  WAIT   .30(sec) ;
 488:L P[241] 250mm/sec CNT50 ;
 489:  !F022 drill D8.5 ;
 490:J P[244] 50% CNT50 ;
 491:L P[245] 250mm/sec CNT10 ;
 492:L P[246] 20mm/sec FINE ;
 493:  WAIT   .30(sec) ;
 494:L P[244] 250mm/sec CNT50 ;
 495:  !F023 drill D8.5 ;
 496:J P[247] 50% CNT50 ;
 497:L P[248] 250mm/sec CNT10 ;
 498:L P[249] 20mm/sec FINE ;
 499:  WAIT   .30(sec) ;
 500:L P[247] 250mm/sec CNT50 ;
 501:  !F024 drill D8.5 ;
 502:J P[250] 50% CNT50 ;
 503:L P[251] 250mm/sec CNT10 ;
 504:L P[252] 20mm/sec FINE ;
 505:  WAIT   .30(sec) ;
 506:L P[250] 250mm/sec CNT50 ;
 507:  !F025 drill D8.5 ;
 508:J P[253] 50% CNT50 ;
 509:L P[254] 250mm/sec CNT10 ;
 510:L P[255] 20mm/sec FINE ;
 511:  WAIT   .30(sec) ;
 512:L P[253] 250mm/sec CNT50 ;
 513:  !F026 drill D8.5 ;
 514:J P[256] 50% CNT50 ;
 515:L P[257] 250mm/sec CNT10 ;
 516:L P[258] 20mm/sec FINE ;
 517:  WAIT   .30(sec) ;
 518:L P[256] 250mm/sec CNT50 ;
 519:  !F027 drill D8.5 ;
 520:J P[259] 50% CNT50 ;
 521:L P[260] 250mm/sec CNT10 ;
 522:L P[261] 20mm/sec FINE ;
 523:  WAIT   .30(sec) ;
 524:L P[259] 250mm/sec CNT50 ;
 525:  !F028 drill D8.5 ;
 526:J P[262] 50% CNT50 ;
 527:L P[263] 250mm/sec CNT10 ;
 528:L P[264] 20mm/sec FINE ;
 529:  WAIT   .30(sec) ;
 530:L P[262] 250mm/sec CNT50 ;
 531:  !F029 drill D8.5 ;
 532:J P[265] 50% CNT50 ;
 533:L P[266] 250mm/sec CNT10 ;
 534:L P[267] 20mm/sec FINE ;
 535:  WAIT   .30(sec) ;
 536:L P[265] 250mm/sec CNT50 ;
 537:  !F030 drill D8.5 ;
 538:J P[268] 50% CNT50 ;
 539:L P[269] 250mm/sec CNT10 ;
 540:L P[270] 20mm/sec FINE ;
 541:  WAIT   .30(sec) ;
 542:L P[268] 250mm/sec CNT50 ;
 543:  !F031 drill D8.5 ;
 544:J P[271] 50% CNT50 ;
 545:L P[272] 250mm/sec CNT10 ;
 546:L P[273] 20mm/sec FINE ;
 547:  WAIT   .30(sec) ;
 548:L P[271] 250mm/sec CNT50 ;
 549:  !F032 drill D8.5 ;
 550:J P[274] 50% CNT50 ;
 551:L P[275] 250mm/sec CNT10 ;
 552:L P[276] 20mm/sec FINE ;
 553:  WAIT   .30(sec) ;
 554:L P[274] 250mm/sec CNT50 ;
 555:  !F033 drill D8.5 ;
 556:J P[277] 50% CNT50 ;
 557:L P[278] 250mm/sec CNT10 ;
 558:L P[279] 20mm/sec FINE ;
 559:  WAIT   .30(sec) ;
 560:L P[277] 250mm/sec CNT50 ;
 561:  !F034 drill D8.5 ;
 562:J P[280] 50% CNT50 ;
 563:L P[281] 250mm/sec CNT10 ;
 564:L P[282] 20mm/sec FINE ;
 565:  WAIT   .30(sec) ;
 566:L P[280] 250mm/sec CNT50 ;
 567:  !F035 drill D8.5 ;
 568:J P[283] 50% CNT50 ;
 569:L P[284] 250mm/sec CNT10 ;
 570:L P[285] 20mm/sec FINE ;
 571:  WAIT   .30(sec) ;
 572:L P[283] 250mm/sec CNT50 ;
 573:  !F036 drill D8.5 ;
 574:J P[286] 50% CNT50 ;
 575:L P[287] 250mm/sec CNT10 ;
 576:L P[288] 20mm/sec FINE ;
 577:  WAIT   .30(sec) ;
 578:L P[286] 250mm/sec CNT50 ;
 579:  !F037 drill D8.5 ;
 580:J P[289] 50% CNT50 ;
 581:L P[290] 250mm/sec CNT10 ;
 582:L P[291] 20mm/sec FINE ;
 583:  WAIT   .30(sec) ;
 584:L P[289] 250mm/sec CNT50 ;
 585:  !F038 drill D8.5 ;
 586:J P[292] 50% CNT50 ;
 587:L P[293] 250mm/sec CNT10 ;
 588:L P[294] 20mm/sec FINE ;
 589:  WAIT   .30(sec) ;
 590:L P[292] 250mm/sec CNT50 ;
 591:  !F039 drill D8.5 ;
 592:J P[295] 50% CNT50 ;
 593:L P[296] 250mm/sec CNT10 ;
 594:L P[297] 20mm/sec FINE ;
 595:  WAIT   .30(sec) ;
 596:L P[295] 250mm/sec CNT50 ;
 597:  !F040 drill D8.5 ;
 598:J P[298] 50% CNT50 ;
 599:L P[299] 250mm/sec CNT10 ;
 600:L P[300] 20mm/sec FINE ;
 601:  WAIT   .30(sec) ;
 602:L P[298] 250mm/sec CNT50 ;
 603:  !F041 drill D12.0 ;
 604:J P[301] 50% CNT50 ;
 605:L P[302] 250mm/sec CNT10 ;
 606:L P[303] 20mm/sec FINE ;
 607:  WAIT   .30(sec) ;
 608:L P[301] 250mm/sec CNT50 ;
 609:  !F042 drill D8.5 ;
 610:J P[304] 50% CNT50 ;
 611:L P[305] 250mm/sec CNT10 ;
 612:L P[306] 20mm/sec FINE ;
 613:  WAIT   .30(sec) ;
 614:L P[304] 250mm/sec CNT50 ;
 615:  !F043 drill D8.5 ;
 616:J P[307] 50% CNT50 ;
 617:L P[308] 250mm/sec CNT10 ;
 618:L P[309] 20mm/sec FINE ;
 619:  WAIT   .30(sec) ;
 620:L P[307] 250mm/sec CNT50 ;
 621:  !F044 drill D8.5 ;
 622:J P[310] 50% CNT50 ;
 623:L P[311] 250mm/sec CNT10 ;
 624:L P[312] 20mm/sec FINE ;
 625:  WAIT   .30(sec) ;
 626:L P[310] 250mm/sec CNT50 ;
 627:  !F045 drill D8.5 ;
 628:J P[313] 50% CNT50 ;
 629:L P[314] 250mm/sec CNT10 ;
 630:L P[315] 20mm/sec FINE ;
 631:  WAIT   .30(sec) ;
 632:L P[313] 250mm/sec CNT50 ;
 633:  !F046 drill D8.5 ;
 634:J P[316] 50% CNT50 ;
 635:L P[317] 250mm/sec CNT10 ;
 636:L P[318] 20mm/sec FINE ;
 637:  WAIT   .30(sec) ;
 638:L P[316] 250mm/sec CNT50 ;
 639:  !F047 drill D8.5 ;
 640:J P[319] 50% CNT50 ;
 641:L P[320] 250mm/sec CNT10 ;
 642:L P[321] 20mm/sec FINE ;
 643:  WAIT   .30(sec) ;
 644:L P[319] 250mm/sec CNT50 ;
 645:  !F048 drill D12.0 ;
 646:J P[322] 50% CNT50 ;
 647:L P[323] 250mm/sec CNT10 ;
 648:L P[324] 20mm/sec FINE ;
 649:  WAIT   .30(sec) ;
 650:L P[322] 250mm/sec CNT50 ;
 651:  !R001 drill D10.2 ;
 652:J P[325] 50% CNT50 ;
 653:L P[326] 250mm/sec CNT10 ;
 654:L P[327] 20mm/sec FINE ;
 655:  WAIT   .30(sec) ;
 656:L P[325] 250mm/sec CNT50 ;
 657:  !R002 drill D10.2 ;
 658:J P[328] 50% CNT50 ;
 659:L P[329] 250mm/sec CNT10 ;
 660:L P[330] 20mm/sec FINE ;
 661:  WAIT   .30(sec) ;
 662:L P[328] 250mm/sec CNT50 ;
 663:  !R003 drill D10.2 ;
 664:J P[331] 50% CNT50 ;
 665:L P[332] 250mm/sec CNT10 ;
 666:L P[333] 20mm/sec FINE ;
 667:  WAIT   .30(sec) ;
 668:L P[331] 250mm/sec CNT50 ;
 669:  !R004 drill D10.2 ;
 670:J P[334] 50% CNT50 ;
 671:L P[335] 250mm/sec CNT10 ;
 672:L P[336] 20mm/sec FINE ;
 673:  WAIT   .30(sec) ;
 674:L P[334] 250mm/sec CNT50 ;
 675:  !R005 drill D10.2 ;
 676:J P[337] 50% CNT50 ;
 677:L P[338] 250mm/sec CNT10 ;
 678:L P[339] 20mm/sec FINE ;
 679:  WAIT   .30(sec) ;
 680:L P[337] 250mm/sec CNT50 ;
 681:  !R006 drill D10.2 ;
 682:J P[340] 50% CNT50 ;
 683:L P[341] 250mm/sec CNT10 ;
 684:L P[342] 20mm/sec FINE ;
 685:  WAIT   .30(sec) ;
 686:L P[340] 250mm/sec CNT50 ;
 687:  !R007 drill D10.2 ;
 688:J P[343] 50% CNT50 ;
 689:L P[344] 250mm/sec CNT10 ;
 690:L P[345] 20mm/sec FINE ;
 691:  WAIT   .30(sec) ;
 692:L P[343] 250mm/sec CNT50 ;
 693:  !R008 drill D10.2 ;
 694:J P[346] 50% CNT50 ;
 695:L P[347] 250mm/sec CNT10 ;
 696:L P[348] 20mm/sec FINE ;
 697:  WAIT   .30(sec) ;
 698:L P[346] 250mm/sec CNT50 ;
 699:  !R009 drill D10.2 ;
 700:J P[349] 50% CNT50 ;
 701:L P[350] 250mm/sec CNT10 ;
 702:L P[351] 20mm/sec FINE ;
 703:  WAIT   .30(sec) ;
 704:L P[349] 250mm/sec CNT50 ;
 705:  !R010 drill D10.2 ;
 706:J P[352] 50% CNT50 ;
 707:L P[353] 250mm/sec CNT10 ;
 708:L P[354] 20mm/sec FINE ;
 709:  WAIT   .30(sec) ;
 710:L P[352] 250mm/sec CNT50 ;
 711:  !R011 drill D10.2 ;
 712:J P[355] 50% CNT50 ;
 713:L P[356] 250mm/sec CNT10 ;
 714:L P[357] 20mm/sec FINE ;
 715:  WAIT   .30(sec) ;
 716:L P[355] 250mm/sec CNT50 ;
 717:  !R012 drill D10.2 ;
 718:J P[358] 50% CNT50 ;
 719:L P[359] 250mm/sec CNT10 ;
 720:L P[360] 20mm/sec FINE ;
 721:  WAIT   .30(sec) ;
 722:L P[358] 250mm/sec CNT50 ;
 723:  !R013 drill D10.2 ;
 724:J P[361] 50% CNT50 ;
 725:L P[362] 250mm/sec CNT10 ;
 726:L P[363] 20mm/sec FINE ;
 727:  WAIT   .30(sec) ;
 728:L P[361] 250mm/sec CNT50 ;
 729:  !R014 drill D10.2 ;
 730:J P[364] 50% CNT50 ;
 731:L P[365] 250mm/sec CNT10 ;
 732:L P[366] 20mm/sec FINE ;
 733:  WAIT   .30(sec) ;
 734:L P[364] 250mm/sec CNT50 ;
 735:  !R015 drill D10.2 ;
 736:J P[367] 50% CNT50 ;
 737:L P[368] 250mm/sec CNT10 ;
 738:L P[369] 20mm/sec FINE ;
 739:  WAIT   .30(sec) ;
 740:L P[367] 250mm/sec CNT50 ;
 741:  !R016 drill D10.2 ;
 742:J P[370] 50% CNT50 ;
 743:L P[371] 250mm/sec CNT10 ;
 744:L P[372] 20mm/sec FINE ;
 745:  WAIT   .30(sec) ;
 746:L P[370] 250mm/sec CNT50 ;
 747:  !R017 drill D10.2 ;
 748:J P[373] 50% CNT50 ;
 749:L P[374] 250mm/sec CNT10 ;
 750:L P[375] 20mm/sec FINE ;
 751:  WAIT   .30(sec) ;
 752:L P[373] 250mm/sec CNT50 ;
 753:  !R018 drill D10.2 ;
 754:J P[376] 50% CNT50 ;
 755:L P[377] 250mm/sec CNT10 ;
 756:L P[378] 20mm/sec FINE ;
 757:  WAIT   .30(sec) ;
 758:L P[376] 250mm/sec CNT50 ;
 759:  !R019 drill D10.2 ;
 760:J P[379] 50% CNT50 ;
 761:L P[380] 250mm/sec CNT10 ;
 762:L P[381] 20mm/sec FINE ;
 763:  WAIT   .30(sec) ;
 764:L P[379] 250mm/sec CNT50 ;
 765:  !R020 drill D10.2 ;
 766:J P[382] 50% CNT50 ;
 767:L P[383] 250mm/sec CNT10 ;
 768:L P[384] 20mm/sec FINE ;
 769:  WAIT   .30(sec) ;
 770:L P[382] 250mm/sec CNT50 ;
 771:  !R021 drill D10.2 ;
 772:J P[385] 50% CNT50 ;
 773:L P[386] 250mm/sec CNT10 ;
 774:L P[387] 20mm/sec FINE ;
 775:  WAIT   .30(sec) ;
 776:L P[385] 250mm/sec CNT50 ;
 777:  !R022 drill D10.2 ;
 778:J P[388] 50% CNT50 ;
 779:L P[389] 250mm/sec CNT10 ;
 780:L P[390] 20mm/sec FINE ;
 781:  WAIT   .30(sec) ;
 782:L P[388] 250mm/sec CNT50 ;
 783:  !R023 drill D10.2 ;
 784:J P[391] 50% CNT50 ;
 785:L P[392] 250mm/sec CNT10 ;
 786:L P[393] 20mm/sec FINE ;
 787:  WAIT   .30(sec) ;
 788:L P[391] 250mm/sec CNT50 ;
 789:  !R024 drill D10.2 ;
 790:J P[394] 50% CNT50 ;
 791:L P[395] 250mm/sec CNT10 ;
 792:L P[396] 20mm/sec FINE ;
 793:  WAIT   .30(sec) ;
 794:L P[394] 250mm/sec CNT50 ;
 795:  !R025 drill D10.2 ;
 796:J P[397] 50% CNT50 ;
 797:L P[398] 250mm/sec CNT10 ;
 798:L P[399] 20mm/sec FINE ;
 799:  WAIT   .30(sec) ;
 800:L P[397] 250mm/sec CNT50 ;
 801:  !R026 drill D10.2 ;
 802:J P[400] 50% CNT50 ;
 803:L P[401] 250mm/sec CNT10 ;
 804:L P[402] 20mm/sec FINE ;
 805:  WAIT   .30(sec) ;
 806:L P[400] 250mm/sec CNT50 ;
 807:  !R027 drill D10.2 ;
 808:J P[403] 50% CNT50 ;
 809:L P[404] 250mm/sec CNT10 ;
 810:L P[405] 20mm/sec FINE ;
 811:  WAIT   .30(sec) ;
 812:L P[403] 250mm/sec CNT50 ;
 813:  !R028 drill D10.2 ;
 814:J P[406] 50% CNT50 ;
 815:L P[407] 250mm/sec CNT10 ;
 816:L P[408] 20mm/sec FINE ;
 817:  WAIT   .30(sec) ;
 818:L P[406] 250mm/sec CNT50 ;
 819:  !R029 drill D10.2 ;
 820:J P[409] 50% CNT50 ;
 821:L P[410] 250mm/sec CNT10 ;
 822:L P[411] 20mm/sec FINE ;
 823:  WAIT   .30(sec) ;
 824:L P[409] 250mm/sec CNT50 ;
 825:  !R030 drill D10.2 ;
 826:J P[412] 50% CNT50 ;
 827:L P[413] 250mm/sec CNT10 ;
 828:L P[414] 20mm/sec FINE ;
 829:  WAIT   .30(sec) ;
 830:L P[412] 250mm/sec CNT50 ;
 831:  !R031 drill D10.2 ;
 832:J P[415] 50% CNT50 ;
 833:L P[416] 250mm/sec CNT10 ;
 834:L P[417] 20mm/sec FINE ;
 835:  WAIT   .30(sec) ;
 836:L P[415] 250mm/sec CNT50 ;
 837:  !R032 drill D10.2 ;
 838:J P[418] 50% CNT50 ;
 839:L P[419] 250mm/sec CNT10 ;
 840:L P[420] 20mm/sec FINE ;
 841:  WAIT   .30(sec) ;
 842:L P[418] 250mm/sec CNT50 ;
 843:  !R033 drill D10.2 ;
 844:J P[421] 50% CNT50 ;
 845:L P[422] 250mm/sec CNT10 ;
 846:L P[423] 20mm/sec FINE ;
 847:  WAIT   .30(sec) ;
 848:L P[421] 250mm/sec CNT50 ;
 849:  !R034 drill D10.2 ;
 850:J P[424] 50% CNT50 ;
 851:L P[425] 250mm/sec CNT10 ;
 852:L P[426] 20mm/sec FINE ;
 853:  WAIT   .30(sec) ;
 854:L P[424] 250mm/sec CNT50 ;
 855:  !R035 drill D10.2 ;
 856:J P[427] 50% CNT50 ;
 857:L P[428] 250mm/sec CNT10 ;
 858:L P[429] 20mm/sec FINE ;
 859:  WAIT   .30(sec) ;
 860:L P[427] 250mm/sec CNT50 ;
 861:  !R036 drill D10.2 ;
 862:J P[430] 50% CNT50 ;
 863:L P[431] 250mm/sec CNT10 ;
 864:L P[432] 20mm/sec FINE ;
 865:  WAIT   .30(sec) ;
 866:L P[430] 250mm/sec CNT50 ;
 867:  !R037 drill D10.2 ;
 868:J P[433] 50% CNT50 ;
 869:L P[434] 250mm/sec CNT10 ;
 870:L P[435] 20mm/sec FINE ;
 871:  WAIT   .30(sec) ;
 872:L P[433] 250mm/sec CNT50 ;
 873:  !R038 drill D10.2 ;
 874:J P[436] 50% CNT50 ;
 875:L P[437] 250mm/sec CNT10 ;
 876:L P[438] 20mm/sec FINE ;
 877:  WAIT   .30(sec) ;
 878:L P[436] 250mm/sec CNT50 ;
 879:  !R039 drill D10.2 ;
 880:J P[439] 50% CNT50 ;
 881:L P[440] 250mm/sec CNT10 ;
 882:L P[441] 20mm/sec FINE ;
 883:  WAIT   .30(sec) ;
 884:L P[439] 250mm/sec CNT50 ;
 885:  !R040 drill D10.2 ;
 886:J P[442] 50% CNT50 ;
 887:L P[443] 250mm/sec CNT10 ;
 888:L P[444] 20mm/sec FINE ;
 889:  WAIT   .30(sec) ;
 890:L P[442] 250mm/sec CNT50 ;
 891:  !R041 drill D10.2 ;
 892:J P[445] 50% CNT50 ;
 893:L P[446] 250mm/sec CNT10 ;
 894:L P[447] 20mm/sec FINE ;
 895:  WAIT   .30(sec) ;
 896:L P[445] 250mm/sec CNT50 ;
 897:  !R042 drill D10.2 ;
 898:J P[448] 50% CNT50 ;
 899:L P[449] 250mm/sec CNT10 ;
 900:L P[450] 20mm/sec FINE ;
 901:  WAIT   .30(sec) ;
 902:L P[448] 250mm/sec CNT50 ;
 903:  !R043 drill D10.2 ;
 904:J P[451] 50% CNT50 ;
 905:L P[452] 250mm/sec CNT10 ;
 906:L P[453] 20mm/sec FINE ;
 907:  WAIT   .30(sec) ;
 908:L P[451] 250mm/sec CNT50 ;
 909:  !R044 drill D10.2 ;
 910:J P[454] 50% CNT50 ;
 911:L P[455] 250mm/sec CNT10 ;
 912:L P[456] 20mm/sec FINE ;
 913:  WAIT   .30(sec) ;
 914:L P[454] 250mm/sec CNT50 ;
 915:  !R045 drill D10.2 ;
 916:J P[457] 50% CNT50 ;
 917:L P[458] 250mm/sec CNT10 ;
 918:L P[459] 20mm/sec FINE ;
 919:  WAIT   .30(sec) ;
 920:L P[457] 250mm/sec CNT50 ;
 921:  !R046 drill D10.2 ;
 922:J P[460] 50% CNT50 ;
 923:L P[461] 250mm/sec CNT10 ;
 924:L P[462] 20mm/sec FINE ;
 925:  WAIT   .30(sec) ;
 926:L P[460] 250mm/sec CNT50 ;
 927:  !R047 drill D10.2 ;
 928:J P[463] 50% CNT50 ;
 929:L P[464] 250mm/sec CNT10 ;
 930:L P[465] 20mm/sec FINE ;
 931:  WAIT   .30(sec) ;
 932:L P[463] 250mm/sec CNT50 ;
 933:  !R048 drill D10.2 ;
 934:J P[466] 50% CNT50 ;
 935:L P[467] 250mm/sec CNT10 ;
 936:L P[468] 20mm/sec FINE ;
 937:  WAIT   .30(sec) ;
 938:L P[466] 250mm/sec CNT50 ;
 939:  !L001 drill D12.0 ;
 940:J P[469] 50% CNT50 ;
 941:L P[470] 250mm/sec CNT10 ;
 942:L P[471] 20mm/sec FINE ;
 943:  WAIT   .30(sec) ;
 944:L P[469] 250mm/sec CNT50 ;
 945:  !L002 drill D6.8 ;
 946:J P[472] 50% CNT50 ;
 947:L P[473] 250mm/sec CNT10 ;
 948:L P[474] 20mm/sec FINE ;
 949:  WAIT   .30(sec) ;
 950:L P[472] 250mm/sec CNT50 ;
 951:  !L003 drill D6.8 ;
 952:J P[475] 50% CNT50 ;
 953:L P[476] 250mm/sec CNT10 ;
 954:L P[477] 20mm/sec FINE ;
 955:  WAIT   .30(sec) ;
 956:L P[475] 250mm/sec CNT50 ;
 957:  !L004 drill D6.8 ;
 958:J P[478] 50% CNT50 ;
 959:L P[479] 250mm/sec CNT10 ;
 960:L P[480] 20mm/sec FINE ;
 961:  WAIT   .30(sec) ;
 962:L P[478] 250mm/sec CNT50 ;
 963:  !L005 drill D6.8 ;
 964:J P[481] 50% CNT50 ;
 965:L P[482] 250mm/sec CNT10 ;
 966:L P[483] 20mm/sec FINE ;
 967:  WAIT   .30(sec) ;
 968:L P[481] 250mm/sec CNT50 ;
 969:  !L006 drill D6.8 ;
 970:J P[484] 50% CNT50 ;
 971:L P[485] 250mm/sec CNT10 ;
 972:L P[486] 20mm/sec FINE ;
 973:  WAIT   .30(sec) ;
 974:L P[484] 250mm/sec CNT50 ;
 975:  !L007 drill D6.8 ;
 976:J P[487] 50% CNT50 ;
 977:L P[488] 250mm/sec CNT10 ;
 978:L P[489] 20mm/sec FINE ;
 979:  WAIT   .30(sec) ;
 980:L P[487] 250mm/sec CNT50 ;
 981:  !L008 drill D12.0 ;
 982:J P[490] 50% CNT50 ;
 983:L P[491] 250mm/sec CNT10 ;
 984:L P[492] 20mm/sec FINE ;
 985:  WAIT   .30(sec) ;
 986:L P[490] 250mm/sec CNT50 ;
 987:  !L009 drill D12.0 ;
 988:J P[493] 50% CNT50 ;
 989:L P[494] 250mm/sec CNT10 ;
 990:L P[495] 20mm/sec FINE ;
 991:  WAIT   .30(sec) ;
 992:L P[493] 250mm/sec CNT50 ;
 993:  !L010 drill D6.8 ;
 994:J P[496] 50% CNT50 ;
 995:L P[497] 250mm/sec CNT10 ;
 996:L P[498] 20mm/sec FINE ;
 997:  WAIT   .30(sec) ;
 998:L P[496] 250mm/sec CNT50 ;
 999:  !L011 drill D6.8 ;
1000:J P[499] 50% CNT50 ;
1001:L P[500] 250mm/sec CNT10 ;
1002:L P[501] 20mm/sec FINE ;
1003:  WAIT   .30(sec) ;
1004:L P[499] 250mm/sec CNT50 ;
1005:  !L012 drill D6.8 ;
1006:J P[502] 50% CNT50 ;
1007:L P[503] 250mm/sec CNT10 ;
1008:L P[504] 20mm/sec FINE ;
1009:  WAIT   .30(sec) ;
1010:L P[502] 250mm/sec CNT50 ;
1011:  !L013 drill D6.8 ;
1012:J P[505] 50% CNT50 ;
1013:L P[506] 250mm/sec CNT10 ;
1014:L P[507] 20mm/sec FINE ;
1015:  WAIT   .30(sec) ;
1016:L P[505] 250mm/sec CNT50 ;
1017:  !L014 drill D6.8 ;
1018:J P[508] 50% CNT50 ;
1019:L P[509] 250mm/sec CNT10 ;
1020:L P[510] 20mm/sec FINE ;
1021:  WAIT   .30(sec) ;
1022:L P[508] 250mm/sec CNT50 ;
1023:  !L015 drill D6.8 ;
1024:J P[511] 50% CNT50 ;
1025:L P[512] 250mm/sec CNT10 ;
1026:L P[513] 20mm/sec FINE ;
1027:  WAIT   .30(sec) ;
1028:L P[511] 250mm/sec CNT50 ;
1029:  !L016 drill D12.0 ;
1030:J P[514] 50% CNT50 ;
1031:L P[515] 250mm/sec CNT10 ;
1032:L P[516] 20mm/sec FINE ;
1033:  WAIT   .30(sec) ;
1034:L P[514] 250mm/sec CNT50 ;
1035:  !L017 drill D12.0 ;
1036:J P[517] 50% CNT50 ;
1037:L P[518] 250mm/sec CNT10 ;
1038:L P[519] 20mm/sec FINE ;
1039:  WAIT   .30(sec) ;
1040:L P[517] 250mm/sec CNT50 ;
1041:  !L018 drill D6.8 ;
1042:J P[520] 50% CNT50 ;
1043:L P[521] 250mm/sec CNT10 ;
1044:L P[522] 20mm/sec FINE ;
1045:  WAIT   .30(sec) ;
1046:L P[520] 250mm/sec CNT50 ;
1047:  !L019 drill D6.8 ;
1048:J P[523] 50% CNT50 ;
1049:L P[524] 250mm/sec CNT10 ;
1050:L P[525] 20mm/sec FINE ;
1051:  WAIT   .30(sec) ;
1052:L P[523] 250mm/sec CNT50 ;
1053:  !L020 drill D6.8 ;
1054:J P[526] 50% CNT50 ;
1055:L P[527] 250mm/sec CNT10 ;
1056:L P[528] 20mm/sec FINE ;
1057:  WAIT   .30(sec) ;
1058:L P[526] 250mm/sec CNT50 ;
1059:  !L021 drill D6.8 ;
1060:J P[529] 50% CNT50 ;
1061:L P[530] 250mm/sec CNT10 ;
1062:L P[531] 20mm/sec FINE ;
1063:  WAIT   .30(sec) ;
1064:L P[529] 250mm/sec CNT50 ;
1065:  !L022 drill D6.8 ;
1066:J P[532] 50% CNT50 ;
1067:L P[533] 250mm/sec CNT10 ;
1068:L P[534] 20mm/sec FINE ;
1069:  WAIT   .30(sec) ;
1070:L P[532] 250mm/sec CNT50 ;
1071:  !L023 drill D6.8 ;
1072:J P[535] 50% CNT50 ;
1073:L P[536] 250mm/sec CNT10 ;
1074:L P[537] 20mm/sec FINE ;
1075:  WAIT   .30(sec) ;
1076:L P[535] 250mm/sec CNT50 ;
1077:  !L024 drill D12.0 ;
1078:J P[538] 50% CNT50 ;
1079:L P[539] 250mm/sec CNT10 ;
1080:L P[540] 20mm/sec FINE ;
1081:  WAIT   .30(sec) ;
1082:L P[538] 250mm/sec CNT50 ;
1083:  !L025 drill D12.0 ;
1084:J P[541] 50% CNT50 ;
1085:L P[542] 250mm/sec CNT10 ;
1086:L P[543] 20mm/sec FINE ;
1087:  WAIT   .30(sec) ;
1088:L P[541] 250mm/sec CNT50 ;
1089:  !L026 drill D6.8 ;
1090:J P[544] 50% CNT50 ;
1091:L P[545] 250mm/sec CNT10 ;
1092:L P[546] 20mm/sec FINE ;
1093:  WAIT   .30(sec) ;
1094:L P[544] 250mm/sec CNT50 ;
1095:  !L027 drill D6.8 ;
1096:J P[547] 50% CNT50 ;
1097:L P[548] 250mm/sec CNT10 ;
1098:L P[549] 20mm/sec FINE ;
1099:  WAIT   .30(sec) ;
1100:L P[547] 250mm/sec CNT50 ;
1101:  !L028 drill D6.8 ;
1102:J P[550] 50% CNT50 ;
1103:L P[551] 250mm/sec CNT10 ;
1104:L P[552] 20mm/sec FINE ;
1105:  WAIT   .30(sec) ;
1106:L P[550] 250mm/sec CNT50 ;
1107:  !L029 drill D6.8 ;
1108:J P[553] 50% CNT50 ;
1109:L P[554] 250mm/sec CNT10 ;
1110:L P[555] 20mm/sec FINE ;
1111:  WAIT   .30(sec) ;
1112:L P[553] 250mm/sec CNT50 ;
1113:  !L030 drill D6.8 ;
1114:J P[556] 50% CNT50 ;
1115:L P[557] 250mm/sec CNT10 ;
1116:L P[558] 20mm/sec FINE ;
1117:  WAIT   .30(sec) ;
1118:L P[556] 250mm/sec CNT50 ;
1119:  !L031 drill D6.8 ;
1120:J P[559] 50% CNT50 ;
1121:L P[560] 250mm/sec CNT10 ;
1122:L P[561] 20mm/sec FINE ;
1123:  WAIT   .30(sec) ;
1124:L P[559] 250mm/sec CNT50 ;
1125:  !L032 drill D12.0 ;
1126:J P[562] 50% CNT50 ;
1127:L P[563] 250mm/sec CNT10 ;
1128:L P[564] 20mm/sec FINE ;
1129:  WAIT   .30(sec) ;
1130:L P[562] 250mm/sec CNT50 ;
1131:  !L033 drill D12.0 ;
1132:J P[565] 50% CNT50 ;
1133:L P[566] 250mm/sec CNT10 ;
1134:L P[567] 20mm/sec FINE ;
1135:  WAIT   .30(sec) ;
1136:L P[565] 250mm/sec CNT50 ;
1137:  !L034 drill D6.8 ;
1138:J P[568] 50% CNT50 ;
1139:L P[569] 250mm/sec CNT10 ;
1140:L P[570] 20mm/sec FINE ;
1141:  WAIT   .30(sec) ;
1142:L P[568] 250mm/sec CNT50 ;
1143:  !L035 drill D6.8 ;
1144:J P[571] 50% CNT50 ;
1145:L P[572] 250mm/sec CNT10 ;
1146:L P[573] 20mm/sec FINE ;
1147:  WAIT   .30(sec) ;
1148:L P[571] 250mm/sec CNT50 ;
1149:  !L036 drill D6.8 ;
1150:J P[574] 50% CNT50 ;
1151:L P[575] 250mm/sec CNT10 ;
1152:L P[576] 20mm/sec FINE ;
1153:  WAIT   .30(sec) ;
1154:L P[574] 250mm/sec CNT50 ;
1155:  !L037 drill D6.8 ;
1156:J P[577] 50% CNT50 ;
1157:L P[578] 250mm/sec CNT10 ;
1158:L P[579] 20mm/sec FINE ;
1159:  WAIT   .30(sec) ;
1160:L P[577] 250mm/sec CNT50 ;
1161:  !L038 drill D6.8 ;
1162:J P[580] 50% CNT50 ;
1163:L P[581] 250mm/sec CNT10 ;
1164:L P[582] 20mm/sec FINE ;
1165:  WAIT   .30(sec) ;
1166:L P[580] 250mm/sec CNT50 ;
1167:  !L039 drill D6.8 ;
1168:J P[583] 50% CNT50 ;
1169:L P[584] 250mm/sec CNT10 ;
1170:L P[585] 20mm/sec FINE ;
1171:  WAIT   .30(sec) ;
1172:L P[583] 250mm/sec CNT50 ;
1173:  !L040 drill D12.0 ;
1174:J P[586] 50% CNT50 ;
1175:L P[587] 250mm/sec CNT10 ;
1176:L P[588] 20mm/sec FINE ;
1177:  WAIT   .30(sec) ;
1178:L P[586] 250mm/sec CNT50 ;
1179:  !L041 drill D12.0 ;
1180:J P[589] 50% CNT50 ;
1181:L P[590] 250mm/sec CNT10 ;
1182:L P[591] 20mm/sec FINE ;
1183:  WAIT   .30(sec) ;
1184:L P[589] 250mm/sec CNT50 ;
1185:  !L042 drill D6.8 ;
1186:J P[592] 50% CNT50 ;
1187:L P[593] 250mm/sec CNT10 ;
1188:L P[594] 20mm/sec FINE ;
1189:  WAIT   .30(sec) ;
1190:L P[592] 250mm/sec CNT50 ;
1191:  !L043 drill D6.8 ;
1192:J P[595] 50% CNT50 ;
1193:L P[596] 250mm/sec CNT10 ;
1194:L P[597] 20mm/sec FINE ;
1195:  WAIT   .30(sec) ;
1196:L P[595] 250mm/sec CNT50 ;
1197:  !L044 drill D6.8 ;
1198:J P[598] 50% CNT50 ;
1199:L P[599] 250mm/sec CNT10 ;
1200:L P[600] 20mm/sec FINE ;
1201:  WAIT   .30(sec) ;
1202:L P[598] 250mm/sec CNT50 ;
1203:  !L045 drill D6.8 ;
1204:J P[601] 50% CNT50 ;
1205:L P[602] 250mm/sec CNT10 ;
1206:L P[603] 20mm/sec FINE ;
1207:  WAIT   .30(sec) ;
1208:L P[601] 250mm/sec CNT50 ;
1209:  !L046 drill D6.8 ;
1210:J P[604] 50% CNT50 ;
1211:L P[605] 250mm/sec CNT10 ;
1212:L P[606] 20mm/sec FINE ;
1213:  WAIT   .30(sec) ;
1214:L P[604] 250mm/sec CNT50 ;
1215:  !L047 drill D6.8 ;
1216:J P[607] 50% CNT50 ;
1217:L P[608] 250mm/sec CNT10 ;
1218:L P[609] 20mm/sec FINE ;
1219:  WAIT   .30(sec) ;
1220:L P[607] 250mm/sec CNT50 ;
1221:  !L048 drill D12.0 ;
1222:J P[610] 50% CNT50 ;
1223:L P[611] 250mm/sec CNT10 ;
1224:L P[612] 20mm/sec FINE ;
1225:  WAIT   .30(sec) ;
1226:L P[610] 250mm/sec CNT50 ;
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
P[11]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   106.066  mm,	Y =   106.066  mm,	Z =   252.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[12]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   106.066  mm,	Y =   106.066  mm,	Z =   234.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[13]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    75.000  mm,	Y =   129.904  mm,	Z =   300.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[14]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    75.000  mm,	Y =   129.904  mm,	Z =   252.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[15]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    75.000  mm,	Y =   129.904  mm,	Z =   234.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[16]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    38.823  mm,	Y =   144.889  mm,	Z =   300.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[17]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    38.823  mm,	Y =   144.889  mm,	Z =   252.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[18]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    38.823  mm,	Y =   144.889  mm,	Z =   234.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[19]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =     0.000  mm,	Y =   150.000  mm,	Z =   300.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[20]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =     0.000  mm,	Y =   150.000  mm,	Z =   252.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[21]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =     0.000  mm,	Y =   150.000  mm,	Z =   234.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[22]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -38.823  mm,	Y =   144.889  mm,	Z =   300.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[23]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -38.823  mm,	Y =   144.889  mm,	Z =   252.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[24]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -38.823  mm,	Y =   144.889  mm,	Z =   234.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[25]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -75.000  mm,	Y =   129.904  mm,	Z =   300.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[26]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -75.000  mm,	Y =   129.904  mm,	Z =   252.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[27]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -75.000  mm,	Y =   129.904  mm,	Z =   234.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[28]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =  -106.066  mm,	Y =   106.066  mm,	Z =   300.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[29]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =  -106.066  mm,	Y =   106.066  mm,	Z =   252.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[30]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =  -106.066  mm,	Y =   106.066  mm,	Z =   234.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[31]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =  -129.904  mm,	Y =    75.000  mm,	Z =   300.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[32]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =  -129.904  mm,	Y =    75.000  mm,	Z =   252.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[33]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =  -129.904  mm,	Y =    75.000  mm,	Z =   234.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[34]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =  -144.889  mm,	Y =    38.823  mm,	Z =   300.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[35]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =  -144.889  mm,	Y =    38.823  mm,	Z =   252.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[36]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =  -144.889  mm,	Y =    38.823  mm,	Z =   234.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[37]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =  -150.000  mm,	Y =     0.000  mm,	Z =   300.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[38]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =  -150.000  mm,	Y =     0.000  mm,	Z =   252.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[39]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =  -150.000  mm,	Y =     0.000  mm,	Z =   234.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[40]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =  -144.889  mm,	Y =   -38.823  mm,	Z =   300.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[41]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =  -144.889  mm,	Y =   -38.823  mm,	Z =   252.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[42]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =  -144.889  mm,	Y =   -38.823  mm,	Z =   234.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[43]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =  -129.904  mm,	Y =   -75.000  mm,	Z =   300.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[44]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =  -129.904  mm,	Y =   -75.000  mm,	Z =   252.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[45]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =  -129.904  mm,	Y =   -75.000  mm,	Z =   234.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[46]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =  -106.066  mm,	Y =  -106.066  mm,	Z =   300.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[47]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =  -106.066  mm,	Y =  -106.066  mm,	Z =   252.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[48]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =  -106.066  mm,	Y =  -106.066  mm,	Z =   234.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[49]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =   -75.000  mm,	Y =  -129.904  mm,	Z =   300.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[50]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =   -75.000  mm,	Y =  -129.904  mm,	Z =   252.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[51]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =   -75.000  mm,	Y =  -129.904  mm,	Z =   234.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[52]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =   -38.823  mm,	Y =  -144.889  mm,	Z =   300.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[53]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =   -38.823  mm,	Y =  -144.889  mm,	Z =   252.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[54]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =   -38.823  mm,	Y =  -144.889  mm,	Z =   234.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[55]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =     0.000  mm,	Y =  -150.000  mm,	Z =   300.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[56]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =     0.000  mm,	Y =  -150.000  mm,	Z =   252.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[57]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =     0.000  mm,	Y =  -150.000  mm,	Z =   234.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[58]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =    38.823  mm,	Y =  -144.889  mm,	Z =   300.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[59]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =    38.823  mm,	Y =  -144.889  mm,	Z =   252.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[60]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =    38.823  mm,	Y =  -144.889  mm,	Z =   234.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[61]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =    75.000  mm,	Y =  -129.904  mm,	Z =   300.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[62]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =    75.000  mm,	Y =  -129.904  mm,	Z =   252.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[63]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =    75.000  mm,	Y =  -129.904  mm,	Z =   234.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[64]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =   106.066  mm,	Y =  -106.066  mm,	Z =   300.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[65]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =   106.066  mm,	Y =  -106.066  mm,	Z =   252.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[66]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =   106.066  mm,	Y =  -106.066  mm,	Z =   234.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[67]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =   129.904  mm,	Y =   -75.000  mm,	Z =   300.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[68]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =   129.904  mm,	Y =   -75.000  mm,	Z =   252.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[69]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =   129.904  mm,	Y =   -75.000  mm,	Z =   234.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[70]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =   144.889  mm,	Y =   -38.823  mm,	Z =   300.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[71]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =   144.889  mm,	Y =   -38.823  mm,	Z =   252.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[72]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =   144.889  mm,	Y =   -38.823  mm,	Z =   234.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[73]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   106.252  mm,	Y =    28.470  mm,	Z =   300.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[74]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   106.252  mm,	Y =    28.470  mm,	Z =   252.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[75]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   106.252  mm,	Y =    28.470  mm,	Z =   220.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[76]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    77.782  mm,	Y =    77.782  mm,	Z =   300.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[77]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    77.782  mm,	Y =    77.782  mm,	Z =   252.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[78]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    77.782  mm,	Y =    77.782  mm,	Z =   220.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[79]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    28.470  mm,	Y =   106.252  mm,	Z =   300.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[80]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    28.470  mm,	Y =   106.252  mm,	Z =   252.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[81]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    28.470  mm,	Y =   106.252  mm,	Z =   220.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[82]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -28.470  mm,	Y =   106.252  mm,	Z =   300.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[83]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -28.470  mm,	Y =   106.252  mm,	Z =   252.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[84]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -28.470  mm,	Y =   106.252  mm,	Z =   220.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[85]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -77.782  mm,	Y =    77.782  mm,	Z =   300.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[86]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -77.782  mm,	Y =    77.782  mm,	Z =   252.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[87]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -77.782  mm,	Y =    77.782  mm,	Z =   220.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[88]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =  -106.252  mm,	Y =    28.470  mm,	Z =   300.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[89]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =  -106.252  mm,	Y =    28.470  mm,	Z =   252.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[90]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =  -106.252  mm,	Y =    28.470  mm,	Z =   220.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[91]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =  -106.252  mm,	Y =   -28.470  mm,	Z =   300.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[92]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =  -106.252  mm,	Y =   -28.470  mm,	Z =   252.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[93]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =  -106.252  mm,	Y =   -28.470  mm,	Z =   220.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[94]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =   -77.782  mm,	Y =   -77.782  mm,	Z =   300.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[95]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =   -77.782  mm,	Y =   -77.782  mm,	Z =   252.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[96]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =   -77.782  mm,	Y =   -77.782  mm,	Z =   220.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[97]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =   -28.470  mm,	Y =  -106.252  mm,	Z =   300.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[98]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =   -28.470  mm,	Y =  -106.252  mm,	Z =   252.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[99]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =   -28.470  mm,	Y =  -106.252  mm,	Z =   220.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[100]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =    28.470  mm,	Y =  -106.252  mm,	Z =   300.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[101]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =    28.470  mm,	Y =  -106.252  mm,	Z =   252.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[102]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =    28.470  mm,	Y =  -106.252  mm,	Z =   220.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[103]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =    77.782  mm,	Y =   -77.782  mm,	Z =   300.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[104]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =    77.782  mm,	Y =   -77.782  mm,	Z =   252.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[105]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =    77.782  mm,	Y =   -77.782  mm,	Z =   220.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[106]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =   106.252  mm,	Y =   -28.470  mm,	Z =   300.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[107]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =   106.252  mm,	Y =   -28.470  mm,	Z =   252.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[108]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =   106.252  mm,	Y =   -28.470  mm,	Z =   220.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[109]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =    70.000  mm,	Y =     0.000  mm,	Z =   300.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[110]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =    70.000  mm,	Y =     0.000  mm,	Z =   252.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[111]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =    70.000  mm,	Y =     0.000  mm,	Z =   230.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[112]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    60.622  mm,	Y =    35.000  mm,	Z =   300.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[113]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    60.622  mm,	Y =    35.000  mm,	Z =   252.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[114]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    60.622  mm,	Y =    35.000  mm,	Z =   230.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[115]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    35.000  mm,	Y =    60.622  mm,	Z =   300.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[116]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    35.000  mm,	Y =    60.622  mm,	Z =   252.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[117]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    35.000  mm,	Y =    60.622  mm,	Z =   230.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[118]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =     0.000  mm,	Y =    70.000  mm,	Z =   300.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[119]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =     0.000  mm,	Y =    70.000  mm,	Z =   252.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[120]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =     0.000  mm,	Y =    70.000  mm,	Z =   230.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[121]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -35.000  mm,	Y =    60.622  mm,	Z =   300.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[122]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -35.000  mm,	Y =    60.622  mm,	Z =   252.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[123]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -35.000  mm,	Y =    60.622  mm,	Z =   230.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[124]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -60.622  mm,	Y =    35.000  mm,	Z =   300.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[125]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -60.622  mm,	Y =    35.000  mm,	Z =   252.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[126]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -60.622  mm,	Y =    35.000  mm,	Z =   230.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[127]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =   -70.000  mm,	Y =     0.000  mm,	Z =   300.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[128]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =   -70.000  mm,	Y =     0.000  mm,	Z =   252.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[129]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =   -70.000  mm,	Y =     0.000  mm,	Z =   230.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[130]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =   -60.622  mm,	Y =   -35.000  mm,	Z =   300.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[131]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =   -60.622  mm,	Y =   -35.000  mm,	Z =   252.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[132]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =   -60.622  mm,	Y =   -35.000  mm,	Z =   230.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[133]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =   -35.000  mm,	Y =   -60.622  mm,	Z =   300.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[134]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =   -35.000  mm,	Y =   -60.622  mm,	Z =   252.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[135]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =   -35.000  mm,	Y =   -60.622  mm,	Z =   230.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[136]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =     0.000  mm,	Y =   -70.000  mm,	Z =   300.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[137]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =     0.000  mm,	Y =   -70.000  mm,	Z =   252.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[138]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =     0.000  mm,	Y =   -70.000  mm,	Z =   230.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[139]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =    35.000  mm,	Y =   -60.622  mm,	Z =   300.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[140]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =    35.000  mm,	Y =   -60.622  mm,	Z =   252.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[141]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =    35.000  mm,	Y =   -60.622  mm,	Z =   230.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[142]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =    60.622  mm,	Y =   -35.000  mm,	Z =   300.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[143]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =    60.622  mm,	Y =   -35.000  mm,	Z =   252.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[144]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =    60.622  mm,	Y =   -35.000  mm,	Z =   230.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[145]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    29.743  mm,	Y =     3.916  mm,	Z =   300.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[146]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    29.743  mm,	Y =     3.916  mm,	Z =   252.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[147]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    29.743  mm,	Y =     3.916  mm,	Z =   238.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[148]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    23.801  mm,	Y =    18.263  mm,	Z =   300.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[149]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    23.801  mm,	Y =    18.263  mm,	Z =   252.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[150]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    23.801  mm,	Y =    18.263  mm,	Z =   238.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[151]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    11.481  mm,	Y =    27.716  mm,	Z =   300.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[152]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    11.481  mm,	Y =    27.716  mm,	Z =   252.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[153]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    11.481  mm,	Y =    27.716  mm,	Z =   238.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[154]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    -3.916  mm,	Y =    29.743  mm,	Z =   300.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[155]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    -3.916  mm,	Y =    29.743  mm,	Z =   252.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[156]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    -3.916  mm,	Y =    29.743  mm,	Z =   238.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[157]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -18.263  mm,	Y =    23.801  mm,	Z =   300.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[158]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -18.263  mm,	Y =    23.801  mm,	Z =   252.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[159]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -18.263  mm,	Y =    23.801  mm,	Z =   238.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[160]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -27.716  mm,	Y =    11.481  mm,	Z =   300.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[161]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -27.716  mm,	Y =    11.481  mm,	Z =   252.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[162]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -27.716  mm,	Y =    11.481  mm,	Z =   238.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[163]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =   -29.743  mm,	Y =    -3.916  mm,	Z =   300.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[164]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =   -29.743  mm,	Y =    -3.916  mm,	Z =   252.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[165]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =   -29.743  mm,	Y =    -3.916  mm,	Z =   238.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[166]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =   -23.801  mm,	Y =   -18.263  mm,	Z =   300.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[167]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =   -23.801  mm,	Y =   -18.263  mm,	Z =   252.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[168]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =   -23.801  mm,	Y =   -18.263  mm,	Z =   238.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[169]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =   -11.481  mm,	Y =   -27.716  mm,	Z =   300.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[170]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =   -11.481  mm,	Y =   -27.716  mm,	Z =   252.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[171]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =   -11.481  mm,	Y =   -27.716  mm,	Z =   238.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[172]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =     3.916  mm,	Y =   -29.743  mm,	Z =   300.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[173]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =     3.916  mm,	Y =   -29.743  mm,	Z =   252.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[174]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =     3.916  mm,	Y =   -29.743  mm,	Z =   238.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[175]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =    18.263  mm,	Y =   -23.801  mm,	Z =   300.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[176]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =    18.263  mm,	Y =   -23.801  mm,	Z =   252.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[177]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =    18.263  mm,	Y =   -23.801  mm,	Z =   238.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[178]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =    27.716  mm,	Y =   -11.481  mm,	Z =   300.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[179]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =    27.716  mm,	Y =   -11.481  mm,	Z =   252.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[180]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 1',
	X =    27.716  mm,	Y =   -11.481  mm,	Z =   238.000  mm,
	W =   180.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[181]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 1, 0',
	X =  -210.711  mm,	Y =  -105.000  mm,	Z =   190.000  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[182]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 1, 0',
	X =  -176.770  mm,	Y =  -105.000  mm,	Z =   156.059  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[183]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 1, 0',
	X =  -158.385  mm,	Y =  -105.000  mm,	Z =   137.674  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[184]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 1, 0',
	X =  -210.711  mm,	Y =   -75.000  mm,	Z =   190.000  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[185]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 1, 0',
	X =  -176.770  mm,	Y =   -75.000  mm,	Z =   156.059  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[186]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 1, 0',
	X =  -158.385  mm,	Y =   -75.000  mm,	Z =   137.674  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[187]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 1, 0',
	X =  -210.711  mm,	Y =   -45.000  mm,	Z =   190.000  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[188]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 1, 0',
	X =  -176.770  mm,	Y =   -45.000  mm,	Z =   156.059  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[189]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 1, 0',
	X =  -158.385  mm,	Y =   -45.000  mm,	Z =   137.674  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[190]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 1, 0',
	X =  -210.711  mm,	Y =   -15.000  mm,	Z =   190.000  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[191]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 1, 0',
	X =  -176.770  mm,	Y =   -15.000  mm,	Z =   156.059  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[192]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 1, 0',
	X =  -158.385  mm,	Y =   -15.000  mm,	Z =   137.674  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[193]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =  -210.711  mm,	Y =    15.000  mm,	Z =   190.000  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[194]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =  -176.770  mm,	Y =    15.000  mm,	Z =   156.059  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[195]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =  -158.385  mm,	Y =    15.000  mm,	Z =   137.674  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[196]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =  -210.711  mm,	Y =    45.000  mm,	Z =   190.000  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[197]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =  -176.770  mm,	Y =    45.000  mm,	Z =   156.059  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[198]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =  -158.385  mm,	Y =    45.000  mm,	Z =   137.674  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[199]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =  -210.711  mm,	Y =    75.000  mm,	Z =   190.000  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[200]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =  -176.770  mm,	Y =    75.000  mm,	Z =   156.059  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[201]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =  -158.385  mm,	Y =    75.000  mm,	Z =   137.674  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[202]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =  -210.711  mm,	Y =   105.000  mm,	Z =   190.000  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[203]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =  -176.770  mm,	Y =   105.000  mm,	Z =   156.059  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[204]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =  -158.385  mm,	Y =   105.000  mm,	Z =   137.674  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[205]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -196.569  mm,	Y =  -105.000  mm,	Z =   204.142  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[206]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -162.627  mm,	Y =  -105.000  mm,	Z =   170.201  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[207]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -144.243  mm,	Y =  -105.000  mm,	Z =   151.816  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[208]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -196.569  mm,	Y =   -75.000  mm,	Z =   204.142  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[209]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -162.627  mm,	Y =   -75.000  mm,	Z =   170.201  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[210]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -144.243  mm,	Y =   -75.000  mm,	Z =   151.816  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[211]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -196.569  mm,	Y =   -45.000  mm,	Z =   204.142  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[212]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -162.627  mm,	Y =   -45.000  mm,	Z =   170.201  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[213]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -144.243  mm,	Y =   -45.000  mm,	Z =   151.816  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[214]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -196.569  mm,	Y =   -15.000  mm,	Z =   204.142  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[215]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -162.627  mm,	Y =   -15.000  mm,	Z =   170.201  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[216]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -144.243  mm,	Y =   -15.000  mm,	Z =   151.816  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[217]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =  -196.569  mm,	Y =    15.000  mm,	Z =   204.142  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[218]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =  -162.627  mm,	Y =    15.000  mm,	Z =   170.201  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[219]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =  -144.243  mm,	Y =    15.000  mm,	Z =   151.816  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[220]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =  -196.569  mm,	Y =    45.000  mm,	Z =   204.142  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[221]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =  -162.627  mm,	Y =    45.000  mm,	Z =   170.201  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[222]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =  -144.243  mm,	Y =    45.000  mm,	Z =   151.816  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[223]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =  -196.569  mm,	Y =    75.000  mm,	Z =   204.142  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[224]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =  -162.627  mm,	Y =    75.000  mm,	Z =   170.201  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[225]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =  -144.243  mm,	Y =    75.000  mm,	Z =   151.816  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[226]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =  -196.569  mm,	Y =   105.000  mm,	Z =   204.142  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[227]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =  -162.627  mm,	Y =   105.000  mm,	Z =   170.201  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[228]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =  -144.243  mm,	Y =   105.000  mm,	Z =   151.816  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[229]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -182.426  mm,	Y =  -105.000  mm,	Z =   218.284  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[230]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -148.485  mm,	Y =  -105.000  mm,	Z =   184.343  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[231]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -130.101  mm,	Y =  -105.000  mm,	Z =   165.958  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[232]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -182.426  mm,	Y =   -75.000  mm,	Z =   218.284  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[233]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -148.485  mm,	Y =   -75.000  mm,	Z =   184.343  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[234]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -130.101  mm,	Y =   -75.000  mm,	Z =   165.958  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[235]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -182.426  mm,	Y =   -45.000  mm,	Z =   218.284  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[236]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -148.485  mm,	Y =   -45.000  mm,	Z =   184.343  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[237]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -130.101  mm,	Y =   -45.000  mm,	Z =   165.958  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[238]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -182.426  mm,	Y =   -15.000  mm,	Z =   218.284  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[239]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -148.485  mm,	Y =   -15.000  mm,	Z =   184.343  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[240]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -130.101  mm,	Y =   -15.000  mm,	Z =   165.958  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[241]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =  -182.426  mm,	Y =    15.000  mm,	Z =   218.284  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[242]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =  -148.485  mm,	Y =    15.000  mm,	Z =   184.343  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[243]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =  -130.101  mm,	Y =    15.000  mm,	Z =   165.958  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[244]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =  -182.426  mm,	Y =    45.000  mm,	Z =   218.284  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[245]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =  -148.485  mm,	Y =    45.000  mm,	Z =   184.343  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[246]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =  -130.101  mm,	Y =    45.000  mm,	Z =   165.958  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[247]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =  -182.426  mm,	Y =    75.000  mm,	Z =   218.284  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[248]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =  -148.485  mm,	Y =    75.000  mm,	Z =   184.343  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[249]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =  -130.101  mm,	Y =    75.000  mm,	Z =   165.958  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[250]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =  -182.426  mm,	Y =   105.000  mm,	Z =   218.284  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[251]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =  -148.485  mm,	Y =   105.000  mm,	Z =   184.343  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[252]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =  -130.101  mm,	Y =   105.000  mm,	Z =   165.958  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[253]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -168.284  mm,	Y =  -105.000  mm,	Z =   232.426  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[254]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -134.343  mm,	Y =  -105.000  mm,	Z =   198.485  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[255]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -115.958  mm,	Y =  -105.000  mm,	Z =   180.101  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[256]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -168.284  mm,	Y =   -75.000  mm,	Z =   232.426  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[257]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -134.343  mm,	Y =   -75.000  mm,	Z =   198.485  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[258]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -115.958  mm,	Y =   -75.000  mm,	Z =   180.101  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[259]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -168.284  mm,	Y =   -45.000  mm,	Z =   232.426  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[260]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -134.343  mm,	Y =   -45.000  mm,	Z =   198.485  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[261]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -115.958  mm,	Y =   -45.000  mm,	Z =   180.101  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[262]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -168.284  mm,	Y =   -15.000  mm,	Z =   232.426  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[263]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -134.343  mm,	Y =   -15.000  mm,	Z =   198.485  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[264]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -115.958  mm,	Y =   -15.000  mm,	Z =   180.101  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[265]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =  -168.284  mm,	Y =    15.000  mm,	Z =   232.426  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[266]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =  -134.343  mm,	Y =    15.000  mm,	Z =   198.485  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[267]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =  -115.958  mm,	Y =    15.000  mm,	Z =   180.101  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[268]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =  -168.284  mm,	Y =    45.000  mm,	Z =   232.426  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[269]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =  -134.343  mm,	Y =    45.000  mm,	Z =   198.485  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[270]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =  -115.958  mm,	Y =    45.000  mm,	Z =   180.101  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[271]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =  -168.284  mm,	Y =    75.000  mm,	Z =   232.426  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[272]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =  -134.343  mm,	Y =    75.000  mm,	Z =   198.485  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[273]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =  -115.958  mm,	Y =    75.000  mm,	Z =   180.101  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[274]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =  -168.284  mm,	Y =   105.000  mm,	Z =   232.426  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[275]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =  -134.343  mm,	Y =   105.000  mm,	Z =   198.485  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[276]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =  -115.958  mm,	Y =   105.000  mm,	Z =   180.101  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[277]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -154.142  mm,	Y =  -105.000  mm,	Z =   246.569  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[278]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -120.201  mm,	Y =  -105.000  mm,	Z =   212.627  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[279]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -101.816  mm,	Y =  -105.000  mm,	Z =   194.243  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[280]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -154.142  mm,	Y =   -75.000  mm,	Z =   246.569  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[281]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -120.201  mm,	Y =   -75.000  mm,	Z =   212.627  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[282]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -101.816  mm,	Y =   -75.000  mm,	Z =   194.243  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[283]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -154.142  mm,	Y =   -45.000  mm,	Z =   246.569  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[284]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -120.201  mm,	Y =   -45.000  mm,	Z =   212.627  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[285]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -101.816  mm,	Y =   -45.000  mm,	Z =   194.243  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[286]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -154.142  mm,	Y =   -15.000  mm,	Z =   246.569  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[287]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -120.201  mm,	Y =   -15.000  mm,	Z =   212.627  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[288]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -101.816  mm,	Y =   -15.000  mm,	Z =   194.243  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[289]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =  -154.142  mm,	Y =    15.000  mm,	Z =   246.569  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[290]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =  -120.201  mm,	Y =    15.000  mm,	Z =   212.627  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[291]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =  -101.816  mm,	Y =    15.000  mm,	Z =   194.243  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[292]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =  -154.142  mm,	Y =    45.000  mm,	Z =   246.569  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[293]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =  -120.201  mm,	Y =    45.000  mm,	Z =   212.627  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[294]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =  -101.816  mm,	Y =    45.000  mm,	Z =   194.243  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[295]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =  -154.142  mm,	Y =    75.000  mm,	Z =   246.569  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[296]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =  -120.201  mm,	Y =    75.000  mm,	Z =   212.627  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[297]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =  -101.816  mm,	Y =    75.000  mm,	Z =   194.243  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[298]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =  -154.142  mm,	Y =   105.000  mm,	Z =   246.569  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[299]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =  -120.201  mm,	Y =   105.000  mm,	Z =   212.627  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[300]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =  -101.816  mm,	Y =   105.000  mm,	Z =   194.243  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[301]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -140.000  mm,	Y =  -105.000  mm,	Z =   260.711  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[302]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -106.059  mm,	Y =  -105.000  mm,	Z =   226.770  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[303]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   -87.674  mm,	Y =  -105.000  mm,	Z =   208.385  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[304]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -140.000  mm,	Y =   -75.000  mm,	Z =   260.711  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[305]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -106.059  mm,	Y =   -75.000  mm,	Z =   226.770  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[306]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   -87.674  mm,	Y =   -75.000  mm,	Z =   208.385  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[307]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -140.000  mm,	Y =   -45.000  mm,	Z =   260.711  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[308]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -106.059  mm,	Y =   -45.000  mm,	Z =   226.770  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[309]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   -87.674  mm,	Y =   -45.000  mm,	Z =   208.385  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[310]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -140.000  mm,	Y =   -15.000  mm,	Z =   260.711  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[311]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -106.059  mm,	Y =   -15.000  mm,	Z =   226.770  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[312]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   -87.674  mm,	Y =   -15.000  mm,	Z =   208.385  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[313]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =  -140.000  mm,	Y =    15.000  mm,	Z =   260.711  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[314]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =  -106.059  mm,	Y =    15.000  mm,	Z =   226.770  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[315]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =   -87.674  mm,	Y =    15.000  mm,	Z =   208.385  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[316]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =  -140.000  mm,	Y =    45.000  mm,	Z =   260.711  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[317]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =  -106.059  mm,	Y =    45.000  mm,	Z =   226.770  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[318]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =   -87.674  mm,	Y =    45.000  mm,	Z =   208.385  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[319]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =  -140.000  mm,	Y =    75.000  mm,	Z =   260.711  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[320]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =  -106.059  mm,	Y =    75.000  mm,	Z =   226.770  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[321]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =   -87.674  mm,	Y =    75.000  mm,	Z =   208.385  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[322]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =  -140.000  mm,	Y =   105.000  mm,	Z =   260.711  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[323]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =  -106.059  mm,	Y =   105.000  mm,	Z =   226.770  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[324]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'N U T, 0, 0, 1',
	X =   -87.674  mm,	Y =   105.000  mm,	Z =   208.385  mm,
	W =   180.000 deg,	P =   -45.000 deg,	R =     0.000 deg
};
P[325]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -105.000  mm,	Y =  -220.000  mm,	Z =    40.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[326]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -105.000  mm,	Y =  -172.000  mm,	Z =    40.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[327]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -105.000  mm,	Y =  -140.000  mm,	Z =    40.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[328]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   -75.000  mm,	Y =  -220.000  mm,	Z =    40.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[329]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   -75.000  mm,	Y =  -172.000  mm,	Z =    40.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[330]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   -75.000  mm,	Y =  -140.000  mm,	Z =    40.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[331]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   -45.000  mm,	Y =  -220.000  mm,	Z =    40.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[332]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   -45.000  mm,	Y =  -172.000  mm,	Z =    40.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[333]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   -45.000  mm,	Y =  -140.000  mm,	Z =    40.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[334]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   -15.000  mm,	Y =  -220.000  mm,	Z =    40.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[335]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   -15.000  mm,	Y =  -172.000  mm,	Z =    40.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[336]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   -15.000  mm,	Y =  -140.000  mm,	Z =    40.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[337]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =    15.000  mm,	Y =  -220.000  mm,	Z =    40.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[338]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =    15.000  mm,	Y =  -172.000  mm,	Z =    40.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[339]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =    15.000  mm,	Y =  -140.000  mm,	Z =    40.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[340]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =    45.000  mm,	Y =  -220.000  mm,	Z =    40.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[341]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =    45.000  mm,	Y =  -172.000  mm,	Z =    40.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[342]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =    45.000  mm,	Y =  -140.000  mm,	Z =    40.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[343]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =    75.000  mm,	Y =  -220.000  mm,	Z =    40.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[344]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =    75.000  mm,	Y =  -172.000  mm,	Z =    40.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[345]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =    75.000  mm,	Y =  -140.000  mm,	Z =    40.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[346]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   105.000  mm,	Y =  -220.000  mm,	Z =    40.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[347]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   105.000  mm,	Y =  -172.000  mm,	Z =    40.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[348]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   105.000  mm,	Y =  -140.000  mm,	Z =    40.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[349]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -105.000  mm,	Y =  -220.000  mm,	Z =    75.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[350]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -105.000  mm,	Y =  -172.000  mm,	Z =    75.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[351]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -105.000  mm,	Y =  -140.000  mm,	Z =    75.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[352]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   -75.000  mm,	Y =  -220.000  mm,	Z =    75.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[353]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   -75.000  mm,	Y =  -172.000  mm,	Z =    75.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[354]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   -75.000  mm,	Y =  -140.000  mm,	Z =    75.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[355]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   -45.000  mm,	Y =  -220.000  mm,	Z =    75.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[356]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   -45.000  mm,	Y =  -172.000  mm,	Z =    75.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[357]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   -45.000  mm,	Y =  -140.000  mm,	Z =    75.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[358]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   -15.000  mm,	Y =  -220.000  mm,	Z =    75.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[359]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   -15.000  mm,	Y =  -172.000  mm,	Z =    75.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[360]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   -15.000  mm,	Y =  -140.000  mm,	Z =    75.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[361]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =    15.000  mm,	Y =  -220.000  mm,	Z =    75.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[362]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =    15.000  mm,	Y =  -172.000  mm,	Z =    75.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[363]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =    15.000  mm,	Y =  -140.000  mm,	Z =    75.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[364]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =    45.000  mm,	Y =  -220.000  mm,	Z =    75.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[365]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =    45.000  mm,	Y =  -172.000  mm,	Z =    75.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[366]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =    45.000  mm,	Y =  -140.000  mm,	Z =    75.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[367]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =    75.000  mm,	Y =  -220.000  mm,	Z =    75.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[368]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =    75.000  mm,	Y =  -172.000  mm,	Z =    75.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[369]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =    75.000  mm,	Y =  -140.000  mm,	Z =    75.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[370]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   105.000  mm,	Y =  -220.000  mm,	Z =    75.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[371]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   105.000  mm,	Y =  -172.000  mm,	Z =    75.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[372]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   105.000  mm,	Y =  -140.000  mm,	Z =    75.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[373]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -105.000  mm,	Y =  -220.000  mm,	Z =   110.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[374]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -105.000  mm,	Y =  -172.000  mm,	Z =   110.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[375]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -105.000  mm,	Y =  -140.000  mm,	Z =   110.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[376]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   -75.000  mm,	Y =  -220.000  mm,	Z =   110.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[377]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   -75.000  mm,	Y =  -172.000  mm,	Z =   110.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[378]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   -75.000  mm,	Y =  -140.000  mm,	Z =   110.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[379]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   -45.000  mm,	Y =  -220.000  mm,	Z =   110.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[380]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   -45.000  mm,	Y =  -172.000  mm,	Z =   110.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[381]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   -45.000  mm,	Y =  -140.000  mm,	Z =   110.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[382]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   -15.000  mm,	Y =  -220.000  mm,	Z =   110.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[383]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   -15.000  mm,	Y =  -172.000  mm,	Z =   110.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[384]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   -15.000  mm,	Y =  -140.000  mm,	Z =   110.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[385]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =    15.000  mm,	Y =  -220.000  mm,	Z =   110.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[386]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =    15.000  mm,	Y =  -172.000  mm,	Z =   110.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[387]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =    15.000  mm,	Y =  -140.000  mm,	Z =   110.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[388]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =    45.000  mm,	Y =  -220.000  mm,	Z =   110.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[389]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =    45.000  mm,	Y =  -172.000  mm,	Z =   110.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[390]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =    45.000  mm,	Y =  -140.000  mm,	Z =   110.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[391]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =    75.000  mm,	Y =  -220.000  mm,	Z =   110.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[392]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =    75.000  mm,	Y =  -172.000  mm,	Z =   110.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[393]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =    75.000  mm,	Y =  -140.000  mm,	Z =   110.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[394]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   105.000  mm,	Y =  -220.000  mm,	Z =   110.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[395]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   105.000  mm,	Y =  -172.000  mm,	Z =   110.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[396]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   105.000  mm,	Y =  -140.000  mm,	Z =   110.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[397]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -105.000  mm,	Y =  -220.000  mm,	Z =   145.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[398]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -105.000  mm,	Y =  -172.000  mm,	Z =   145.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[399]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -105.000  mm,	Y =  -140.000  mm,	Z =   145.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[400]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   -75.000  mm,	Y =  -220.000  mm,	Z =   145.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[401]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   -75.000  mm,	Y =  -172.000  mm,	Z =   145.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[402]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   -75.000  mm,	Y =  -140.000  mm,	Z =   145.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[403]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   -45.000  mm,	Y =  -220.000  mm,	Z =   145.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[404]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   -45.000  mm,	Y =  -172.000  mm,	Z =   145.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[405]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   -45.000  mm,	Y =  -140.000  mm,	Z =   145.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[406]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   -15.000  mm,	Y =  -220.000  mm,	Z =   145.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[407]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   -15.000  mm,	Y =  -172.000  mm,	Z =   145.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[408]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   -15.000  mm,	Y =  -140.000  mm,	Z =   145.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[409]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =    15.000  mm,	Y =  -220.000  mm,	Z =   145.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[410]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =    15.000  mm,	Y =  -172.000  mm,	Z =   145.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[411]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =    15.000  mm,	Y =  -140.000  mm,	Z =   145.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[412]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =    45.000  mm,	Y =  -220.000  mm,	Z =   145.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[413]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =    45.000  mm,	Y =  -172.000  mm,	Z =   145.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[414]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =    45.000  mm,	Y =  -140.000  mm,	Z =   145.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[415]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =    75.000  mm,	Y =  -220.000  mm,	Z =   145.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[416]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =    75.000  mm,	Y =  -172.000  mm,	Z =   145.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[417]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =    75.000  mm,	Y =  -140.000  mm,	Z =   145.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[418]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   105.000  mm,	Y =  -220.000  mm,	Z =   145.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[419]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   105.000  mm,	Y =  -172.000  mm,	Z =   145.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[420]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   105.000  mm,	Y =  -140.000  mm,	Z =   145.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[421]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -105.000  mm,	Y =  -220.000  mm,	Z =   180.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[422]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -105.000  mm,	Y =  -172.000  mm,	Z =   180.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[423]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -105.000  mm,	Y =  -140.000  mm,	Z =   180.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[424]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   -75.000  mm,	Y =  -220.000  mm,	Z =   180.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[425]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   -75.000  mm,	Y =  -172.000  mm,	Z =   180.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[426]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   -75.000  mm,	Y =  -140.000  mm,	Z =   180.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[427]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   -45.000  mm,	Y =  -220.000  mm,	Z =   180.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[428]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   -45.000  mm,	Y =  -172.000  mm,	Z =   180.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[429]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   -45.000  mm,	Y =  -140.000  mm,	Z =   180.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[430]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   -15.000  mm,	Y =  -220.000  mm,	Z =   180.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[431]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   -15.000  mm,	Y =  -172.000  mm,	Z =   180.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[432]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   -15.000  mm,	Y =  -140.000  mm,	Z =   180.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[433]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =    15.000  mm,	Y =  -220.000  mm,	Z =   180.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[434]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =    15.000  mm,	Y =  -172.000  mm,	Z =   180.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[435]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =    15.000  mm,	Y =  -140.000  mm,	Z =   180.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[436]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =    45.000  mm,	Y =  -220.000  mm,	Z =   180.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[437]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =    45.000  mm,	Y =  -172.000  mm,	Z =   180.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[438]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =    45.000  mm,	Y =  -140.000  mm,	Z =   180.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[439]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =    75.000  mm,	Y =  -220.000  mm,	Z =   180.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[440]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =    75.000  mm,	Y =  -172.000  mm,	Z =   180.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[441]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =    75.000  mm,	Y =  -140.000  mm,	Z =   180.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[442]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   105.000  mm,	Y =  -220.000  mm,	Z =   180.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[443]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   105.000  mm,	Y =  -172.000  mm,	Z =   180.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[444]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   105.000  mm,	Y =  -140.000  mm,	Z =   180.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[445]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -105.000  mm,	Y =  -220.000  mm,	Z =   215.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[446]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -105.000  mm,	Y =  -172.000  mm,	Z =   215.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[447]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =  -105.000  mm,	Y =  -140.000  mm,	Z =   215.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[448]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   -75.000  mm,	Y =  -220.000  mm,	Z =   215.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[449]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   -75.000  mm,	Y =  -172.000  mm,	Z =   215.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[450]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   -75.000  mm,	Y =  -140.000  mm,	Z =   215.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[451]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   -45.000  mm,	Y =  -220.000  mm,	Z =   215.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[452]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   -45.000  mm,	Y =  -172.000  mm,	Z =   215.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[453]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   -45.000  mm,	Y =  -140.000  mm,	Z =   215.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[454]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   -15.000  mm,	Y =  -220.000  mm,	Z =   215.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[455]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   -15.000  mm,	Y =  -172.000  mm,	Z =   215.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[456]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   -15.000  mm,	Y =  -140.000  mm,	Z =   215.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[457]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =    15.000  mm,	Y =  -220.000  mm,	Z =   215.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[458]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =    15.000  mm,	Y =  -172.000  mm,	Z =   215.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[459]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =    15.000  mm,	Y =  -140.000  mm,	Z =   215.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[460]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =    45.000  mm,	Y =  -220.000  mm,	Z =   215.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[461]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =    45.000  mm,	Y =  -172.000  mm,	Z =   215.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[462]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =    45.000  mm,	Y =  -140.000  mm,	Z =   215.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[463]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =    75.000  mm,	Y =  -220.000  mm,	Z =   215.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[464]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =    75.000  mm,	Y =  -172.000  mm,	Z =   215.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[465]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =    75.000  mm,	Y =  -140.000  mm,	Z =   215.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[466]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   105.000  mm,	Y =  -220.000  mm,	Z =   215.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[467]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   105.000  mm,	Y =  -172.000  mm,	Z =   215.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[468]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 0, 1',
	X =   105.000  mm,	Y =  -140.000  mm,	Z =   215.000  mm,
	W =   -90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[469]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =  -105.000  mm,	Y =   220.000  mm,	Z =    40.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[470]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =  -105.000  mm,	Y =   172.000  mm,	Z =    40.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[471]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =  -105.000  mm,	Y =   152.000  mm,	Z =    40.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[472]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -75.000  mm,	Y =   220.000  mm,	Z =    40.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[473]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -75.000  mm,	Y =   172.000  mm,	Z =    40.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[474]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -75.000  mm,	Y =   152.000  mm,	Z =    40.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[475]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -45.000  mm,	Y =   220.000  mm,	Z =    40.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[476]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -45.000  mm,	Y =   172.000  mm,	Z =    40.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[477]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -45.000  mm,	Y =   152.000  mm,	Z =    40.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[478]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -15.000  mm,	Y =   220.000  mm,	Z =    40.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[479]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -15.000  mm,	Y =   172.000  mm,	Z =    40.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[480]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -15.000  mm,	Y =   152.000  mm,	Z =    40.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[481]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    15.000  mm,	Y =   220.000  mm,	Z =    40.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[482]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    15.000  mm,	Y =   172.000  mm,	Z =    40.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[483]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    15.000  mm,	Y =   152.000  mm,	Z =    40.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[484]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    45.000  mm,	Y =   220.000  mm,	Z =    40.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[485]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    45.000  mm,	Y =   172.000  mm,	Z =    40.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[486]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    45.000  mm,	Y =   152.000  mm,	Z =    40.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[487]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    75.000  mm,	Y =   220.000  mm,	Z =    40.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[488]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    75.000  mm,	Y =   172.000  mm,	Z =    40.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[489]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    75.000  mm,	Y =   152.000  mm,	Z =    40.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[490]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   105.000  mm,	Y =   220.000  mm,	Z =    40.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[491]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   105.000  mm,	Y =   172.000  mm,	Z =    40.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[492]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   105.000  mm,	Y =   152.000  mm,	Z =    40.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[493]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =  -105.000  mm,	Y =   220.000  mm,	Z =    75.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[494]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =  -105.000  mm,	Y =   172.000  mm,	Z =    75.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[495]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =  -105.000  mm,	Y =   152.000  mm,	Z =    75.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[496]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -75.000  mm,	Y =   220.000  mm,	Z =    75.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[497]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -75.000  mm,	Y =   172.000  mm,	Z =    75.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[498]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -75.000  mm,	Y =   152.000  mm,	Z =    75.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[499]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -45.000  mm,	Y =   220.000  mm,	Z =    75.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[500]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -45.000  mm,	Y =   172.000  mm,	Z =    75.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[501]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -45.000  mm,	Y =   152.000  mm,	Z =    75.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[502]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -15.000  mm,	Y =   220.000  mm,	Z =    75.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[503]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -15.000  mm,	Y =   172.000  mm,	Z =    75.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[504]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -15.000  mm,	Y =   152.000  mm,	Z =    75.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[505]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    15.000  mm,	Y =   220.000  mm,	Z =    75.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[506]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    15.000  mm,	Y =   172.000  mm,	Z =    75.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[507]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    15.000  mm,	Y =   152.000  mm,	Z =    75.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[508]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    45.000  mm,	Y =   220.000  mm,	Z =    75.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[509]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    45.000  mm,	Y =   172.000  mm,	Z =    75.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[510]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    45.000  mm,	Y =   152.000  mm,	Z =    75.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[511]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    75.000  mm,	Y =   220.000  mm,	Z =    75.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[512]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    75.000  mm,	Y =   172.000  mm,	Z =    75.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[513]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    75.000  mm,	Y =   152.000  mm,	Z =    75.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[514]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   105.000  mm,	Y =   220.000  mm,	Z =    75.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[515]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   105.000  mm,	Y =   172.000  mm,	Z =    75.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[516]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   105.000  mm,	Y =   152.000  mm,	Z =    75.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[517]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =  -105.000  mm,	Y =   220.000  mm,	Z =   110.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[518]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =  -105.000  mm,	Y =   172.000  mm,	Z =   110.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[519]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =  -105.000  mm,	Y =   152.000  mm,	Z =   110.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[520]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -75.000  mm,	Y =   220.000  mm,	Z =   110.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[521]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -75.000  mm,	Y =   172.000  mm,	Z =   110.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[522]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -75.000  mm,	Y =   152.000  mm,	Z =   110.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[523]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -45.000  mm,	Y =   220.000  mm,	Z =   110.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[524]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -45.000  mm,	Y =   172.000  mm,	Z =   110.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[525]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -45.000  mm,	Y =   152.000  mm,	Z =   110.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[526]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -15.000  mm,	Y =   220.000  mm,	Z =   110.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[527]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -15.000  mm,	Y =   172.000  mm,	Z =   110.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[528]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -15.000  mm,	Y =   152.000  mm,	Z =   110.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[529]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    15.000  mm,	Y =   220.000  mm,	Z =   110.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[530]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    15.000  mm,	Y =   172.000  mm,	Z =   110.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[531]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    15.000  mm,	Y =   152.000  mm,	Z =   110.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[532]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    45.000  mm,	Y =   220.000  mm,	Z =   110.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[533]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    45.000  mm,	Y =   172.000  mm,	Z =   110.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[534]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    45.000  mm,	Y =   152.000  mm,	Z =   110.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[535]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    75.000  mm,	Y =   220.000  mm,	Z =   110.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[536]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    75.000  mm,	Y =   172.000  mm,	Z =   110.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[537]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    75.000  mm,	Y =   152.000  mm,	Z =   110.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[538]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   105.000  mm,	Y =   220.000  mm,	Z =   110.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[539]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   105.000  mm,	Y =   172.000  mm,	Z =   110.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[540]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   105.000  mm,	Y =   152.000  mm,	Z =   110.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[541]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =  -105.000  mm,	Y =   220.000  mm,	Z =   145.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[542]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =  -105.000  mm,	Y =   172.000  mm,	Z =   145.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[543]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =  -105.000  mm,	Y =   152.000  mm,	Z =   145.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[544]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -75.000  mm,	Y =   220.000  mm,	Z =   145.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[545]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -75.000  mm,	Y =   172.000  mm,	Z =   145.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[546]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -75.000  mm,	Y =   152.000  mm,	Z =   145.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[547]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -45.000  mm,	Y =   220.000  mm,	Z =   145.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[548]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -45.000  mm,	Y =   172.000  mm,	Z =   145.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[549]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -45.000  mm,	Y =   152.000  mm,	Z =   145.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[550]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -15.000  mm,	Y =   220.000  mm,	Z =   145.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[551]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -15.000  mm,	Y =   172.000  mm,	Z =   145.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[552]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -15.000  mm,	Y =   152.000  mm,	Z =   145.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[553]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    15.000  mm,	Y =   220.000  mm,	Z =   145.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[554]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    15.000  mm,	Y =   172.000  mm,	Z =   145.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[555]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    15.000  mm,	Y =   152.000  mm,	Z =   145.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[556]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    45.000  mm,	Y =   220.000  mm,	Z =   145.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[557]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    45.000  mm,	Y =   172.000  mm,	Z =   145.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[558]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    45.000  mm,	Y =   152.000  mm,	Z =   145.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[559]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    75.000  mm,	Y =   220.000  mm,	Z =   145.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[560]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    75.000  mm,	Y =   172.000  mm,	Z =   145.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[561]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    75.000  mm,	Y =   152.000  mm,	Z =   145.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[562]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   105.000  mm,	Y =   220.000  mm,	Z =   145.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[563]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   105.000  mm,	Y =   172.000  mm,	Z =   145.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[564]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   105.000  mm,	Y =   152.000  mm,	Z =   145.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[565]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =  -105.000  mm,	Y =   220.000  mm,	Z =   180.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[566]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =  -105.000  mm,	Y =   172.000  mm,	Z =   180.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[567]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =  -105.000  mm,	Y =   152.000  mm,	Z =   180.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[568]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -75.000  mm,	Y =   220.000  mm,	Z =   180.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[569]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -75.000  mm,	Y =   172.000  mm,	Z =   180.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[570]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -75.000  mm,	Y =   152.000  mm,	Z =   180.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[571]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -45.000  mm,	Y =   220.000  mm,	Z =   180.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[572]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -45.000  mm,	Y =   172.000  mm,	Z =   180.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[573]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -45.000  mm,	Y =   152.000  mm,	Z =   180.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[574]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -15.000  mm,	Y =   220.000  mm,	Z =   180.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[575]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -15.000  mm,	Y =   172.000  mm,	Z =   180.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[576]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -15.000  mm,	Y =   152.000  mm,	Z =   180.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[577]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    15.000  mm,	Y =   220.000  mm,	Z =   180.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[578]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    15.000  mm,	Y =   172.000  mm,	Z =   180.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[579]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    15.000  mm,	Y =   152.000  mm,	Z =   180.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[580]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    45.000  mm,	Y =   220.000  mm,	Z =   180.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[581]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    45.000  mm,	Y =   172.000  mm,	Z =   180.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[582]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    45.000  mm,	Y =   152.000  mm,	Z =   180.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[583]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    75.000  mm,	Y =   220.000  mm,	Z =   180.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[584]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    75.000  mm,	Y =   172.000  mm,	Z =   180.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[585]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    75.000  mm,	Y =   152.000  mm,	Z =   180.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[586]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   105.000  mm,	Y =   220.000  mm,	Z =   180.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[587]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   105.000  mm,	Y =   172.000  mm,	Z =   180.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[588]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   105.000  mm,	Y =   152.000  mm,	Z =   180.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[589]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =  -105.000  mm,	Y =   220.000  mm,	Z =   215.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[590]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =  -105.000  mm,	Y =   172.000  mm,	Z =   215.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[591]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =  -105.000  mm,	Y =   152.000  mm,	Z =   215.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[592]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -75.000  mm,	Y =   220.000  mm,	Z =   215.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[593]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -75.000  mm,	Y =   172.000  mm,	Z =   215.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[594]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -75.000  mm,	Y =   152.000  mm,	Z =   215.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[595]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -45.000  mm,	Y =   220.000  mm,	Z =   215.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[596]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -45.000  mm,	Y =   172.000  mm,	Z =   215.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[597]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -45.000  mm,	Y =   152.000  mm,	Z =   215.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[598]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -15.000  mm,	Y =   220.000  mm,	Z =   215.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[599]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -15.000  mm,	Y =   172.000  mm,	Z =   215.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[600]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   -15.000  mm,	Y =   152.000  mm,	Z =   215.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[601]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    15.000  mm,	Y =   220.000  mm,	Z =   215.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[602]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    15.000  mm,	Y =   172.000  mm,	Z =   215.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[603]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    15.000  mm,	Y =   152.000  mm,	Z =   215.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[604]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    45.000  mm,	Y =   220.000  mm,	Z =   215.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[605]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    45.000  mm,	Y =   172.000  mm,	Z =   215.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[606]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    45.000  mm,	Y =   152.000  mm,	Z =   215.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[607]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    75.000  mm,	Y =   220.000  mm,	Z =   215.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[608]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    75.000  mm,	Y =   172.000  mm,	Z =   215.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[609]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =    75.000  mm,	Y =   152.000  mm,	Z =   215.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[610]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   105.000  mm,	Y =   220.000  mm,	Z =   215.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[611]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   105.000  mm,	Y =   172.000  mm,	Z =   215.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
P[612]{
   GP1:
	UF : 1, UT : 1,		CONFIG : 'F U T, 0, 1, 0',
	X =   105.000  mm,	Y =   152.000  mm,	Z =   215.000  mm,
	W =    90.000 deg,	P =     0.000 deg,	R =     0.000 deg
};
/END
