C     LEGACY_LAWS: THE CONTACT LAW BY NAME FROM A FIXED-FORM, FORTRAN 77
C     STYLE PROGRAM: GCLCON, GCLSTP, GCLBEG (ONE POINT), GCMLRN, GCMLBG
C     (SEVERAL POINTS) TAKE THE LAW'S NAME AND ITS PARAMETERS FROM THE
C     REGISTRY ('POWER': K_C [N/M^P], P; 'EXPONENTIAL': F_S [N],
C     DELTA_S [M]). RUN FROM THE TOP FOLDER (IT WRITES
C     BUILD/LEGACY_LAWS.NML AND THE DRIVER'S FILES INTO
C     BUILD/LEGACY_LAWS/); NO INPUT.
C
C     1. THE EXPONENTIAL LAW: A SCENE WITH &CONTACT LAW = 'EXPONENTIAL'
C        RUN AS THE DRIVER RUNS IT (GCSCEN), THEN THE SAME STRUCTURE,
C        ROAD AND LAW THROUGH GCLCON: U, F AND DELTA EQUAL THE DRIVER'S
C        TO 1E-12 OF THE COLUMN'S LARGEST MAGNITUDE (IT PRINTS 16
C        DIGITS), AND THE BODY LIFTS OFF AND LANDS AGAIN; GCLBEG AND A
C        LOOP OF GCLADV CALLS EQUAL GCLCON BIT FOR BIT.
C     2. THE POWER LAW BY NAME EQUALS THE (K_C, P) DOORS BIT FOR BIT:
C        GCLCON AND GCLBEG + GCLADV = GCCONT, GCLSTP = GCSTEP, GCMLRN =
C        GCMRUN (A LAW A POINT AND ONE LAW FOR EVERY POINT), GCMLBG +
C        GCMSTP AND GCMBEG + GCMSTP = GCMRUN.
C     3. A BAD NAME, COUNT OR PARAMETER: IERR = 2 AND A MESSAGE NAMING
C        THE DOOR, THE LAW, THE PARAMETER WITH ITS UNIT, ITS RANGE AND
C        THE VALUE FOUND; A HANDLE OF 0 OR OF SEVERAL POINTS, A STEP
C        WITH NO RUN GOING ON: IERR = 2.
C     ONE LINE PER CHECK, 'ok: ...' OR 'FAIL: ...'; STOP 1 ON A FAILURE.
      PROGRAM LEGLAW
      USE GREENCONV_LEGACY
      USE GREENCONV_LEGACY_MULTI
      IMPLICIT NONE
      INTEGER NSTEP, NT, NC
      PARAMETER (NSTEP = 1500, NT = 200, NC = 3)
      DOUBLE PRECISION DT, XMASS, STIFF, XI, F0, XKC, P
      PARAMETER (DT = 1.0D-4, XMASS = 1.0D0, STIFF = 1.0D6, XI = 0.02D0)
      PARAMETER (F0 = 9.81D0, XKC = 2.0D6, P = 1.5D0)
      DOUBLE PRECISION ROAD(NSTEP), U(NSTEP, 2), F(NSTEP, 2)
      DOUBLE PRECISION DELTA(NSTEP, 2)
      DOUBLE PRECISION UREF(NSTEP), FREF(NSTEP), DREF(NSTEP)
      DOUBLE PRECISION PEXP(2), PPOW(2), PBAD(2), PPTS(2, NC)
      DOUBLE PRECISION POLRE(1), POLIM(1), RESRE(1), RESIM(1)
      DOUBLE PRECISION SHAPE(NC, 1), KCS(NC), PS(NC), F0S(NC)
      DOUBLE PRECISION ROADM(NT, NC), UM(NT, NC, 2), FM(NT, NC, 2)
      DOUBLE PRECISION DM(NT, NC, 2), R(NC), US(NC), FS(NC), DS(NC)
      DOUBLE PRECISION DEV, DU, DF, DD, ZERO
      INTEGER*8 HANDLE, HM, HNULL
      INTEGER IERR, IERR2, N, I, NBAD, NLIFT, NDIFF
      CHARACTER*300 MSG
      CHARACTER*40 PATH
