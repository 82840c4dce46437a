C     LEGACY_PATCH_FILE: THE SHIPPED 2D CONTACT PATCH OF
C     DATA/PATCH_ROAD.NML RUN FROM A FIXED-FORM, FORTRAN 77 STYLE
C     PROGRAM THROUGH THE PLAIN SUBROUTINES OF GREENCONV_LEGACY_MULTI,
C     WITH ITS OWN TIME LOOP, AND CHECKED AGAINST THE DRIVER'S FILES.
C
C     DATA/PATCH_GREEN.UFF HOLDS THE RECEPTANCES BETWEEN THE 12 POINTS
C     OF A 4 X 3 PATCH UNDER A TYRE BELT AND THE POINTS' COORDINATES.
C     GCMFIL READS IT AND IDENTIFIES ITS SHARED POLES ONCE (DIAGRAM UP
C     TO 60 MODES, AS THE SCENE'S MAX_ORDER) FOR 'MODAL' (EXPLICIT, ON
C     THE IDENTIFIED MODES); GCMMTH BUILDS 'DIRECT' (G_IJ FROM THE
C     INVERSE FFT OF THE FILE'S RECEPTANCES) ON THE SAME FILE WITHOUT
C     A SECOND IDENTIFICATION. THE SCENE'S CONVENTIONS: PRELOAD 3000 N
C     SHARED EVENLY, A LINEAR LAW KC = 5E4 N/M PER POINT, POINT I AT
C     X(I) SEES THE ROAD OF DATA/ROAD_SAMPLE.DAT (LINEAR INTERPOLATION)
C     AT XSTART + (X(I) - MEAN X) + V*T, XSTART = 0.5 M, V = 5 M/S,
C     DT = 2E-4 S, 3000 STEPS; ONE GCMSTP CALL A STEP.
C
C     INPUT (ONE LINE ON STANDARD INPUT): THE FOLDER HOLDING THE
C     DRIVER'S PATCH_ROAD_MODAL.DAT AND PATCH_ROAD_DIRECT.DAT FOR
C     DATA/PATCH_ROAD.NML (E.G. OUT). RUN FROM THE TOP FOLDER. THE
C     ROAD HEIGHTS AND FORCES MUST EQUAL THE DRIVER'S BIT FOR BIT (THE
C     SAME ROUTINES ON THE SAME NUMBERS, PRINTED WITH 17 DIGITS).
C     STOP 1 ON A MISMATCH OR AN ERROR.
      PROGRAM LEGPTF
      USE GREENCONV_LEGACY_MULTI
      IMPLICIT NONE
      INTEGER NP, NSTEP, NRMAX
      PARAMETER (NP = 12, NSTEP = 3000, NRMAX = 20000)
      DOUBLE PRECISION DT, V, XSTART, XKC0, FTOT
      PARAMETER (DT = 2.0D-4, V = 5.0D0, XSTART = 0.5D0)
      PARAMETER (XKC0 = 5.0D4, FTOT = 3000.0D0)
      DOUBLE PRECISION RX(NRMAX), RH(NRMAX)
      DOUBLE PRECISION X(NP), Y(NP), XKC(NP), P(NP), F0(NP)
      DOUBLE PRECISION ROAD(NSTEP, NP), FREF(NSTEP, NP)
      DOUBLE PRECISION RREF(NSTEP, NP)
      DOUBLE PRECISION R(NP), UI(NP), FI(NP), DI(NP)
      DOUBLE PRECISION XSUM, WORST, WROAD, PEAK, EWORST, EMEAN, ROADH
      DOUBLE PRECISION T, XP, UR, U, F
      INTEGER*8 HANDLE(2)
      INTEGER NODE(NP), IERR, NC, NPOLE, NR, I, N, M, NSIZE, ROW, LS
      CHARACTER*300 MSG, DIR, FNAME
      CHARACTER*400 LINE
      CHARACTER*4000 SUMMRY
      CHARACTER*6 METHOD(2)
      DATA METHOD /'modal', 'direct'/
C
      READ (*, '(A)') DIR
C     THE ROAD FILE: "X HEIGHT" A LINE, "#" LINES ARE COMMENTS.
      NR = 0
      OPEN (10, FILE='data/road_sample.dat', STATUS='OLD', ERR=920)
    5 READ (10, '(A)', END=8) LINE
      IF (LINE(1:1) .EQ. '#' .OR. LINE .EQ. ' ') GOTO 5
      NR = NR + 1
      IF (NR .GT. NRMAX) GOTO 920
      READ (LINE, *) RX(NR), RH(NR)
      GOTO 5
    8 CLOSE (10)
C
      CALL GCMFIL('data/patch_green.uff', METHOD(1), DT, NSTEP, 0.01D0,
     &            60, HANDLE(1), IERR, MSG)
      IF (IERR .NE. 0) GOTO 900
      CALL GCMMTH(HANDLE(1), METHOD(2), DT, NSTEP, 0.01D0, HANDLE(2),
     &            IERR, MSG)
      IF (IERR .NE. 0) GOTO 900
      CALL GCMNPT(HANDLE(1), NC, IERR, MSG)
      IF (IERR .NE. 0) GOTO 900
      IF (NC .NE. NP) GOTO 930
      CALL GCMPTS(HANDLE(1), NP, NODE, X, Y, IERR, MSG)
      IF (IERR .NE. 0) GOTO 900
      CALL GCMSUM(HANDLE(1), EWORST, EMEAN, NPOLE, SUMMRY, IERR)
      IF (IERR .NE. 0) GOTO 900
      WRITE (*, '(A, I3, A, I3, A, 1PE9.2, A, 1PE9.2)')
     &   ' legacy_patch_file: data/patch_green.uff:', NP, ' points,',
     &   NPOLE, ' shared poles, E of the modes worst', EWORST,
     &   ', mean', EMEAN
