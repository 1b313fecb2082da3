C     Fortran-77 caller of the flat API: no module, implicit externals (symbols fc_*_),
C     plain arrays.  scripts/build_shared.sh --examples && build/legacy_f77
      PROGRAM F77DEMO
      IMPLICIT NONE
      INTEGER IH, IERR, NCON, NADH, NSLIP, NX
      PARAMETER (NX = 20)
      DOUBLE PRECISION FN, FX, FY, MZ, PN(NX*NX), PX(NX*NX), PY(NX*NX)
      CHARACTER*128 MSG
      CALL FC_INIT(IH, IERR)
      CALL FC_SET_MATERIAL(IH, 200D0, 200D0, 0.42D0, 0.42D0, IERR)
      CALL FC_SET_GRID(IH, NX, NX, -1.2857D0, 1.2857D0, -1.2857D0,
     &                 1.2857D0, IERR)
      CALL FC_SET_GAP_QUADRATIC(IH, 50D0, 50D0, IERR)
      CALL FC_SET_NORMAL_FORCE(IH, 9.1954D0, IERR)
      CALL FC_SET_FRICTION(IH, 0.4D0, IERR)
      CALL FC_SET_FORCES(IH, 2.0D0, 0D0, 0D0, IERR)
      CALL FC_CALCULATE(IH, IERR)
      CALL FC_GET_FORCES(IH, FN, FX, FY, MZ, IERR)
      CALL FC_GET_CONTACT_STATS(IH, NCON, NADH, NSLIP, IERR)
      CALL FC_GET_TRACTIONS(IH, NX*NX, PN, PX, PY, IERR)
      WRITE(*,'(A,3F10.5,3I5)') 'F77:', FN, FX, FY, NCON, NADH, NSLIP
C     steady rolling with creepages (xi, eta, phi [1/mm]) on the same handle; the edge flag
C     says whether the grid clips the contact (0: it does not)
      CALL FC_SET_FRICTION(IH, 0.4D0, IERR)
      CALL FC_SET_ROLLING(IH, 0.0021D0, 0.001D0, 0.003D0, IERR)
      CALL FC_CALCULATE(IH, IERR)
      IF (IERR .NE. 0) STOP 1
      CALL FC_GET_FORCES(IH, FN, FX, FY, MZ, IERR)
      CALL FC_GET_EDGE_CONTACT(IH, NCON, IERR)
      WRITE(*,'(A,3F10.5,I3)') 'F77 rolling:', FX, FY, MZ, NCON
      CALL FC_SET_FRICTION(IH, -1D0, IERR)
      CALL FC_GET_ERROR_MESSAGE(IH, MSG, 128, IERR)
      WRITE(*,'(A,A)') 'F77 error: ', MSG(1:INDEX(MSG, CHAR(0))-1)
      CALL FC_FINALIZE(IH, IERR)
      END