C
      PATH = 'build/legacy_laws.nml'
      NBAD = 0
      HNULL = 0
      ZERO = 0.0D0
      PEXP(1) = 5.0D0
      PEXP(2) = 2.0D-4
      PPOW(1) = XKC
      PPOW(2) = P
C
C     1. THE EXPONENTIAL LAW AGAINST THE DRIVER'S RUN OF THE SAME SCENE.
      OPEN (UNIT=12, FILE=PATH, STATUS='REPLACE', IOSTAT=IERR)
      IF (IERR .NE. 0) THEN
         WRITE (*, '(2A)') 'FAIL: cannot write ', PATH
         STOP 1
      END IF
      WRITE (12, '(A)') '&scene name = ''legacy_laws'', output_dir = '
     &   //'''build/legacy_laws'', dt = 1.0e-4, n_steps = 1500 /'
      WRITE (12, '(A)') '&structure model = ''sdof'', mass = 1.0, '
     &   //'stiffness = 1.0e6, damping_ratio = 0.02 /'
      WRITE (12, '(A)') '&road profile = ''sine'', amplitude = 3.0e-4,'
     &   //' omega = 100.0 /'
      WRITE (12, '(A)') '&contact law = ''exponential'', '
     &   //'law_parameters = 5.0, 2.0e-4, preload = 9.81 /'
      WRITE (12, '(A)') '&convolution methods = ''exact'' /'
      CLOSE (12)
      CALL GCSCEN(PATH, IERR, MSG)
      CALL OKIF(IERR .EQ. 0 .OR. IERR .EQ. 4,
     &   'the driver runs the exponential scene', MSG, NBAD)
      CALL READRF('build/legacy_laws/legacy_laws_exact.dat', NSTEP,
     &   ROAD, UREF, FREF, DREF, NBAD)
      CALL GCSDOF(XMASS, STIFF, XI, DT, NSTEP, 'exact', HANDLE, IERR,
     &   MSG)
      CALL GCLCON(HANDLE, 'Exponential', 2, PEXP, F0, NSTEP, ROAD, U,
     &   F, DELTA, IERR, MSG)
      DU = DEV(NSTEP, U, UREF)
      DF = DEV(NSTEP, F, FREF)
      DD = DEV(NSTEP, DELTA, DREF)
      WRITE (*, '(A, 3(ES9.1, A))') 'legacy_laws: GCLCON vs driver: '
     &   //'max|du| =', DU, ', max|dF| =', DF, ', max|d delta| =', DD,
     &   ' (of max|.|; tolerance 1e-12)'
      CALL OKIF(IERR .EQ. 0 .AND. DU .LE. 1.0D-12 .AND. DF .LE. 1.0D-12
     &   .AND. DD .LE. 1.0D-12, 'GCLCON on the exponential law '
     &   //'equals the driver within 1e-12', MSG, NBAD)
      NLIFT = 0
      DO 10 N = 1, NSTEP
         IF (F(N, 1) .EQ. 0.0D0) NLIFT = NLIFT + 1
   10 CONTINUE
      CALL OKIF(NLIFT .GT. 0 .AND. NLIFT .LT. NSTEP/2,
     &   'the exponential run lifts off and lands again', ' ', NBAD)
      CALL GCLBEG(HANDLE, 'exponential', 2, PEXP, F0, IERR, MSG)
      IF (IERR .EQ. 0) CALL STEPL(HANDLE, NSTEP, ROAD, U, F, DELTA,
     &   NDIFF, IERR, MSG)
      CALL OKIF(IERR .EQ. 0 .AND. NDIFF .EQ. 0, 'GCLBEG + GCLADV '
     &   //'equals GCLCON on the exponential law bit for bit', MSG,
     &   NBAD)
C
C     2. THE POWER LAW BY NAME AGAINST THE (K_C, P) DOORS.
      CALL GCCONT(HANDLE, XKC, P, F0, NSTEP, ROAD, U(1, 1), F(1, 1),
     &   DELTA(1, 1), IERR, MSG)
      CALL GCLCON(HANDLE, 'power', 2, PPOW, F0, NSTEP, ROAD, U(1, 2),
     &   F(1, 2), DELTA(1, 2), IERR2, MSG)
      NDIFF = 0
      DO 20 N = 1, NSTEP
         IF (U(N, 1) .NE. U(N, 2) .OR. F(N, 1) .NE. F(N, 2) .OR.
     &      DELTA(N, 1) .NE. DELTA(N, 2)) NDIFF = NDIFF + 1
   20 CONTINUE
      CALL OKIF(IERR .EQ. 0 .AND. IERR2 .EQ. 0 .AND. NDIFF .EQ. 0,
     &   'GCLCON equals GCCONT on the power law bit for bit', MSG, NBAD)
      CALL GCLBEG(HANDLE, 'power', 2, PPOW, F0, IERR, MSG)
      IF (IERR .EQ. 0) CALL STEPL(HANDLE, NSTEP, ROAD, U, F, DELTA,
     &   NDIFF, IERR, MSG)
      CALL OKIF(IERR .EQ. 0 .AND. NDIFF .EQ. 0, 'GCLBEG + GCLADV '
     &   //'equals GCCONT on the power law bit for bit', MSG, NBAD)
      CALL GCRSET(HANDLE, IERR)
      DO 30 N = 1, 50
         CALL GCSTEP(HANDLE, XKC, P, F0, ROAD(N), U(N, 1), F(N, 1),
     &      DELTA(N, 1), IERR)
         IF (IERR .NE. 0) NBAD = NBAD + 1
   30 CONTINUE
      CALL GCRSET(HANDLE, IERR)
      DO 40 N = 1, 50
         CALL GCLSTP(HANDLE, 'POWER', 2, PPOW, F0, ROAD(N), U(N, 2),
     &      F(N, 2), DELTA(N, 2), IERR, MSG)
         IF (IERR .NE. 0) NBAD = NBAD + 1
   40 CONTINUE
      NDIFF = 0
      DO 50 N = 1, 50
         IF (U(N, 1) .NE. U(N, 2) .OR. F(N, 1) .NE. F(N, 2) .OR.
     &      DELTA(N, 1) .NE. DELTA(N, 2)) NDIFF = NDIFF + 1
   50 CONTINUE
      CALL OKIF(NDIFF .EQ. 0 .AND. F(50, 1) .GT. 0.0D0,
     &   'GCLSTP equals GCSTEP on the power law bit for bit', MSG, NBAD)
C
C     SEVERAL POINTS: ONE MODE OF UNIT MODAL MASS AT 1000 RAD/S.
      POLRE(1) = -0.02D0*1000.0D0
      POLIM(1) = 1000.0D0*SQRT(1.0D0 - 0.02D0**2)
      RESRE(1) = 0.0D0
      RESIM(1) = -1.0D0/(2.0D0*POLIM(1))
      SHAPE(1, 1) = 1.0D0
      SHAPE(2, 1) = 0.8D0
      SHAPE(3, 1) = 0.5D0
      DO 70 I = 1, NC
         KCS(I) = 1.0D6*DBLE(I)
         PS(I) = 1.5D0
         F0S(I) = 3.0D0
         PPTS(1, I) = KCS(I)
         PPTS(2, I) = PS(I)
         R(I) = 0.0D0
         DO 60 N = 1, NT
            ROADM(N, I) = 5.0D-5*SIN(200.0D0*DBLE(N - 1)*DT + DBLE(I))
   60    CONTINUE
   70 CONTINUE
      CALL GCMMOD(NC, 1, POLRE, POLIM, RESRE, RESIM, SHAPE, DT, NT,
     &   0.01D0, 'exact', HM, IERR, MSG)
      CALL OKIF(IERR .EQ. 0, 'GCMMOD: a convolver of 3 points', MSG,
     &   NBAD)
      CALL GCMRUN(HM, NC, NT, KCS, PS, F0S, ROADM, UM(1, 1, 1),
     &   FM(1, 1, 1), DM(1, 1, 1), IERR, MSG)
      CALL GCMLRN(HM, NC, NT, 'power', 2, NC, PPTS, F0S, ROADM,
     &   UM(1, 1, 2), FM(1, 1, 2), DM(1, 1, 2), IERR2, MSG)
      CALL SAMEM(NT*NC, UM, FM, DM, NDIFF)
      CALL OKIF(IERR .EQ. 0 .AND. IERR2 .EQ. 0 .AND. NDIFF .EQ. 0,
     &   'GCMLRN equals GCMRUN, a power law a point, bit for bit', MSG,
     &   NBAD)
      DO 80 I = 1, NC
         KCS(I) = XKC
   80 CONTINUE
      CALL GCMRUN(HM, NC, NT, KCS, PS, F0S, ROADM, UM(1, 1, 1),
     &   FM(1, 1, 1), DM(1, 1, 1), IERR, MSG)
      CALL GCMLRN(HM, NC, NT, 'power', 2, 1, PPOW, F0S, ROADM,
     &   UM(1, 1, 2), FM(1, 1, 2), DM(1, 1, 2), IERR2, MSG)
      CALL SAMEM(NT*NC, UM, FM, DM, NDIFF)
      CALL OKIF(IERR .EQ. 0 .AND. IERR2 .EQ. 0 .AND. NDIFF .EQ. 0,
     &   'GCMLRN equals GCMRUN, one power law for every point, bit for'
     &   //' bit', MSG, NBAD)
      CALL GCMBEG(HM, NC, KCS, PS, F0S, IERR, MSG)
      IF (IERR .EQ. 0) CALL STEPM(HM, NT, NC, ROADM, UM, FM, DM, NDIFF,
     &   IERR, MSG)
      CALL OKIF(IERR .EQ. 0 .AND. NDIFF .EQ. 0,
     &   'GCMBEG + GCMSTP equals the whole run bit for bit', MSG, NBAD)
      CALL GCMLBG(HM, NC, 'power', 2, 1, PPOW, F0S, IERR, MSG)
      IF (IERR .EQ. 0) CALL STEPM(HM, NT, NC, ROADM, UM, FM, DM, NDIFF,
     &   IERR, MSG)
      CALL OKIF(IERR .EQ. 0 .AND. NDIFF .EQ. 0,
     &   'GCMLBG + GCMSTP equals the whole run bit for bit', MSG, NBAD)
      CALL GCMLRN(HM, NC, NT, 'exponential', 2, 1, PEXP, F0S, ROADM,
     &   UM(1, 1, 2), FM(1, 1, 2), DM(1, 1, 2), IERR, MSG)
      CALL OKIF(IERR .EQ. 0 .AND. FM(NT, 1, 2) .GE. 0.0D0,
     &   'GCMLRN runs one exponential law at every point', MSG, NBAD)
C
C     3. BAD NAME, COUNT OR PARAMETER: IERR = 2 AND WHAT IS WRONG.
      CALL GCLCON(HANDLE, 'hertz', 2, PPOW, F0, NSTEP, ROAD, U, F,
     &   DELTA, IERR, MSG)
      CALL CHKMSG('unknown law', IERR, MSG, 'gclcon: ', '''hertz''',
     &   '''power'', ''exponential''', NBAD)
      CALL OKIF(F(1, 1) .EQ. 0.0D0 .AND. U(NSTEP, 1) .EQ. 0.0D0,
     &   'refused: u, F and delta 0', ' ', NBAD)
      CALL GCLCON(HANDLE, 'exponential', 1, PEXP, F0, NSTEP, ROAD, U,
     &   F, DELTA, IERR, MSG)
      CALL CHKMSG('one value for two', IERR, MSG, 'gclcon: ',
     &   'expected 2 parameters', '(F_s [N], delta_s [m]), found 1',
     &   NBAD)
      CALL GCLCON(HANDLE, 'power', 1000000, PPOW, F0, NSTEP, ROAD, U,
     &   F, DELTA, IERR, MSG)
      CALL CHKMSG('NPAR = 1000000 (not read)', IERR, MSG,
     &   'gclcon: NPAR = 1000000: give 0 to 3 parameter values', ' ',
     &   ' ', NBAD)
      PBAD(1) = 5.0D0
      PBAD(2) = -2.0D-4
      CALL GCLCON(HANDLE, 'exponential', 2, PBAD, F0, NSTEP, ROAD, U,
     &   F, DELTA, IERR, MSG)
      CALL CHKMSG('delta_s < 0', IERR, MSG, 'gclcon: contact law '
     &   //'''exponential'': parameter delta_s [m]', '> 0',
     &   'found -2.00E-04', NBAD)
      PBAD(1) = -1.0D0
      PBAD(2) = 1.5D0
      CALL GCLSTP(HANDLE, 'power', 2, PBAD, F0, ROAD(1), U(1, 1),
     &   F(1, 1), DELTA(1, 1), IERR, MSG)
      CALL CHKMSG('k_c < 0', IERR, MSG, 'gclstp: contact law '
     &   //'''power'': parameter k_c [N/m^p]', '> 0',
     &   'found -1.00E+00', NBAD)
      PBAD(1) = XKC
      PBAD(2) = ZERO/ZERO
      CALL GCLSTP(HANDLE, 'power', 2, PBAD, F0, ROAD(1), U(1, 1),
     &   F(1, 1), DELTA(1, 1), IERR, MSG)
      CALL CHKMSG('p NaN', IERR, MSG, 'gclstp: ', 'parameter p ',
     &   'must be finite', NBAD)
      CALL GCLCON(HNULL, 'power', 2, PPOW, F0, NSTEP, ROAD, U, F,
     &   DELTA, IERR, MSG)
      CALL CHKMSG('handle 0', IERR, MSG, 'gclcon: null convolver',
     &   ' ', ' ', NBAD)
      CALL GCMLRN(HM, NC, NT, 'power', 2, 2, PPTS, F0S, ROADM,
     &   UM, FM, DM, IERR, MSG)
      CALL CHKMSG('NLAW = 2 of 3 points', IERR, MSG, 'gcmlrn: ',
     &   'NLAW = 2', ' ', NBAD)
      PPTS(2, 2) = -1.5D0
      CALL GCMLRN(HM, NC, NT, 'power', 2, NC, PPTS, F0S, ROADM,
     &   UM, FM, DM, IERR, MSG)
      CALL CHKMSG('p < 0 at point 2', IERR, MSG, 'gcmlrn: point 2: ',
     &   'parameter p must be finite and > ', 'found -1.50E+00', NBAD)
      CALL GCMLBG(HM, NC, 'hertz', 2, 1, PPOW, F0S, IERR, MSG)
      CALL CHKMSG('GCMLBG unknown law', IERR, MSG, 'gcmlbg: ',
     &   'unknown law ''hertz''', ' ', NBAD)
      CALL GCMSTP(HM, NC, R, US, FS, DS, IERR, MSG)
      CALL OKIF(IERR .EQ. 2, 'a start refused ends the run going on',
     &   MSG, NBAD)
      CALL GCMLBG(HM, NC, 'power', -1, 1, PPOW, F0S, IERR, MSG)
      CALL CHKMSG('NPAR = -1', IERR, MSG, 'gcmlbg: ', 'NPAR = -1',
     &   ' ', NBAD)
      CALL GCLBEG(HANDLE, 'power', 2, PPOW, F0, IERR, MSG)
      PBAD(1) = -5.0D0
      PBAD(2) = 2.0D-4
      CALL GCLBEG(HANDLE, 'exponential', 2, PBAD, F0, IERR, MSG)
      CALL CHKMSG('GCLBEG F_s < 0', IERR, MSG, 'gclbeg: contact law '
     &   //'''exponential'': parameter F_s [N]', '> 0',
     &   'found -5.00E+00', NBAD)
      CALL GCLADV(HANDLE, ROAD(1), U(1, 1), F(1, 1), DELTA(1, 1), IERR,
     &   MSG)
      CALL CHKMSG('GCLADV after a start refused', IERR, MSG,
     &   'gcladv: no contact run is going on', ' ', ' ', NBAD)
      CALL GCLBEG(HANDLE, 'exponential', 2, PEXP, -1.0D0, IERR, MSG)
      CALL CHKMSG('GCLBEG F0 < 0', IERR, MSG, 'gclbeg: ',
     &   'the preload F0 must be finite and >= 0 N', ' ', NBAD)
      CALL GCLBEG(HM, 'power', 2, PPOW, F0, IERR, MSG)
      CALL CHKMSG('GCLBEG on 3 points', IERR, MSG,
     &   'gclbeg: the handle is a convolver of 3 points', ' ', ' ',
     &   NBAD)
      CALL GCLADV(HNULL, ROAD(1), U(1, 1), F(1, 1), DELTA(1, 1), IERR,
     &   MSG)
      CALL CHKMSG('GCLADV handle 0', IERR, MSG,
     &   'gcladv: null convolver handle', ' ', ' ', NBAD)
      CALL GCFREE(HANDLE)
      CALL GCMFRE(HM)
C
      IF (NBAD .NE. 0) THEN
         WRITE (*, '(A, I3, A)') 'legacy_laws: FAILED (', NBAD,
     &      ' checks)'
         STOP 1
      END IF
      WRITE (*, '(A)') 'legacy_laws: all checks passed'
      END
C
C     ONE CHECK: 'ok: WHAT' WHEN COND, ELSE 'FAIL: WHAT: MSG' AND NBAD
C     ONE MORE.
      SUBROUTINE OKIF(COND, WHAT, MSG, NBAD)
      IMPLICIT NONE
      LOGICAL COND
      CHARACTER*(*) WHAT, MSG
      INTEGER NBAD
      IF (COND) THEN
         WRITE (*, '(2A)') 'ok: ', WHAT
      ELSE
         WRITE (*, '(4A)') 'FAIL: ', WHAT, ': ', MSG(1:LEN_TRIM(MSG))
         NBAD = NBAD + 1
      END IF
      END
C
C     A REFUSAL: IERR = 2 AND THE MESSAGE HOLDS S1, S2 AND S3 (A BLANK
C     ONE IS NOT LOOKED FOR).
      SUBROUTINE CHKMSG(WHAT, IERR, MSG, S1, S2, S3, NBAD)
      IMPLICIT NONE
      CHARACTER*(*) WHAT, MSG, S1, S2, S3
      INTEGER IERR, NBAD
      LOGICAL FOUND
      FOUND = INDEX(MSG, S1) .GT. 0
      IF (LEN_TRIM(S2) .GT. 0) FOUND = FOUND .AND. INDEX(MSG, S2) .GT. 0
      IF (LEN_TRIM(S3) .GT. 0) FOUND = FOUND .AND. INDEX(MSG, S3) .GT. 0
      CALL OKIF(IERR .EQ. 2 .AND. FOUND, WHAT//': status 2 and the '
     &   //'message', MSG, NBAD)
      IF (IERR .EQ. 2 .AND. FOUND) WRITE (*, '(2A)') '    ',
     &   MSG(1:LEN_TRIM(MSG))
      END
C
C     A RUN STEPPED BY GCMSTP FROM THE START GCMBEG OR GCMLBG MADE: NDIFF
C     COUNTS THE STEPS WHOSE U, F OR DELTA DIFFER IN ANY BIT FROM THE
C     WHOLE RUN IN UM, FM, DM(..., 1); IERR THE FIRST FAULT.
      SUBROUTINE STEPM(HM, NT, NC, ROADM, UM, FM, DM, NDIFF, IERR, MSG)
      USE GREENCONV_LEGACY_MULTI
      IMPLICIT NONE
      INTEGER*8 HM
      INTEGER NT, NC, NDIFF, IERR, N, I
      DOUBLE PRECISION ROADM(NT, NC), UM(NT, NC, 2), FM(NT, NC, 2)
      DOUBLE PRECISION DM(NT, NC, 2), R(NC), U(NC), F(NC), D(NC)
      CHARACTER*(*) MSG
      NDIFF = 0
      DO 20 N = 1, NT
         DO 10 I = 1, NC
            R(I) = ROADM(N, I)
   10    CONTINUE
         CALL GCMSTP(HM, NC, R, U, F, D, IERR, MSG)
         IF (IERR .NE. 0) RETURN
         DO 15 I = 1, NC
            IF (U(I) .NE. UM(N, I, 1) .OR. F(I) .NE. FM(N, I, 1) .OR.
     &         D(I) .NE. DM(N, I, 1)) NDIFF = NDIFF + 1
   15    CONTINUE
   20 CONTINUE
      END
C
C     A RUN STEPPED BY GCLADV FROM THE START GCLBEG MADE: NDIFF COUNTS
C     THE STEPS WHOSE U, F OR DELTA DIFFER IN ANY BIT FROM THE WHOLE RUN
C     IN U, F, D(..., 1); IERR THE FIRST FAULT.
      SUBROUTINE STEPL(HANDLE, NSTEP, ROAD, U, F, D, NDIFF, IERR, MSG)
      USE GREENCONV_LEGACY
      IMPLICIT NONE
      INTEGER*8 HANDLE
      INTEGER NSTEP, NDIFF, IERR, N
      DOUBLE PRECISION ROAD(NSTEP), U(NSTEP, 2), F(NSTEP, 2)
      DOUBLE PRECISION D(NSTEP, 2), UN, FN, DN
      CHARACTER*(*) MSG
      NDIFF = 0
      DO 10 N = 1, NSTEP
         CALL GCLADV(HANDLE, ROAD(N), UN, FN, DN, IERR, MSG)
         IF (IERR .NE. 0) RETURN
         IF (UN .NE. U(N, 1) .OR. FN .NE. F(N, 1) .OR. DN .NE. D(N, 1))
     &      NDIFF = NDIFF + 1
   10 CONTINUE
      END
C
C     NDIFF: HOW MANY OF THE N VALUES OF U, F AND D (..., 1) DIFFER
C     FROM THEIR (..., 2) TWIN IN ANY BIT.
      SUBROUTINE SAMEM(N, U, F, D, NDIFF)
      IMPLICIT NONE
      INTEGER N, NDIFF, K
      DOUBLE PRECISION U(N, 2), F(N, 2), D(N, 2)
      NDIFF = 0
      DO 10 K = 1, N
         IF (U(K, 1) .NE. U(K, 2) .OR. F(K, 1) .NE. F(K, 2) .OR.
     &      D(K, 1) .NE. D(K, 2)) NDIFF = NDIFF + 1
   10 CONTINUE
      END
C
C     ROAD, U, F AND DELTA OF THE DRIVER'S FILE (COLUMNS T [S],
C     U_ROAD [M], U [M], F_CONTACT [N], DELTA [M]).
      SUBROUTINE READRF(FILE, NSTEP, ROAD, U, F, D, NBAD)
      IMPLICIT NONE
      CHARACTER*(*) FILE
      INTEGER NSTEP, NBAD
      DOUBLE PRECISION ROAD(NSTEP), U(NSTEP), F(NSTEP), D(NSTEP)
      CHARACTER*300 LINE
      DOUBLE PRECISION T
      INTEGER N, IOS
      OPEN (UNIT=11, FILE=FILE, STATUS='OLD', IOSTAT=IOS)
      IF (IOS .NE. 0) THEN
         WRITE (*, '(2A)') 'FAIL: cannot open ', FILE
         STOP 1
      END IF
      N = 0
   10 READ (11, '(A)', END=20) LINE
      IF (LINE(1:1) .EQ. '#') GOTO 10
      N = N + 1
      IF (N .GT. NSTEP) GOTO 20
      READ (LINE, *) T, ROAD(N), U(N), F(N), D(N)
      GOTO 10
   20 CLOSE (11)
      CALL OKIF(N .EQ. NSTEP, 'the driver''s file has a row a step',
     &   FILE, NBAD)
      IF (N .NE. NSTEP) STOP 1
      END
C
C     MAX|A - B|/MAX|B| OVER N VALUES.
      DOUBLE PRECISION FUNCTION DEV(N, A, B)
      IMPLICIT NONE
      INTEGER N, K
      DOUBLE PRECISION A(N), B(N), SCALE, WORST
      SCALE = 0.0D0
      WORST = 0.0D0
      DO 10 K = 1, N
         SCALE = MAX(SCALE, ABS(B(K)))
         WORST = MAX(WORST, ABS(A(K) - B(K)))
   10 CONTINUE
      DEV = WORST/SCALE
      END