C
C     THE SCENE'S CONVENTIONS.
      XSUM = 0.0D0
      DO 10 I = 1, NP
         XSUM = XSUM + X(I)
   10 CONTINUE
      DO 30 I = 1, NP
         XKC(I) = XKC0
         P(I) = 1.0D0
         F0(I) = FTOT/NP
         XP = XSTART + (X(I) - XSUM/NP)
         DO 20 N = 1, NSTEP
            ROAD(N, I) = ROADH(XP + V*(DBLE(N - 1)*DT), RX, RH, NR)
   20    CONTINUE
   30 CONTINUE
C
      DO 90 M = 1, 2
C        THE DRIVER'S COLUMNS: T X U_ROAD U F_CONTACT ..., A ROW PER
C        STEP AND POINT.
         LS = LEN_TRIM(DIR)
         FNAME = DIR(1:LS)//'/patch_road_'//TRIM(METHOD(M))//'.dat'
         OPEN (11, FILE=FNAME, STATUS='OLD', ERR=940)
         ROW = 0
   40    READ (11, '(A)', END=45) LINE
         IF (LINE(1:1) .EQ. '#') GOTO 40
         IF (ROW .GE. NP*NSTEP) GOTO 45
         READ (LINE, *) T, XP, UR, U, F
         RREF(ROW/NP + 1, MOD(ROW, NP) + 1) = UR
         FREF(ROW/NP + 1, MOD(ROW, NP) + 1) = F
         ROW = ROW + 1
         GOTO 40
   45    CLOSE (11)
         IF (ROW .NE. NP*NSTEP) GOTO 940
C
         CALL GCMBEG(HANDLE(M), NP, XKC, P, F0, IERR, MSG)
         IF (IERR .NE. 0) GOTO 900
         WORST = 0.0D0
         WROAD = 0.0D0
         PEAK = 0.0D0
         DO 60 N = 1, NSTEP
            DO 50 I = 1, NP
               R(I) = ROAD(N, I)
   50       CONTINUE
            CALL GCMSTP(HANDLE(M), NP, R, UI, FI, DI, IERR, MSG)
            IF (IERR .NE. 0) GOTO 900
            DO 55 I = 1, NP
               WORST = MAX(WORST, ABS(FI(I) - FREF(N, I)))
               WROAD = MAX(WROAD, ABS(R(I) - RREF(N, I)))
               PEAK = MAX(PEAK, ABS(FREF(N, I)))
   55       CONTINUE
   60    CONTINUE
         CALL GCMDSC(HANDLE(M), NSIZE, MSG, IERR)
         WRITE (*, '(3A)') ' legacy_patch_file: ', TRIM(MSG)
         WRITE (*, '(3A, F7.1, A, 1PE9.2, A, 1PE9.2, A)')
     &      ' legacy_patch_file: ', TRIM(METHOD(M)),
     &      ', GCMSTP loop vs the driver: peak force', PEAK,
     &      ' N, max |dF|', WORST, ' N, max |d u_road|', WROAD, ' m'
         IF (WORST .NE. 0.0D0 .OR. WROAD .NE. 0.0D0) GOTO 910
   90 CONTINUE
      CALL GCMFRE(HANDLE(1))
      CALL GCMFRE(HANDLE(2))
C     NO STOP HERE: GFORTRAN'S STOP WOULD PRINT THE UNDERFLOW FLAGS
C     THE IDENTIFICATION RAISES (HARMLESS).
      GOTO 999
  900 WRITE (*, '(A, I2, 2A)') ' legacy_patch_file: IERR = ', IERR,
     &   ': ', TRIM(MSG)
      STOP 1
  910 WRITE (*, '(A)') ' FAIL: legacy_patch_file: differs from the'
     &   //' driver'
      STOP 1
  920 WRITE (*, '(A)') ' legacy_patch_file: cannot read'
     &   //' data/road_sample.dat (run from the top folder)'
      STOP 1
  930 WRITE (*, '(A, I4)') ' legacy_patch_file: points in the file:', NC
      STOP 1
  940 WRITE (*, '(2A)') ' legacy_patch_file: cannot read the rows of ',
     &   TRIM(FNAME)
      STOP 1
  999 CONTINUE
      END
C
C     THE ROAD HEIGHT [M] AT XP [M]: LINEAR INTERPOLATION IN THE TABLE
C     (RX, RH) OF NR POINTS, THE END VALUES BEYOND IT; THE SAME
C     INTERVAL SEARCH AND WEIGHT AS THE LIBRARY'S ROAD READER.
      DOUBLE PRECISION FUNCTION ROADH(XP, RX, RH, NR)
      IMPLICIT NONE
      INTEGER NR, LOW, HIGH, MID
      DOUBLE PRECISION XP, RX(NR), RH(NR), W
      IF (XP .LE. RX(1)) THEN
         ROADH = RH(1)
         RETURN
      END IF
      IF (XP .GE. RX(NR)) THEN
         ROADH = RH(NR)
         RETURN
      END IF
      LOW = 1
      HIGH = NR
   10 IF (HIGH - LOW .GT. 1) THEN
         MID = (LOW + HIGH)/2
         IF (RX(MID) .LE. XP) THEN
            LOW = MID
         ELSE
            HIGH = MID
         END IF
         GOTO 10
      END IF
      W = (XP - RX(LOW))/(RX(LOW + 1) - RX(LOW))
      ROADH = (1.0D0 - W)*RH(LOW) + W*RH(LOW + 1)
      END
