!> Multi-point contact for Fortran 77 style programs: plain subroutines `GCM...` (scalars,
!> explicit-shape arrays, strings), after `use greenconv_legacy_multi`, on the shared layer
!> greenconv_api_multi_handle.
!>
!> A multi-point convolver is an `INTEGER*8` handle (0: none), made by `GCMMOD` (poles,
!> residues and mode shapes at the points), `GCMSMP` (samples g_ij(m*dt)) or `GCMFIL` (a
!> universal file of a Green's matrix; `GCMMTH` another method on the file already read) or
!> `GCMMFL` (a universal file of normal modes, datasets 15/2411 and 55), freed by `GCMFRE`.
!> Every routine returns `IERR` (0 success, 2 bad input or a 0 handle, 3 a step that diverged
!> or did not converge, 4 a run outside the accuracy asked with `GCMACC`: the method's own
!> estimate, `GCMEST`, exceeds it) and a message `ERRMSG` (blank on success). Arrays are
!> Fortran's: SHAPE(NC, NMODE), G(NSAMP, NC, NC) with G(M+1, I, J) = g_ij(M*DT),
!> ROAD(NSTEP, NC), W0(NC, NC). SI units: poles [rad/s], g [m/(N*s)], k_c [N/m^p], forces [N],
!> displacements and heights [m].
module greenconv_legacy_multi
    use, intrinsic :: iso_c_binding, only: c_loc, c_f_pointer
    use, intrinsic :: iso_fortran_env, only: int64
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type, fatal_error
    use greenconv_core_text, only: int_text, lower_text
    use greenconv_model_point_modes, only: point_modes
    use greenconv_contact_laws, only: contact_law, new_law, new_laws, replicate_law, max_law_parameters
    use greenconv_api_multi_handle, only: modes_multi_box, samples_multi_box, patch_modes, &
                                          check_box, set_multi_options, start_multi_box, advance_multi_box, &
                                          run_multi_box, file_multi_box, method_multi_box, check_file_box, &
                                          file_e_modes, modes_file_box, box_points, &
                                          file_summary, run_request
    use greenconv_api_doors, only: report, handle_address, address_handle, need_count
    use greenconv_api_handle, only: convolver_box, box_at, free_box, reset_box, describe_box, check_steps
    use greenconv_api_budget, only: set_box_accuracy
    implicit none
    private

    public :: gcmmod, gcmsmp, gcmplt, gcmfre, gcmnpt, gcmhis, gcmpsh, gcmw0, gcmrst, gcmdsc
    public :: gcmopt, gcmbeg, gcmstp, gcmrun, gcmfil, gcmmth, gcmpts, gcmsum, gcmmfl, gcmest, gcmacc
    public :: gcest, gcacc
    public :: gcmlbg, gcmlrn
    public :: door_laws

    !> What a 0 handle's message says.
    character(len=*), parameter :: null_handle = 'the handle is 0: make a convolver with GCMMOD, GCMSMP, GCMFIL or GCMMFL'
    !> What a 0 single-point handle's message says.
    character(len=*), parameter :: point_null_handle = 'the handle is 0: make a convolver with GCSDOF, GCMODE, ' &
                                                       //'GCSAMP or GCFRF'

contains

    !> Multi-point convolver from modes shared by NC points:
    !> g_ij(t) = sum_k SHAPE(i,k)*SHAPE(j,k)*2*Re(r_k*exp(lambda_k*t)).
    subroutine gcmmod(nc, nmode, polre, polim, resre, resim, shape, dt, nstep, tol, method, handle, ierr, errmsg)
        !> Number of points N_c, >= 1.
        integer, intent(in) :: nc
        !> Number of modes N_m, >= 1.
        integer, intent(in) :: nmode
        !> Real parts of the poles [rad/s], < 0.
        real(dp), intent(in) :: polre(*)
        !> Imaginary parts of the poles [rad/s], > 0.
        real(dp), intent(in) :: polim(*)
        !> Real parts of the modal residues r_k.
        real(dp), intent(in) :: resre(*)
        !> Imaginary parts of the modal residues.
        real(dp), intent(in) :: resim(*)
        !> Mode shapes phi_ik at the points (NC x NMODE).
        real(dp), intent(in) :: shape(max(nc, 0), *)
        !> Time step dt [s], > 0.
        real(dp), intent(in) :: dt
        !> Number of steps N_t of the run, >= 1.
        integer, intent(in) :: nstep
        !> Truncation fraction of max |g_ij| for 'direct' and 'fft', in [0, 1) (0.01: the paper's).
        real(dp), intent(in) :: tol
        !> Method: 'modal' (= 'recursive'), 'exact', 'direct' or 'fft' (any case).
        character(len=*), intent(in) :: method
        !> Handle of the new modal multi-point convolver; 0 on failure.
        integer(int64), intent(out) :: handle
        !> Status: 0 success, 2 for NC, NMODE, a pole, residue, dt, nstep, tol or method out of range.
        integer, intent(out) :: ierr
        !> Message on failure, blank on success.
        character(len=*), intent(out) :: errmsg

        type(error_type), allocatable :: error
        type(convolver_box), pointer :: box
        integer :: n_m

        box => null()
        n_m = max(nmode, 0)
        call need_count('gcmmod', 'NC', nc, 1, 'point', error)
        if (.not. allocated(error)) then
            call modes_multi_box('gcmmod', polre(1:n_m), polim(1:n_m), resre(1:n_m), resim(1:n_m), shape(:, 1:n_m), &
                                 run_request(method, dt, tol, nstep), box, error)
        end if
        call new_handle(box, handle, error, ierr, errmsg)
    end subroutine gcmmod

    !> Multi-point convolver from samples G(M+1, I, J) = g_ij(M*DT) ('direct' or 'fft').
    subroutine gcmsmp(nc, nsamp, g, dt, nstep, tol, method, handle, ierr, errmsg)
        !> Number of points N_c, >= 1.
        integer, intent(in) :: nc
        !> Number of samples of each g_ij, >= 2.
        integer, intent(in) :: nsamp
        !> Samples [m/(N*s)] (NSAMP x NC x NC).
        real(dp), intent(in) :: g(max(nsamp, 0), max(nc, 0), *)
        !> Time step dt [s] of the samples and the run, > 0.
        real(dp), intent(in) :: dt
        !> Number of steps N_t of the run, >= 1.
        integer, intent(in) :: nstep
        !> Truncation fraction of max |g_ij|, in [0, 1) (0.01: the paper's).
        real(dp), intent(in) :: tol
        !> Method: 'direct' or 'fft' (any case).
        character(len=*), intent(in) :: method
        !> Handle of the new convolver on the sampled matrix; 0 on failure.
        integer(int64), intent(out) :: handle
        !> Status: 0 success, 2 for NC, too few samples, or a dt, nstep, tol or method out of range.
        integer, intent(out) :: ierr
        !> Message on failure, blank on success.
        character(len=*), intent(out) :: errmsg

        type(error_type), allocatable :: error
        type(convolver_box), pointer :: box

        box => null()
        call need_count('gcmsmp', 'NC', nc, 1, 'point', error)
        if (.not. allocated(error)) then
            call samples_multi_box('gcmsmp', g(:, :, 1:nc), run_request(method, dt, tol, nstep), box, error)
        end if
        call new_handle(box, handle, error, ierr, errmsg)
    end subroutine gcmsmp

    !> Multi-point convolver on a universal file of a Green's matrix: its receptances identified
    !> with shared poles (or its impulse responses, 'direct' and 'fft' only), at its nodes.
    subroutine gcmfil(path, method, dt, nstep, tol, maxord, handle, ierr, errmsg)
        !> Path of the universal file (trailing blanks ignored).
        character(len=*), intent(in) :: path
        !> Method: 'modal' (= 'recursive'), 'exact', 'direct' or 'fft' (any case).
        character(len=*), intent(in) :: method
        !> Time step dt [s], > 0.
        real(dp), intent(in) :: dt
        !> Number of steps N_t of the run, >= 1.
        integer, intent(in) :: nstep
        !> Truncation fraction of max |g_ij| for 'direct' and 'fft', in [0, 1) (0.01: the paper's).
        real(dp), intent(in) :: tol
        !> Largest order of the pole fit's stabilisation diagram, or 0 for the library's default (30).
        integer, intent(in) :: maxord
        !> Handle of the new convolver on the file's Green's matrix; 0 on failure.
        integer(int64), intent(out) :: handle
        !> Status: 0 success, 2 bad input or file, 3 a failed identification.
        integer, intent(out) :: ierr
        !> Message on failure, blank on success.
        character(len=*), intent(out) :: errmsg

        type(error_type), allocatable :: error
        type(convolver_box), pointer :: box

        call file_multi_box('gcmfil', trim(path), run_request(trim(method), dt, tol, nstep), maxord, box, error)
        call new_handle(box, handle, error, ierr, errmsg)
    end subroutine gcmfil

    !> Multi-point convolver on a universal file of normal modes (nodes in dataset 15 or 2411,
    !> one dataset 55 per mode): every node a point (GCMPTS gives them), the modes up to FBAND
    !> stepped and those above kept as their static compliance in W0 (not in the explicit
    !> 'modal'), the same convolver as a scene's `&structure model = 'modes_file'`.
    subroutine gcmmfl(path, idir, xi, fband, method, dt, nstep, tol, handle, ierr, errmsg)
        !> Path of the universal file (trailing blanks ignored).
        character(len=*), intent(in) :: path
        !> Direction of the shapes at the contact: 1, 2, 3 for X, Y, Z, negative for the opposite sense.
        integer, intent(in) :: idir
        !> Viscous damping ratio of the modes the file gives none, in [0, 1).
        real(dp), intent(in) :: xi
        !> Highest natural frequency stepped [Hz], or 0 for the Nyquist frequency 1/(2*DT).
        real(dp), intent(in) :: fband
        !> Method: 'modal' (= 'recursive'), 'exact', 'direct' or 'fft' (any case).
        character(len=*), intent(in) :: method
        !> Time step dt [s], > 0.
        real(dp), intent(in) :: dt
        !> Number of steps N_t of the run, >= 1.
        integer, intent(in) :: nstep
        !> Truncation fraction of max |g_ij| for 'direct' and 'fft', in [0, 1) (0.01: the paper's).
        real(dp), intent(in) :: tol
        !> Handle of the new convolver on the file's modes; 0 on failure.
        integer(int64), intent(out) :: handle
        !> Status: 0 success, 2 bad input or file (the reader's message).
        integer, intent(out) :: ierr
        !> Message on failure, blank on success.
        character(len=*), intent(out) :: errmsg

        type(error_type), allocatable :: error
        type(convolver_box), pointer :: box

        call modes_file_box('gcmmfl', trim(path), idir, xi, fband, run_request(trim(method), dt, tol, nstep), box, &
                            error)
        call new_handle(box, handle, error, ierr, errmsg)
    end subroutine gcmmfl

    !> The method's own estimate of the relative error of its contact forces: the model's terms
    !> (0 for modes given exactly, E of eq. (7) of an identified model, what a sampled kernel
    !> leaves out), plus the time-step and band terms of the contact run going on (GCMBEG,
    !> GCMSTP) or last run (GCMRUN): its companions at 2*dt and 4*dt, and with a modes file's
    !> modes up to twice the band.
    subroutine gcmest(handle, est, ierr, errmsg)
        !> The handle.
        integer(int64), intent(in) :: handle
        !> The estimate [-] (0 on failure).
        real(dp), intent(out) :: est
        !> Status: 0, or 2 for a 0 handle.
        integer, intent(out) :: ierr
        !> Message on failure, blank on success.
        character(len=*), intent(out) :: errmsg

        call estimate_of('gcmest', null_handle, handle, est, ierr, errmsg)
    end subroutine gcmest

    !> GCMEST's single-point twin, for a handle of GCSDOF, GCMODE, GCSAMP or GCFRF (after GCCONT).
    subroutine gcest(handle, est, ierr, errmsg)
        !> The handle.
        integer(int64), intent(in) :: handle
        !> The estimate [-] (0 on failure).
        real(dp), intent(out) :: est
        !> Status: 0, or 2 for a 0 handle.
        integer, intent(out) :: ierr
        !> Message on failure, blank on success.
        character(len=*), intent(out) :: errmsg

        call estimate_of('gcest', point_null_handle, handle, est, ierr, errmsg)
    end subroutine gcest

    !> The relative accuracy the host asks (0: none): IERR = 4 at once when the method's own
    !> estimate exceeds it, and from GCMBEG and GCMRUN afterwards (their results whole).
    subroutine gcmacc(handle, acc, ierr, errmsg)
        !> The handle.
        integer(int64), intent(in) :: handle
        !> Relative accuracy asked (the largest error estimate accepted), > 0, or 0 for none.
        real(dp), intent(in) :: acc
        !> Status: 0, 2 for a 0 handle or a bad ACC, 4 when the method is outside ACC.
        integer, intent(out) :: ierr
        !> Message on failure, blank on success.
        character(len=*), intent(out) :: errmsg

        call accuracy_of('gcmacc', null_handle, handle, acc, ierr, errmsg)
    end subroutine gcmacc

    !> GCMACC's single-point twin: IERR = 4 from GCCONT when outside ACC (its results whole).
    subroutine gcacc(handle, acc, ierr, errmsg)
        !> The handle.
        integer(int64), intent(in) :: handle
        !> Relative accuracy asked (the largest error estimate accepted), > 0, or 0 for none.
        real(dp), intent(in) :: acc
        !> Status: 0, 2 for a 0 handle or a bad ACC, 4 when the method is outside ACC.
        integer, intent(out) :: ierr
        !> Message on failure, blank on success.
        character(len=*), intent(out) :: errmsg

        call accuracy_of('gcacc', point_null_handle, handle, acc, ierr, errmsg)
    end subroutine gcacc

    !> The estimate of a handle's box (GCMEST, GCEST).
    subroutine estimate_of(caller, missing, handle, est, ierr, errmsg)
        character(len=*), intent(in) :: caller, missing
        integer(int64), intent(in) :: handle
        real(dp), intent(out) :: est
        integer, intent(out) :: ierr
        character(len=*), intent(out) :: errmsg

        type(error_type), allocatable :: error
        type(convolver_box), pointer :: box

        est = 0.0_dp
        box => box_at(handle_address(handle))
        call check_box(caller, missing, box, error=error)
        if (.not. allocated(error)) est = box%estimate + box%run_terms
        call report(error, ierr, errmsg)
    end subroutine estimate_of

    !> The accuracy asked of a handle's box (GCMACC, GCACC).
    subroutine accuracy_of(caller, missing, handle, acc, ierr, errmsg)
        character(len=*), intent(in) :: caller, missing
        integer(int64), intent(in) :: handle
        real(dp), intent(in) :: acc
        integer, intent(out) :: ierr
        character(len=*), intent(out) :: errmsg

        type(error_type), allocatable :: error
        type(convolver_box), pointer :: box

        box => box_at(handle_address(handle))
        call check_box(caller, missing, box, error=error)
        if (.not. allocated(error)) call set_box_accuracy(caller, box, acc, error)
        call report(error, ierr, errmsg)
    end subroutine accuracy_of

    !> Another method (or time step) on the file GCMFIL read into HFROM, without a second identification.
    subroutine gcmmth(hfrom, method, dt, nstep, tol, handle, ierr, errmsg)
        !> A handle made by GCMFIL (or GCMMTH).
        integer(int64), intent(in) :: hfrom
        !> Method: 'modal' (= 'recursive'), 'exact', 'direct' or 'fft' (any case).
        character(len=*), intent(in) :: method
        !> Time step dt [s], > 0.
        real(dp), intent(in) :: dt
        !> Number of steps N_t of the run, >= 1.
        integer, intent(in) :: nstep
        !> Truncation fraction of max |g_ij| for 'direct' and 'fft', in [0, 1).
        real(dp), intent(in) :: tol
        !> Handle of the new convolver on HFROM's file; 0 on failure.
        integer(int64), intent(out) :: handle
        !> Status: 0 success, 2 bad input or a source not made by GCMFIL.
        integer, intent(out) :: ierr
        !> Message on failure, blank on success.
        character(len=*), intent(out) :: errmsg

        type(error_type), allocatable :: error
        type(convolver_box), pointer :: box, from

        box => null()
        from => checked('gcmmth', hfrom, error=error)
        if (.not. allocated(error)) call method_multi_box('gcmmth', from, run_request(trim(method), dt, tol, nstep), &
                                                          box, error)
        call new_handle(box, handle, error, ierr, errmsg)
    end subroutine gcmmth

    !> Node labels and positions of the NC points of a convolver made by GCMFIL or GCMMTH.
    subroutine gcmpts(handle, nc, node, x, y, ierr, errmsg)
        !> The handle.
        integer(int64), intent(in) :: handle
        !> Number of points (the convolver's).
        integer, intent(in) :: nc
        !> Node labels of the points (NC).
        integer, intent(out) :: node(*)
        !> x_i [m], along the travel (NC).
        real(dp), intent(out) :: x(*)
        !> y_i [m], across (NC).
        real(dp), intent(out) :: y(*)
        !> Status: 0, or 2 for a 0 handle, a wrong NC or a convolver not made from a file.
        integer, intent(out) :: ierr
        !> Message on failure, blank on success.
        character(len=*), intent(out) :: errmsg

        type(error_type), allocatable :: error
        type(convolver_box), pointer :: box
        integer, allocatable :: nodes(:)
        real(dp), allocatable :: x_points(:), y_points(:)

        box => checked('gcmpts', handle, nc, error)
        if (.not. allocated(error)) call box_points('gcmpts', box, nodes, x_points, y_points, error)
        if (.not. allocated(error)) then
            node(1:nc) = nodes
            x(1:nc) = x_points
            y(1:nc) = y_points
        end if
        call report(error, ierr, errmsg)
    end subroutine gcmpts

    !> What GCMFIL found in its file: E of eq. (7) of the identified modes alone, worst and mean
    !> over the receptances, the number of shared poles (0 for impulse responses), and the
    !> summary in "# " lines separated by line ends (the file, points, identification, modes).
    subroutine gcmsum(handle, eworst, emean, npole, text, ierr)
        !> The handle.
        integer(int64), intent(in) :: handle
        !> Worst E (0 on failure).
        real(dp), intent(out) :: eworst
        !> Mean E (0 on failure).
        real(dp), intent(out) :: emean
        !> Number of shared poles (0 on failure).
        integer, intent(out) :: npole
        !> The summary; the message on failure.
        character(len=*), intent(out) :: text
        !> Status: 0, or 2 for a 0 handle or a convolver not made from a file.
        integer, intent(out) :: ierr

        type(error_type), allocatable :: error
        type(convolver_box), pointer :: box
        character(len=:), allocatable :: summary

        eworst = 0.0_dp
        emean = 0.0_dp
        npole = 0
        box => checked('gcmsum', handle, error=error)
        if (.not. allocated(error)) call check_file_box('gcmsum', box, error)
        call report(error, ierr, text)
        if (allocated(error)) return
        call file_e_modes(box%green, eworst, emean, npole)
        call file_summary(box, summary)
        text = summary
    end subroutine gcmsum

    !> Modes of the library's tyre belt (a pre-tensioned orthotropic plate on an elastic
    !> foundation, greenconv_model_plate) up to FMAX at an NX by NY patch of XLEN by YLEN
    !> centred on the belt: points I = (IY-1)*NX + IX at (X(I), Y(I)).
    subroutine gcmplt(nx, ny, xlen, ylen, fmax, ncap, nmode, polre, polim, resre, resim, shape, x, y, ierr, errmsg)
        !> Points along x (the direction of travel), >= 1.
        integer, intent(in) :: nx
        !> Points across, >= 1.
        integer, intent(in) :: ny
        !> Length of the patch along x [m].
        real(dp), intent(in) :: xlen
        !> Width of the patch across [m].
        real(dp), intent(in) :: ylen
        !> Highest natural frequency kept [Hz].
        real(dp), intent(in) :: fmax
        !> Room for modes in the arrays.
        integer, intent(in) :: ncap
        !> Number of modes N_m (also set when it exceeds NCAP).
        integer, intent(out) :: nmode
        !> Real parts of the poles [rad/s] (NCAP).
        real(dp), intent(out) :: polre(*)
        !> Imaginary parts of the poles [rad/s] (NCAP).
        real(dp), intent(out) :: polim(*)
        !> Real parts of the modal residues (NCAP).
        real(dp), intent(out) :: resre(*)
        !> Imaginary parts of the modal residues (NCAP).
        real(dp), intent(out) :: resim(*)
        !> Mode shapes at the points [1/sqrt(kg)] (NX*NY x NCAP).
        real(dp), intent(out) :: shape(max(nx*ny, 0), *)
        !> x_i [m] (NX*NY).
        real(dp), intent(out) :: x(*)
        !> y_i [m] (NX*NY).
        real(dp), intent(out) :: y(*)
        !> Status: 0 success, 2 bad input or too small arrays.
        integer, intent(out) :: ierr
        !> Message on failure, blank on success.
        character(len=*), intent(out) :: errmsg

        type(error_type), allocatable :: error
        type(point_modes) :: modes
        real(dp), allocatable :: x_points(:), y_points(:)
        integer :: n_c

        nmode = 0
        call patch_modes('gcmplt', 'FMAX', nx, ny, [xlen, ylen], fmax, modes, x_points, y_points, error)
        if (.not. allocated(error)) then
            nmode = modes%modes%n_modes()
            n_c = modes%n_points()
            if (nmode > ncap) then
                call fatal_error(error, 'gcmplt: NCAP = '//int_text(ncap)//': the plate has '//int_text(nmode) &
                                 //' modes below FMAX: give arrays of that many modes')
            else
                polre(1:nmode) = modes%modes%pole%re
                polim(1:nmode) = modes%modes%pole%im
                resre(1:nmode) = modes%modes%residue%re
                resim(1:nmode) = modes%modes%residue%im
                shape(:, 1:nmode) = modes%shape
                x(1:n_c) = x_points
                y(1:n_c) = y_points
            end if
        end if
        call report(error, ierr, errmsg)
    end subroutine gcmplt

    !> Free a convolver (its FFTW plans too), multi- or single-point (the one box behind every
    !> handle; greenconv_legacy's `GCFREE` is this door); the handle is 0 on return.
    subroutine gcmfre(handle)
        !> The handle (0: nothing).
        integer(int64), intent(inout) :: handle

        type(convolver_box), pointer :: box

        box => box_at(handle_address(handle))
        call free_box(box)
        handle = 0_int64
    end subroutine gcmfre

    !> Number of points N_c of a multi-point convolver.
    subroutine gcmnpt(handle, nc, ierr, errmsg)
        !> The handle.
        integer(int64), intent(in) :: handle
        !> Number of points (0 on failure).
        integer, intent(out) :: nc
        !> Status: 0, or 2 for a 0 handle.
        integer, intent(out) :: ierr
        !> Message on failure, blank on success.
        character(len=*), intent(out) :: errmsg

        type(error_type), allocatable :: error
        type(convolver_box), pointer :: box

        nc = 0
        box => checked('gcmnpt', handle, error=error)
        if (.not. allocated(error)) nc = box%conv%n_points()
        call report(error, ierr, errmsg)
    end subroutine gcmnpt

    !> History displacements u_h,i(n) [m] at the NC points.
    subroutine gcmhis(handle, nc, uh, ierr, errmsg)
        !> The handle.
        integer(int64), intent(in) :: handle
        !> Number of points (the convolver's).
        integer, intent(in) :: nc
        !> History displacements [m] (NC).
        real(dp), intent(out) :: uh(*)
        !> Status: 0, or 2 for a 0 handle or a wrong NC.
        integer, intent(out) :: ierr
        !> Message on failure, blank on success.
        character(len=*), intent(out) :: errmsg

        type(error_type), allocatable :: error
        type(convolver_box), pointer :: box

        box => checked('gcmhis', handle, nc, error)
        if (.not. allocated(error)) call check_steps(box, 'gcmhis', 1_int64, error)
        if (.not. allocated(error)) call box%conv%history(uh(1:nc))
        call report(error, ierr, errmsg)
    end subroutine gcmhis

    !> Push this step's forces q_i(t_n) [N] and advance to the next step.
    subroutine gcmpsh(handle, nc, q, ierr, errmsg)
        !> The handle.
        integer(int64), intent(in) :: handle
        !> Number of points (the convolver's).
        integer, intent(in) :: nc
        !> Forces [N] (NC).
        real(dp), intent(in) :: q(*)
        !> Status: 0, or 2 for a 0 handle or a wrong NC.
        integer, intent(out) :: ierr
        !> Message on failure, blank on success.
        character(len=*), intent(out) :: errmsg

        type(error_type), allocatable :: error
        type(convolver_box), pointer :: box

        box => checked('gcmpsh', handle, nc, error)
        if (.not. allocated(error)) call check_steps(box, 'gcmpsh', 1_int64, error)
        if (.not. allocated(error)) call box%conv%push(q(1:nc))
        call report(error, ierr, errmsg)
    end subroutine gcmpsh

    !> The instant compliance matrix W0 [m/N] (NC x NC; zero for an explicit method).
    subroutine gcmw0(handle, nc, w0, ierr, errmsg)
        !> The handle.
        integer(int64), intent(in) :: handle
        !> Number of points (the convolver's).
        integer, intent(in) :: nc
        !> W0 [m/N] (NC x NC).
        real(dp), intent(out) :: w0(max(nc, 0), *)
        !> Status: 0, or 2 for a 0 handle or a wrong NC.
        integer, intent(out) :: ierr
        !> Message on failure, blank on success.
        character(len=*), intent(out) :: errmsg

        type(error_type), allocatable :: error
        type(convolver_box), pointer :: box

        box => checked('gcmw0', handle, nc, error)
        if (.not. allocated(error)) w0(:, 1:nc) = box%conv%weight0
        call report(error, ierr, errmsg)
    end subroutine gcmw0

    !> Back to step 0 with no force history (ends a stepped contact run).
    subroutine gcmrst(handle, ierr, errmsg)
        !> The handle.
        integer(int64), intent(in) :: handle
        !> Status: 0, or 2 for a 0 handle.
        integer, intent(out) :: ierr
        !> Message on failure, blank on success.
        character(len=*), intent(out) :: errmsg

        type(error_type), allocatable :: error
        type(convolver_box), pointer :: box

        box => checked('gcmrst', handle, error=error)
        if (.not. allocated(error)) then
            call reset_box(box)
        end if
        call report(error, ierr, errmsg)
    end subroutine gcmrst

    !> Model size (N_g samples or N_m modes) and "method: what the model neglects".
    subroutine gcmdsc(handle, nsize, text, ierr)
        !> The handle.
        integer(int64), intent(in) :: handle
        !> Model size (0 on failure).
        integer, intent(out) :: nsize
        !> Description; the message on failure.
        character(len=*), intent(out) :: text
        !> Status: 0, or 2 for a 0 handle.
        integer, intent(out) :: ierr

        type(error_type), allocatable :: error
        type(convolver_box), pointer :: box
        character(len=:), allocatable :: description

        nsize = 0
        box => checked('gcmdsc', handle, error=error)
        call report(error, ierr, text)
        if (allocated(error)) return
        call describe_box(box, description, nsize)
        text = description
    end subroutine gcmdsc

    !> Newton and divergence settings of the next contact runs (defaults 1D-12, 50, 1 m).
    subroutine gcmopt(handle, tol, maxit, bound, ierr, errmsg)
        !> The handle.
        integer(int64), intent(in) :: handle
        !> Relative tolerance of a step's residual, > 0.
        real(dp), intent(in) :: tol
        !> Most Newton iterations per step, >= 1.
        integer, intent(in) :: maxit
        !> Largest |u_i| [m] accepted, > 0.
        real(dp), intent(in) :: bound
        !> Status: 0, or 2 for a 0 handle or a value out of range.
        integer, intent(out) :: ierr
        !> Message on failure, blank on success.
        character(len=*), intent(out) :: errmsg

        type(error_type), allocatable :: error
        type(convolver_box), pointer :: box

        box => checked('gcmopt', handle, error=error)
        if (.not. allocated(error)) call set_multi_options('gcmopt', box, tol, maxit, bound, error)
        call report(error, ierr, errmsg)
    end subroutine gcmopt

    !> Start a contact run stepped by GCMSTP (the convolver reset): a power law and a preload per
    !> point; GCMLBG with the law 'power' of (KC(I), P(I)) at point I.
    subroutine gcmbeg(handle, nc, kc, p, f0, ierr, errmsg)
        !> The handle.
        integer(int64), intent(in) :: handle
        !> Number of points (the convolver's).
        integer, intent(in) :: nc
        !> Contact stiffness k_c,i [N/m^p] (NC), > 0.
        real(dp), intent(in) :: kc(*)
        !> Contact exponent p_i (NC), > 0.
        real(dp), intent(in) :: p(*)
        !> Static preload F0_i [N] (NC), >= 0.
        real(dp), intent(in) :: f0(*)
        !> Status: 0, or 2 for bad input.
        integer, intent(out) :: ierr
        !> Message on failure, blank on success.
        character(len=*), intent(out) :: errmsg

        call start_points('gcmbeg', handle, nc, f0, ierr, errmsg, kc=kc, p=p)
    end subroutine gcmbeg

    !> Start a contact run stepped by GCMSTP (the convolver reset) on the contact law NAME of the
    !> registry ('power': k_c [N/m^p], p; 'exponential': F_s [N], delta_s [m]; any case), one
    !> law for every point, its parameters PAR(1:NPAR, 1) at every point (NLAW = 1) or
    !> PAR(1:NPAR, I) at point I (NLAW = NC), and a preload per point.
    subroutine gcmlbg(handle, nc, name, npar, nlaw, par, f0, ierr, errmsg)
        !> The handle.
        integer(int64), intent(in) :: handle
        !> Number of points (the convolver's).
        integer, intent(in) :: nc
        !> The law's name, e.g. 'power' or 'exponential' (any case, trailing blanks ignored).
        character(len=*), intent(in) :: name
        !> Number of parameters of each law (the law's: 2 for both laws).
        integer, intent(in) :: npar
        !> Number of parameter sets: 1 (every point the same) or NC (one a point).
        integer, intent(in) :: nlaw
        !> Parameter values in the registry's order and SI units (NPAR x NLAW).
        real(dp), intent(in) :: par(*)
        !> Static preload F0_i [N] (NC), >= 0.
        real(dp), intent(in) :: f0(*)
        !> Status: 0, or 2 for bad input (a law's name, count or parameter: the message names the
        !> door, the law, the parameter with its unit, its range and the value found).
        integer, intent(out) :: ierr
        !> Message on failure, blank on success.
        character(len=*), intent(out) :: errmsg

        call start_points('gcmlbg', handle, nc, f0, ierr, errmsg, name=name, npar=npar, nlaw=nlaw, par=par)
    end subroutine gcmlbg

    !> What GCMBEG and GCMLBG do: the handle and NC checked, the laws made (`door_laws`), the run
    !> started; a start refused ends the run going on.
    subroutine start_points(caller, handle, nc, f0, ierr, errmsg, kc, p, name, npar, nlaw, par)
        character(len=*), intent(in) :: caller
        integer(int64), intent(in) :: handle
        integer, intent(in) :: nc
        real(dp), intent(in) :: f0(*)
        integer, intent(out) :: ierr
        character(len=*), intent(out) :: errmsg
        real(dp), intent(in), optional :: kc(*), p(*), par(*)
        character(len=*), intent(in), optional :: name
        integer, intent(in), optional :: npar, nlaw

        type(error_type), allocatable :: error
        type(convolver_box), pointer :: box
        class(contact_law), allocatable :: laws(:)

        box => checked(caller, handle, nc, error)
        call door_laws(caller, nc, laws, error, kc, p, name, npar, nlaw, par)
        if (.not. allocated(error)) then
            call start_multi_box(caller, box, laws, f0(1:nc), error)
        else if (associated(box)) then
            box%stepping = .false.
        end if
        call report(error, ierr, errmsg)
    end subroutine start_points

    !> The next step of the run GCMBEG or GCMLBG began: all forces of the step solved together.
    subroutine gcmstp(handle, nc, road, u, f, delta, ierr, errmsg)
        !> The handle.
        integer(int64), intent(in) :: handle
        !> Number of points (the convolver's).
        integer, intent(in) :: nc
        !> Road heights u_r,i(t_n) [m] (NC).
        real(dp), intent(in) :: road(*)
        !> Displacements u_i(t_n) [m] (NC); 0 on a fault.
        real(dp), intent(out) :: u(*)
        !> Forces F_i(t_n) [N] (NC); 0 on a fault.
        real(dp), intent(out) :: f(*)
        !> Compressions delta_i(t_n) [m] (NC); 0 on a fault.
        real(dp), intent(out) :: delta(*)
        !> Status: 0, 2 bad input or no run going on, 3 a step that diverged or did not converge.
        integer, intent(out) :: ierr
        !> Message on failure (naming step and point), blank on success.
        character(len=*), intent(out) :: errmsg

        type(error_type), allocatable :: error
        type(convolver_box), pointer :: box

        box => checked('gcmstp', handle, nc, error)
        if (.not. allocated(error)) call advance_multi_box('gcmstp', box, road(1:nc), u(1:nc), f(1:nc), &
                                                          delta(1:nc), error)
        call report(error, ierr, errmsg)
    end subroutine gcmstp

    !> A whole contact run (the convolver reset first): ROAD(N, I) = u_r,i(t_(N-1)); GCMLRN with
    !> the law 'power' of (KC(I), P(I)) at point I.
    subroutine gcmrun(handle, nc, nstep, kc, p, f0, road, u, f, delta, ierr, errmsg)
        !> The handle.
        integer(int64), intent(in) :: handle
        !> Number of points (the convolver's).
        integer, intent(in) :: nc
        !> Number of steps N_t, >= 1.
        integer, intent(in) :: nstep
        !> Contact stiffness k_c,i [N/m^p] (NC), > 0.
        real(dp), intent(in) :: kc(*)
        !> Contact exponent p_i (NC), > 0.
        real(dp), intent(in) :: p(*)
        !> Static preload F0_i [N] (NC), >= 0.
        real(dp), intent(in) :: f0(*)
        !> Road heights [m] (NSTEP x NC).
        real(dp), intent(in) :: road(max(nstep, 0), *)
        !> Displacements [m] (NSTEP x NC); 0 from a fault on.
        real(dp), intent(out) :: u(max(nstep, 0), *)
        !> Forces [N] (NSTEP x NC); 0 from a fault on.
        real(dp), intent(out) :: f(max(nstep, 0), *)
        !> Compressions [m] (NSTEP x NC); 0 from a fault on.
        real(dp), intent(out) :: delta(max(nstep, 0), *)
        !> Status: 0, 2 bad input, 3 a step that diverged or did not converge.
        integer, intent(out) :: ierr
        !> Message on failure (naming step and point), blank on success.
        character(len=*), intent(out) :: errmsg

        call run_points('gcmrun', handle, nc, nstep, f0, road, u, f, delta, ierr, errmsg, kc=kc, p=p)
    end subroutine gcmrun

    !> A whole contact run (the convolver reset first) on the contact law NAME of the registry,
    !> its parameters PAR(1:NPAR, 1) at every point (NLAW = 1) or PAR(1:NPAR, I) at point I
    !> (NLAW = NC), as GCMLBG takes them: ROAD(N, I) = u_r,i(t_(N-1)).
    subroutine gcmlrn(handle, nc, nstep, name, npar, nlaw, par, f0, road, u, f, delta, ierr, errmsg)
        !> The handle.
        integer(int64), intent(in) :: handle
        !> Number of points (the convolver's).
        integer, intent(in) :: nc
        !> Number of steps N_t, >= 1.
        integer, intent(in) :: nstep
        !> The law's name, e.g. 'power' or 'exponential' (any case, trailing blanks ignored).
        character(len=*), intent(in) :: name
        !> Number of parameters of each law (the law's: 2 for both laws).
        integer, intent(in) :: npar
        !> Number of parameter sets: 1 (every point the same) or NC (one a point).
        integer, intent(in) :: nlaw
        !> Parameter values in the registry's order and SI units (NPAR x NLAW).
        real(dp), intent(in) :: par(*)
        !> Static preload F0_i [N] (NC), >= 0.
        real(dp), intent(in) :: f0(*)
        !> Road heights [m] (NSTEP x NC).
        real(dp), intent(in) :: road(max(nstep, 0), *)
        !> Displacements [m] (NSTEP x NC); 0 from a fault on.
        real(dp), intent(out) :: u(max(nstep, 0), *)
        !> Forces [N] (NSTEP x NC); 0 from a fault on.
        real(dp), intent(out) :: f(max(nstep, 0), *)
        !> Compressions [m] (NSTEP x NC); 0 from a fault on.
        real(dp), intent(out) :: delta(max(nstep, 0), *)
        !> Status: 0, 2 bad input (a law's name, count or parameter: the message names the door,
        !> the law, the parameter with its unit, its range and the value found), 3 a step that
        !> diverged or did not converge.
        integer, intent(out) :: ierr
        !> Message on failure (naming step and point), blank on success.
        character(len=*), intent(out) :: errmsg

        call run_points('gcmlrn', handle, nc, nstep, f0, road, u, f, delta, ierr, errmsg, name=name, npar=npar, &
                        nlaw=nlaw, par=par)
    end subroutine gcmlrn

    !> What GCMRUN and GCMLRN do: the handle, NC and NSTEP checked, the laws made (`door_laws`),
    !> the run.
    subroutine run_points(caller, handle, nc, nstep, f0, road, u, f, delta, ierr, errmsg, kc, p, name, npar, nlaw, par)
        character(len=*), intent(in) :: caller
        integer(int64), intent(in) :: handle
        integer, intent(in) :: nc, nstep
        real(dp), intent(in) :: f0(*)
        real(dp), intent(in) :: road(max(nstep, 0), *)
        real(dp), intent(out) :: u(max(nstep, 0), *), f(max(nstep, 0), *), delta(max(nstep, 0), *)
        integer, intent(out) :: ierr
        character(len=*), intent(out) :: errmsg
        real(dp), intent(in), optional :: kc(*), p(*), par(*)
        character(len=*), intent(in), optional :: name
        integer, intent(in), optional :: npar, nlaw

        type(error_type), allocatable :: error
        type(convolver_box), pointer :: box
        class(contact_law), allocatable :: laws(:)

        box => checked(caller, handle, nc, error)
        call need_count(caller, 'NSTEP', nstep, 1, 'step', error)
        call door_laws(caller, nc, laws, error, kc, p, name, npar, nlaw, par)
        if (.not. allocated(error)) call run_multi_box(caller, box, laws, f0(1:nc), road(:, 1:nc), u(:, 1:nc), &
                                                       f(:, 1:nc), delta(:, 1:nc), error)
        call report(error, ierr, errmsg)
    end subroutine run_points

    !> The contact laws of NC points for a contact door, unless `error` is already set: the
    !> power laws (KC(I), P(I)), unchecked (the contact run checks them and speaks as the
    !> (k_c, p) doors always have), or the law NAME of the registry (any case) with the
    !> parameters PAR(1:NPAR, 1) at every point (NLAW = 1) or PAR(1:NPAR, I) at point I
    !> (NLAW = NC), checked by the registry: status 2, the message naming the door, the law,
    !> the parameter with its unit, its range and the value found (and the point, for NLAW > 1).
    subroutine door_laws(caller, nc, laws, error, kc, p, name, npar, nlaw, par)
        !> Name of the door, first word of a message.
        character(len=*), intent(in) :: caller
        !> Number of points N_c, >= 1 (checked by the caller).
        integer, intent(in) :: nc
        !> The laws, one a point, of one dynamic type; unallocated on error.
        class(contact_law), allocatable, intent(out) :: laws(:)
        !> Set for a law refused; nothing is done when already set.
        type(error_type), allocatable, intent(inout) :: error
        !> Contact stiffness k_c,i [N/m^p] of the power law (NC), with `p`.
        real(dp), intent(in), optional :: kc(*)
        !> Contact exponent p_i of the power law (NC), with `kc`.
        real(dp), intent(in), optional :: p(*)
        !> The registry's name of the law, with `npar`, `nlaw` and `par` instead of `kc` and `p`.
        character(len=*), intent(in), optional :: name
        !> Number of parameters of each law.
        integer, intent(in), optional :: npar
        !> Number of parameter sets: 1 or NC.
        integer, intent(in), optional :: nlaw
        !> Parameter values (NPAR x NLAW), in the registry's order and SI units.
        real(dp), intent(in), optional :: par(*)

        class(contact_law), allocatable :: law

        if (allocated(error)) return
        if (present(kc) .and. present(p)) then
            allocate (laws, source=contact_law(kc(1:nc), p(1:nc)))
            return
        end if
        if (.not. (present(name) .and. present(npar) .and. present(nlaw) .and. present(par))) then
            call fatal_error(error, caller//': no contact law given')
            return
        end if
        if (npar < 0 .or. npar > max_law_parameters) then
            call fatal_error(error, caller//': NPAR = '//int_text(npar)//': give 0 to ' &
                             //int_text(max_law_parameters)//' parameter values')
        else if (nlaw /= 1 .and. nlaw /= nc) then
            call fatal_error(error, caller//': NLAW = '//int_text(nlaw)//': give 1 (the same parameters at every ' &
                             //'point) or NC = '//int_text(nc)//' (one set a point)')
        end if
        if (allocated(error)) return
        if (nlaw == 1) then
            call new_law(lower_text(name), par(1:npar), law, error)
            if (.not. allocated(error)) call replicate_law(law, nc, laws)
        else
            call new_laws(lower_text(name), reshape(par(1:npar*nc), [npar, nc]), laws, error)
        end if
        if (allocated(error)) error%message = caller//': '//error%message
    end subroutine door_laws

    ! ---- conversions -------------------------------------------------------------------------

    !> The handle of a new box (0 when it was not made), with status and message.
    subroutine new_handle(box, handle, error, ierr, errmsg)
        type(convolver_box), pointer, intent(in) :: box
        integer(int64), intent(out) :: handle
        type(error_type), allocatable, intent(in) :: error
        integer, intent(out) :: ierr
        character(len=*), intent(out) :: errmsg

        handle = 0_int64
        call report(error, ierr, errmsg)
        if (allocated(error) .or. .not. associated(box)) return
        handle = address_handle(c_loc(box))
    end subroutine new_handle


    !> The box of a handle, checked (with NC when present; a negative NC is refused).
    function checked(caller, handle, nc, error) result(box)
        character(len=*), intent(in) :: caller
        integer(int64), intent(in) :: handle
        integer, intent(in), optional :: nc
        type(error_type), allocatable, intent(out) :: error
        type(convolver_box), pointer :: box

        box => box_at(handle_address(handle))
        call check_box(caller, null_handle, box, nc, error)
    end function checked

end module greenconv_legacy_multi
