C     LEGACY_MODES_FILE: A CONTACT PATCH FROM THE NORMAL MODES OF A
C     USER'S FE MODEL (A UNIVERSAL FILE, DATASETS 15 AND 55), STEPPED
C     FROM A FIXED-FORM, FORTRAN 77 STYLE PROGRAM'S OWN TIME LOOP
C     THROUGH GREENCONV_LEGACY_MULTI, AND THE ACCURACY A HOST ASKS.
C
C     1. TEST/DATA/UFF/MODES_PLATE.UFF (A PLATE'S 32 MODES AT 9 NODES,
C        SHAPES IN +Z, DAMPING 3 % WHERE THE FILE GIVES NONE): GCMMFL
C        MAKES 'EXACT' ON EVERY NODE (GCMPTS: THEIR LABELS AND X, Y); A
C        HERTZ LAW PER NODE, KC = 1E7 N/M**1.5, 300 N SHARED; NODE I
C        SEES THE ROAD AT 0.3 M + (X(I) - MEAN X) + V*T, V = 5 M/S.
C        THIS PROGRAM'S LOOP (ONE GCMSTP A STEP) AGAINST THE LIBRARY'S
C        WHOLE RUN GCMRUN: EQUAL BIT FOR BIT. GCMEST: MODES GIVEN
C        EXACTLY HAVE NO MODEL TERM; AFTER THE WHOLE RUN IT HOLDS THAT
C        RUN'S TIME-STEP TERM (ITS RUNS AT 2*DT AND 4*DT), ABOUT 5E-4
C        AT 80 US, SO GCMACC ACCEPTS 1E-2.
C     2. A RECEPTANCE FILE THIS PROGRAM WRITES (ONE MASS-SPRING SYSTEM,
C        50 HZ, MEASURED TO 200 HZ ONLY), 'FFT' AT DT = 1 MS: ITS OWN
C        ESTIMATE (GCMEST) SAYS WHAT THE BAND LEAVES OUT; ASKED HALF OF
C        IT (GCMACC), GCMACC AND GCMRUN END WITH IERR = 4 ("RAN, BUT
C        OUTSIDE THE ACCURACY ASKED"), THE RESULTS WHOLE.
C     RUN FROM THE TOP FOLDER (IT READS TEST/DATA/UFF/). STOP 1 ON A
C     MISMATCH OR AN UNEXPECTED STATUS.
      PROGRAM LEGMOD
      USE GREENCONV_LEGACY_MULTI
      IMPLICIT NONE
      INTEGER NP, NSTEP
      PARAMETER (NP = 9, NSTEP = 500)
      DOUBLE PRECISION DT, V, XKC0, P0, FTOT
      PARAMETER (DT = 8.0D-5, V = 5.0D0, XKC0 = 1.0D7, P0 = 1.5D0)
      PARAMETER (FTOT = 300.0D0)
      DOUBLE PRECISION XKC(NP), P(NP), F0(NP), ROAD(NSTEP, NP)
      DOUBLE PRECISION U(NSTEP, NP), F(NSTEP, NP), DELTA(NSTEP, NP)
      DOUBLE PRECISION R(NP), UI(NP), FI(NP), DI(NP), X(NP), Y(NP)
      DOUBLE PRECISION XMEAN, WORST, PEAK, EST, ROADH
      DOUBLE PRECISION SKC(1), SP(1), SF0(1), SROAD(200, 1)
      DOUBLE PRECISION SU(200, 1), SF(200, 1), SD(200, 1), FLAST
      INTEGER*8 HANDLE
      INTEGER IERR, I, N, NODE(NP)
      CHARACTER*400 MSG
C
C     1. EXACT ON THE MODES FILE, STEPPED BY THIS PROGRAM.
      CALL GCMMFL('test/data/uff/modes_plate.uff', 3, 0.03D0, 0.0D0,
     &            'EXACT', DT, NSTEP, 0.01D0, HANDLE, IERR, MSG)
      IF (IERR .NE. 0) GOTO 900
      CALL GCMPTS(HANDLE, NP, NODE, X, Y, IERR, MSG)
      IF (IERR .NE. 0) GOTO 900
      XMEAN = 0.0D0
      DO 10 I = 1, NP
         XMEAN = XMEAN + X(I)/NP
   10 CONTINUE
      DO 30 I = 1, NP
         XKC(I) = XKC0
         P(I) = P0
         F0(I) = FTOT/NP
         DO 20 N = 1, NSTEP
            ROAD(N, I) = ROADH(0.3D0 + (X(I) - XMEAN)
     &                         + V*DBLE(N - 1)*DT)
   20    CONTINUE
   30 CONTINUE
      CALL GCMRUN(HANDLE, NP, NSTEP, XKC, P, F0, ROAD, U, F, DELTA,
     &            IERR, MSG)
      IF (IERR .NE. 0) GOTO 900
      CALL GCMBEG(HANDLE, NP, XKC, P, F0, IERR, MSG)
      IF (IERR .NE. 0) GOTO 900
      WORST = 0.0D0
      PEAK = 0.0D0
      DO 50 N = 1, NSTEP
         DO 40 I = 1, NP
            R(I) = ROAD(N, I)
   40    CONTINUE
         CALL GCMSTP(HANDLE, NP, R, UI, FI, DI, IERR, MSG)
         IF (IERR .NE. 0) GOTO 900
         DO 45 I = 1, NP
            WORST = MAX(WORST, ABS(FI(I) - F(N, I)),
     &                  ABS(UI(I) - U(N, I)), ABS(DI(I) - DELTA(N, I)))
            PEAK = MAX(PEAK, F(N, I))
   45    CONTINUE
   50 CONTINUE
      CALL GCMEST(HANDLE, EST, IERR, MSG)
      IF (IERR .NE. 0) GOTO 900
      IF (.NOT. (EST .GT. 0.0D0 .AND. EST .LT. 1.0D-2)) GOTO 920
      CALL GCMACC(HANDLE, 1.0D-2, IERR, MSG)
      IF (IERR .NE. 0) GOTO 900
      CALL GCMFRE(HANDLE)
      WRITE (*, '(A, I4, A, I4, A, F7.1, A, 1PE9.2)')
     &   ' legacy_modes_file: exact on nodes', NODE(1), ' to',
     &   NODE(NP), ', GCMSTP loop vs GCMRUN: peak force', PEAK,
     &   ' N, max difference', WORST
      WRITE (*, '(A, 1PE9.2)')
     &   ' legacy_modes_file: estimate after the whole run', EST
      IF (WORST .NE. 0.0D0) GOTO 910
C
C     2. FFT ON A BAND-LIMITED RECEPTANCE: OUTSIDE THE ACCURACY ASKED.
      CALL WRFILE('build/legacy_modes_file_sdof.uff')
      CALL GCMFIL('build/legacy_modes_file_sdof.uff', 'FFT', 1.0D-3,
     &            200, 0.01D0, 6, HANDLE, IERR, MSG)
      IF (IERR .NE. 0) GOTO 900
      CALL GCMEST(HANDLE, EST, IERR, MSG)
      IF (IERR .NE. 0) GOTO 900
      IF (.NOT. (EST .GT. 0.0D0)) GOTO 920
      SKC(1) = 1.0D6
      SP(1) = 1.5D0
      SF0(1) = 10.0D0
      DO 60 N = 1, 200
         SROAD(N, 1) = 1.0D-5*SIN(0.3D0*DBLE(N - 1))
   60 CONTINUE
      CALL GCMRUN(HANDLE, 1, 200, SKC, SP, SF0, SROAD, SU, SF, SD,
     &            IERR, MSG)
      IF (IERR .NE. 0) GOTO 900
      FLAST = SF(200, 1)
      CALL GCMACC(HANDLE, 0.5D0*EST, IERR, MSG)
      IF (IERR .NE. 4) GOTO 900
      CALL GCMRUN(HANDLE, 1, 200, SKC, SP, SF0, SROAD, SU, SF, SD,
     &            IERR, MSG)
      IF (IERR .NE. 4) GOTO 900
      IF (SF(200, 1) .NE. FLAST) GOTO 910
      CALL GCMFRE(HANDLE)
      WRITE (*, '(A, 1PE9.2, A)')
     &   ' legacy_modes_file: fft to 200 Hz estimates', EST,
     &   '; asked half of it: IERR = 4, the run whole'
      STOP
  900 WRITE (*, '(A, I2, 2A)') ' legacy_modes_file: IERR = ', IERR,
     &   ': ', TRIM(MSG)
      STOP 1
  910 WRITE (*, '(A)') ' FAIL: legacy_modes_file: runs differ'
      STOP 1
  920 WRITE (*, '(A, 1PE9.2)') ' FAIL: legacy_modes_file: estimate',
     &   EST
      STOP 1
      END
C
C     THE ROAD HEIGHT [M] AT X [M]: 0.1 MM AT 50 MM, 0.05 MM AT 21 MM.
      DOUBLE PRECISION FUNCTION ROADH(X)
      IMPLICIT NONE
      DOUBLE PRECISION X, PI
      PARAMETER (PI = 3.14159265358979323846D0)
      ROADH = 1.0D-4*SIN(2.0D0*PI*X/0.05D0)
     &      + 0.5D-4*SIN(2.0D0*PI*X/0.021D0)
      END
C
C     A UNIVERSAL FILE OF ONE NODE (DATASET 15) AND THE RECEPTANCE
C     G(F) [M/N] OF A MASS-SPRING SYSTEM (1.5 KG, 50 HZ, 2 %) FROM 0 TO
C     200 HZ BY 2.5 HZ (DATASET 58, COMPLEX DOUBLE).
      SUBROUTINE WRFILE(PATH)
      IMPLICIT NONE
      CHARACTER*(*) PATH
      DOUBLE PRECISION PI, XM, FN, ZETA, DF, WN, XK, C, W, RE, XIM, D
      DOUBLE PRECISION VALS(2*81)
      PARAMETER (PI = 3.14159265358979323846D0, XM = 1.5D0)
      PARAMETER (FN = 50.0D0, ZETA = 0.02D0, DF = 2.5D0)
      INTEGER L, IU
      WN = 2.0D0*PI*FN
      XK = XM*WN*WN
      C = 2.0D0*ZETA*XM*WN
      DO 10 L = 0, 80
         W = 2.0D0*PI*DF*L
         RE = XK - XM*W*W
         XIM = C*W
         D = RE*RE + XIM*XIM
         VALS(2*L + 1) = RE/D
         VALS(2*L + 2) = -XIM/D
   10 CONTINUE
      OPEN (NEWUNIT=IU, FILE=PATH, STATUS='REPLACE', ACTION='WRITE')
      WRITE (IU, '(A)') '    -1', '    15',
     &   '         1         0         0         1  0.00000E+00  0.0000'
     &   //'0E+00  0.00000E+00', '    -1', '    -1', '    58',
     &   'legacy_modes_file', 'SDOF', 'NONE', 'NONE', 'NONE',
     &   '    4         0    0         0       NONE         1   3     '
     &   //'  NONE         1   3',
     &   '         6        81         1  0.00000e+00  2.50000e+00  0.0'
     &   //'0000e+00',
     &   '        18    0    0    0 NONE                 Hz          '
     &   //'        ',
     &   '         8    1    0    0 NONE                 m           '
     &   //'        ',
     &   '        13    0    1    0 NONE                 N           '
     &   //'        ',
     &   '         0    0    0    0 NONE                 NONE        '
     &   //'        '
      WRITE (IU, '(4(1PE20.11))') VALS
      WRITE (IU, '(A)') '    -1'
      CLOSE (IU)
      END
