!> greenconv for Fortran 77 style programs: plain subroutines whose arguments are scalars,
!> explicit-shape arrays and character strings only, so that fixed-form code calls them
!> after a single `use greenconv_legacy`. Names are six letters, `GC` first.
!>
!> Types: `DOUBLE PRECISION` reals (SI units), default `INTEGER` counts and status codes,
!> and an `INTEGER*8` handle for a convolver (as FFTW's legacy Fortran interface does for
!> its plans): the address of an object made by a `GC...` constructor, 0 when there is none.
!> Free it with `GCFREE`. There is no module state: handles are independent of each other.
!>
!> Status `IERR`: 0 success, 2 bad input (`stat_input`: a value, a file, a null handle),
!> 3 numerical failure (`stat_numerical`: a failed fit, a contact run that diverged); the C
!> API (`greenconv_capi`, include/greenconv.h) uses the same codes. Routines that can fail
!> also return a message in `ERRMSG` (any length; truncated to fit, blank on success).
!>
!> Methods (the `METHOD` string, any case): 'direct', 'fft', 'modal' (= 'recursive'),
!> 'paper', 'exact', 'backward' and 'auto'; see `new_convolver` (greenconv_api_library).
!> Each routine is a thin conversion onto the Fortran API (greenconv_api_handle). A single-point
!> convolver is the multi-point one of one point: `GCFREE`, `GCHIST`, `GCPUSH`, `GCW0` and
!> `GCRSET` are greenconv_legacy_multi's `GCMFRE`, `GCMHIS`, `GCMPSH`, `GCMW0` and `GCMRST` with
!> NC = 1 (the same box behind every handle), without their message.
!>
!> Units: masses [kg], stiffnesses [N/m], contact stiffness k_c [N/m^p], time step [s],
!> forces [N], displacements and heights [m], poles [rad/s], residues [m/(N*s)],
!> impulse-response samples g [m/(N*s)], frequencies [Hz].
module greenconv_legacy
    use, intrinsic :: iso_c_binding, only: c_loc
    use, intrinsic :: iso_fortran_env, only: int64, output_unit
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type, fatal_error, stat_input
    use greenconv_core_text, only: int_text
    use greenconv_model_modal_set, only: modal_set
    use greenconv_ident_mlfit, only: ml_result
    use greenconv_ident_structure, only: structure_model
    use greenconv_contact_single, only: contact_law, contact_options
    use greenconv_conv_point_matrix, only: point_matrix
    use greenconv_api_library, only: run_scene_file, check_contact_law
    use greenconv_api_handle, only: convolver_box, new_box, box_at, sdof_structure, modes_structure, &
                                    samples_structure, frf_file_structure, identify_file, identify_file_ml, step_box, &
                                    describe_box, check_steps
    use greenconv_legacy_multi, only: gcmfre, gcmhis, gcmpsh, gcmw0, gcmrst, door_laws
    use greenconv_api_budget, only: run_point_budget, start_point_budget
    use greenconv_api_multi_handle, only: advance_multi_box
    use greenconv_api_doors, only: report, handle_address, address_handle
    use greenconv_api_version, only: gcvers
    implicit none
    private

    public :: gcsdof, gcmode, gcsamp, gcfrf, gcfrfi, gcfree
    public :: gchist, gcpush, gcw0, gcrset, gcsize, gcdesc, gcwarn
    public :: gcstep, gccont, gcid, gcidml, gcscen
    public :: gclstp, gclcon, gclbeg, gcladv
    public :: gcvers

    !> Status of a call that succeeded.
    integer, parameter :: stat_ok = 0

contains

    !> Convolver of a damped mass-spring system (section 3.1): mass M, stiffness K, damping
    !> ratio xi; one exact mode.
    subroutine gcsdof(mass, stiff, xi, dt, nstep, method, handle, ierr, errmsg)
        !> Mass M [kg], > 0.
        real(dp), intent(in) :: mass
        !> Stiffness K [N/m], > 0.
        real(dp), intent(in) :: stiff
        !> Damping ratio xi, 0 <= xi < 1.
        real(dp), intent(in) :: xi
        !> Time step dt [s], > 0.
        real(dp), intent(in) :: dt
        !> Number of steps N_t of the run, >= 1.
        integer, intent(in) :: nstep
        !> Method: 'direct', 'fft', 'modal', 'recursive', 'paper', 'exact', 'backward' or 'auto'
        !> (any case).
        character(len=*), intent(in) :: method
        !> Handle of the new mass-spring convolver; 0 on failure.
        integer(int64), intent(out) :: handle
        !> Status: 0 success, 2 for a mass, stiffness, damping ratio, dt, nstep or method out of
        !> range.
        integer, intent(out) :: ierr
        !> Message on failure, blank on success.
        character(len=*), intent(out) :: errmsg

        type(error_type), allocatable :: error
        type(structure_model) :: structure

        call sdof_structure('gcsdof', mass, stiff, xi, structure, error)
        call new_handle(method, structure, dt, nstep, handle, ierr, errmsg, error)
    end subroutine gcsdof

    !> Convolver of a structure given by its modes in pole-residue form (greenconv_model_modal_set):
    !> g(t) = sum_k 2*Re(r_k*exp(lambda_k*t)).
    subroutine gcmode(nmode, polre, polim, resre, resim, dt, nstep, method, handle, ierr, errmsg)
        !> Number of modes (conjugate pairs), >= 1.
        integer, intent(in) :: nmode
        !> Real parts of the poles lambda_k [rad/s], < 0.
        real(dp), intent(in) :: polre(nmode)
        !> Imaginary parts of the poles [rad/s], > 0.
        real(dp), intent(in) :: polim(nmode)
        !> Real parts of the residues r_k [m/(N*s)].
        real(dp), intent(in) :: resre(nmode)
        !> Imaginary parts of the residues [m/(N*s)].
        real(dp), intent(in) :: resim(nmode)
        !> Time step dt [s], > 0.
        real(dp), intent(in) :: dt
        !> Number of steps N_t of the run, >= 1.
        integer, intent(in) :: nstep
        !> Method name (see `gcsdof`).
        character(len=*), intent(in) :: method
        !> Handle of the new modal convolver; 0 on failure.
        integer(int64), intent(out) :: handle
        !> Status: 0 success, 2 for a pole, residue, dt, nstep or method out of range.
        integer, intent(out) :: ierr
        !> Message on failure, blank on success.
        character(len=*), intent(out) :: errmsg

        type(error_type), allocatable :: error
        type(structure_model) :: structure
        integer :: n

        n = max(nmode, 0)
        call modes_structure('gcmode', polre(1:n), polim(1:n), resre(1:n), resim(1:n), structure, error)
        call new_handle(method, structure, dt, nstep, handle, ierr, errmsg, error)
    end subroutine gcmode

    !> Convolver of a structure known by its impulse response sampled at the time step:
    !> methods 'direct' and 'fft' only.
    subroutine gcsamp(nsamp, g, dt, nstep, method, handle, ierr, errmsg)
        !> Number of samples, >= 2.
        integer, intent(in) :: nsamp
        !> Samples g(n*dt), n = 0..nsamp-1 [m/(N*s)].
        real(dp), intent(in) :: g(nsamp)
        !> Time step dt [s] of the samples and of the run, > 0.
        real(dp), intent(in) :: dt
        !> Number of steps N_t of the run, >= 1.
        integer, intent(in) :: nstep
        !> Method: 'direct' or 'fft'.
        character(len=*), intent(in) :: method
        !> Handle of the new convolver on the samples; 0 on failure.
        integer(int64), intent(out) :: handle
        !> Status: 0 success, 2 for too few samples, or a dt, nstep or method out of range.
        integer, intent(out) :: ierr
        !> Message on failure, blank on success.
        character(len=*), intent(out) :: errmsg

        type(error_type), allocatable :: error
        type(structure_model) :: structure

        call samples_structure('gcsamp', g(1:max(nsamp, 0)), structure, error)
        call new_handle(method, structure, dt, nstep, handle, ierr, errmsg, error)
    end subroutine gcsamp

    !> Convolver of a structure known by a receptance file (`#` comments, then columns
    !> f [Hz], Re G, Im G [m/N] on a uniform grid from 0 Hz): modes identified for the modal
    !> methods as a scene's `frf_file` model identifies them (maximum likelihood, the order by
    !> MDL up to maxmod modes; `GCFRFI` selects LSCE), g by inverse FFT for 'direct' and 'fft'
    !> (dt a whole multiple of 1/(2*f_max) then). `GCFRFI` with a blank IDENT.
    subroutine gcfrf(path, dt, nstep, method, tole, maxmod, handle, ierr, errmsg)
        !> Path of the receptance file.
        character(len=*), intent(in) :: path
        !> Time step dt [s], > 0; for 'direct' and 'fft' a whole multiple of 1/(2*f_max).
        real(dp), intent(in) :: dt
        !> Number of steps N_t of the run, >= 1.
        integer, intent(in) :: nstep
        !> Method name (see `gcsdof`).
        character(len=*), intent(in) :: method
        !> Target of the identification error E of eq. (7), > 0 (1e-6 is usual; LSCE's).
        real(dp), intent(in) :: tole
        !> Largest number of modes the order search tries, >= 1 (30 is usual).
        integer, intent(in) :: maxmod
        !> Handle of the new convolver on the identified structure; 0 on failure.
        integer(int64), intent(out) :: handle
        !> Status: 0 success, 2 bad input, 3 failed identification.
        integer, intent(out) :: ierr
        !> Message on failure, blank on success.
        character(len=*), intent(out) :: errmsg

        call gcfrfi(path, dt, nstep, method, ' ', tole, maxmod, handle, ierr, errmsg)
    end subroutine gcfrf

    !> `gcfrf` with the identification method IDENT: 'ml' (maximum likelihood, the default, as a
    !> scene's), 'lsce' (the smallest model with E <= tole up to maxmod modes), blank for the default.
    subroutine gcfrfi(path, dt, nstep, method, ident, tole, maxmod, handle, ierr, errmsg)
        !> Path of the receptance file.
        character(len=*), intent(in) :: path
        !> Time step dt [s], > 0; for 'direct' and 'fft' a whole multiple of 1/(2*f_max).
        real(dp), intent(in) :: dt
        !> Number of steps N_t of the run, >= 1.
        integer, intent(in) :: nstep
        !> Method name (see `gcsdof`).
        character(len=*), intent(in) :: method
        !> Identification method, 'ml' or 'lsce'; blank: 'ml'.
        character(len=*), intent(in) :: ident
        !> Target of the identification error E of eq. (7), > 0 (LSCE's).
        real(dp), intent(in) :: tole
        !> Largest number of modes the order search tries, >= 1 (30 is usual).
        integer, intent(in) :: maxmod
        !> Handle of the new convolver on the identified structure; 0 on failure.
        integer(int64), intent(out) :: handle
        !> Status: 0 success, 2 bad input, 3 failed identification.
        integer, intent(out) :: ierr
        !> Message on failure, blank on success.
        character(len=*), intent(out) :: errmsg

        type(error_type), allocatable :: error
        type(structure_model) :: structure

        call frf_file_structure(trim(path), method, dt, tole, maxmod, structure, error, ident)
        call new_handle(method, structure, dt, nstep, handle, ierr, errmsg, error)
    end subroutine gcfrfi

    !> Build a convolver for a structure and return its handle, unless `error` already says
    !> the structure could not be made.
    subroutine new_handle(method, structure, dt, nstep, handle, ierr, errmsg, error)
        character(len=*), intent(in) :: method
        type(structure_model), intent(in) :: structure
        real(dp), intent(in) :: dt
        integer, intent(in) :: nstep
        integer(int64), intent(out) :: handle
        integer, intent(out) :: ierr
        character(len=*), intent(out) :: errmsg
        type(error_type), allocatable, intent(inout) :: error

        type(convolver_box), pointer :: box

        handle = 0_int64
        if (.not. allocated(error)) call new_box(method, structure, dt, nstep, box, error)
        call report(error, ierr, errmsg)
        if (allocated(error)) return
        handle = address_handle(c_loc(box))
    end subroutine new_handle

    !> Free a convolver (its FFTW plans too) and set its handle to 0; nothing for handle 0.
    subroutine gcfree(handle)
        !> The handle; 0 on return.
        integer(int64), intent(inout) :: handle

        call gcmfre(handle)
    end subroutine gcfree

    !> History displacement u_h(n) [m]: the displacement at t_n from the forces pushed so far.
    subroutine gchist(handle, uh, ierr)
        !> The convolver's handle.
        integer(int64), intent(in) :: handle
        !> u_h(n) [m]; 0 on failure.
        real(dp), intent(out) :: uh
        !> Status: 0 success, 2 null handle, a multi-point handle or a step past a cut kernel's validity.
        integer, intent(out) :: ierr

        real(dp) :: values(1)
        character(len=1) :: message

        values(1) = 0.0_dp
        call gcmhis(handle, 1, values, ierr, message)
        uh = values(1)
    end subroutine gchist

    !> Push the force q(t_n) [N] of the current step and advance to step n + 1.
    subroutine gcpush(handle, q, ierr)
        !> The convolver's handle.
        integer(int64), intent(in) :: handle
        !> Force q(t_n) [N] on the structure at this step.
        real(dp), intent(in) :: q
        !> Status: 0 success, 2 null handle, a multi-point handle or a step past a cut kernel's validity.
        integer, intent(out) :: ierr

        character(len=1) :: message

        call gcmpsh(handle, 1, [q], ierr, message)
    end subroutine gcpush

    !> Instantaneous weight w0 [m/N]: displacement per newton of the current step's own
    !> force, u(t_n) = u_h(n) + w0*q(t_n) (0 for a mass-spring with the paper's scheme).
    subroutine gcw0(handle, w0, ierr)
        !> The convolver's handle.
        integer(int64), intent(in) :: handle
        !> w0 [m/N]; 0 on failure.
        real(dp), intent(out) :: w0
        !> Status: 0 success, 2 null handle or a multi-point handle.
        integer, intent(out) :: ierr

        real(dp) :: matrix(1, 1)
        character(len=1) :: message

        matrix(1, 1) = 0.0_dp
        call gcmw0(handle, 1, matrix, ierr, message)
        w0 = matrix(1, 1)
    end subroutine gcw0

    !> Forget every force pushed: back to step 0 (the structure at rest).
    subroutine gcrset(handle, ierr)
        !> The convolver's handle.
        integer(int64), intent(in) :: handle
        !> Status: 0 success, 2 null handle.
        integer, intent(out) :: ierr

        character(len=1) :: message

        call gcmrst(handle, ierr, message)
    end subroutine gcrset

    !> Size of the convolver's model: N_g kernel samples ('direct', 'fft') or N_m modes.
    subroutine gcsize(handle, nsize, ierr)
        !> The convolver's handle.
        integer(int64), intent(in) :: handle
        !> N_g or N_m; 0 on failure.
        integer, intent(out) :: nsize
        !> Status: 0 success, 2 null handle.
        integer, intent(out) :: ierr

        type(convolver_box), pointer :: box
        character(len=:), allocatable :: label

        nsize = 0
        box => checked_box(handle, ierr)
        if (associated(box)) call box%conv%model_size(nsize, label)
    end subroutine gcsize

    !> The warnings of the identification the convolver's structure came from (wrap-around, a
    !> fit that missed its target, dropped poles), "; " between them; blank when none.
    subroutine gcwarn(handle, text, ierr)
        !> The convolver's handle.
        integer(int64), intent(in) :: handle
        !> The warnings, truncated to fit; blank when none or on failure.
        character(len=*), intent(out) :: text
        !> Status: 0 success, 2 null handle.
        integer, intent(out) :: ierr

        type(convolver_box), pointer :: box

        text = ' '
        box => checked_box(handle, ierr)
        if (.not. associated(box)) return
        if (allocated(box%warning)) text = box%warning
    end subroutine gcwarn

    !> The method's name, a colon and what its model neglects (for `auto`, what it chose).
    subroutine gcdesc(handle, text, ierr)
        !> The convolver's handle.
        integer(int64), intent(in) :: handle
        !> The description, truncated to fit; blank on failure.
        character(len=*), intent(out) :: text
        !> Status: 0 success, 2 null handle.
        integer, intent(out) :: ierr

        type(convolver_box), pointer :: box
        character(len=:), allocatable :: description

        box => checked_box(handle, ierr)
        text = ' '
        if (.not. associated(box)) return
        call describe_box(box, description)
        text = description
    end subroutine gcdesc

    !> One explicit step of the contact loop (eqs. 20-24), as the driver takes it: from the
    !> road height, the contact force and the body displacement of this step, the convolver
    !> advanced. Start from a new or reset convolver (the body at rest under the preload).
    !> GCLSTP with the law 'power' of (KC, P), without its message.
    subroutine gcstep(handle, kc, p, f0, road, u, f, delta, ierr)
        !> The convolver's handle.
        integer(int64), intent(in) :: handle
        !> Contact stiffness k_c [N/m^p], > 0.
        real(dp), intent(in) :: kc
        !> Contact exponent p (1.5: Hertz, 1: linear), > 0.
        real(dp), intent(in) :: p
        !> Static preload F0 [N], >= 0.
        real(dp), intent(in) :: f0
        !> Road height u_r(t_n) [m].
        real(dp), intent(in) :: road
        !> The body's displacement u(t_n) [m] from static equilibrium; 0 on failure.
        real(dp), intent(out) :: u
        !> The contact force F(t_n) [N], >= 0; 0 on failure.
        real(dp), intent(out) :: f
        !> The spring's compression delta(t_n) [m] (<= 0: no contact); 0 on failure.
        real(dp), intent(out) :: delta
        !> Status: 0 success, 2 null handle, bad contact law or a multi-point handle, 3 a step not finite.
        integer, intent(out) :: ierr

        character(len=1) :: message

        call step_point('gcstep', handle, f0, road, u, f, delta, ierr, message, kc=[kc], p=[p])
    end subroutine gcstep

    !> One explicit step of the contact loop as GCSTEP takes it, on the contact law NAME of the
    !> registry ('power': k_c [N/m^p], p; 'exponential': F_s [N], delta_s [m]; any case) of
    !> the NPAR parameter values PAR.
    subroutine gclstp(handle, name, npar, par, f0, road, u, f, delta, ierr, errmsg)
        !> The convolver's handle.
        integer(int64), intent(in) :: handle
        !> The law's name, e.g. 'power' or 'exponential' (any case, trailing blanks ignored).
        character(len=*), intent(in) :: name
        !> Number of parameter values (the law's: 2 for both laws).
        integer, intent(in) :: npar
        !> Parameter values in the registry's order and SI units (NPAR).
        real(dp), intent(in) :: par(*)
        !> Static preload F0 [N], >= 0.
        real(dp), intent(in) :: f0
        !> Road height u_r(t_n) [m].
        real(dp), intent(in) :: road
        !> The body's displacement u(t_n) [m] from static equilibrium; 0 on failure.
        real(dp), intent(out) :: u
        !> The contact force F(t_n) [N], >= 0; 0 on failure.
        real(dp), intent(out) :: f
        !> The spring's compression delta(t_n) [m] (<= 0: no contact); 0 on failure.
        real(dp), intent(out) :: delta
        !> Status: 0 success, 2 null handle, bad preload or a law's name, count or parameter
        !> refused (the message names the door, the law, the parameter with its unit, its range
        !> and the value found).
        integer, intent(out) :: ierr
        !> Message on failure, blank on success.
        character(len=*), intent(out) :: errmsg

        call step_point('gclstp', handle, f0, road, u, f, delta, ierr, errmsg, name=name, npar=npar, par=par)
    end subroutine gclstp

    !> What GCSTEP and GCLSTP do: the handle checked, the law made (`door_laws`), the step.
    subroutine step_point(caller, handle, f0, road, u, f, delta, ierr, errmsg, kc, p, name, npar, par)
        character(len=*), intent(in) :: caller
        integer(int64), intent(in) :: handle
        real(dp), intent(in) :: f0, road
        real(dp), intent(out) :: u, f, delta
        integer, intent(out) :: ierr
        character(len=*), intent(out) :: errmsg
        real(dp), intent(in), optional :: kc(*), p(*), par(*)
        character(len=*), intent(in), optional :: name
        integer, intent(in), optional :: npar

        type(convolver_box), pointer :: box
        type(error_type), allocatable :: error
        class(contact_law), allocatable :: laws(:)

        u = 0.0_dp
        f = 0.0_dp
        delta = 0.0_dp
        box => point_box(caller, handle, error)
        call door_laws(caller, 1, laws, error, kc, p, name, npar, 1, par)
        if (.not. allocated(error)) then
            call step_box(caller, box, laws(1), f0, road, u, f, delta, error)
        end if
        call named(caller, error)
        call report(error, ierr, errmsg)
    end subroutine step_point

    !> Start a contact run stepped by GCLADV (the convolver reset; the driver's explicit scheme,
    !> as GCCONT runs it) on the contact law NAME of the registry of the NPAR parameter values
    !> PAR, as GCLSTP takes it; a start refused ends the run going on.
    subroutine gclbeg(handle, name, npar, par, f0, ierr, errmsg)
        !> The convolver's handle (a single-point convolver).
        integer(int64), intent(in) :: handle
        !> The law's name, e.g. 'power' or 'exponential' (any case, trailing blanks ignored).
        character(len=*), intent(in) :: name
        !> Number of parameter values (the law's: 2 for both laws).
        integer, intent(in) :: npar
        !> Parameter values in the registry's order and SI units (NPAR).
        real(dp), intent(in) :: par(*)
        !> Static preload F0 [N], >= 0.
        real(dp), intent(in) :: f0
        !> Status: 0 success, 2 null or multi-point handle, bad preload or a law's name, count or
        !> parameter refused (the message names the door, the law, the parameter with its unit,
        !> its range and the value found), 4 outside the accuracy asked with GCACC (the run started).
        integer, intent(out) :: ierr
        !> Message on failure, blank on success.
        character(len=*), intent(out) :: errmsg

        character(len=*), parameter :: caller = 'gclbeg'
        type(convolver_box), pointer :: box
        type(error_type), allocatable :: error
        class(contact_law), allocatable :: laws(:)

        box => stepped_box(caller, handle, error)
        if (associated(box)) box%stepping = .false.
        call door_laws(caller, 1, laws, error, name=name, npar=npar, nlaw=1, par=par)
        if (.not. allocated(error)) call check_contact_law(laws(1), f0, error)
        if (.not. allocated(error)) call start_point_budget(caller, box, laws(1), f0, contact_options(), error)
        call named(caller, error)
        call report(error, ierr, errmsg)
    end subroutine gclbeg

    !> The next step of the run GCLBEG began: u, F and delta at this step's road height (a
    !> fault or GCRSET ends the run).
    subroutine gcladv(handle, road, u, f, delta, ierr, errmsg)
        !> The convolver's handle (a single-point convolver).
        integer(int64), intent(in) :: handle
        !> Road height u_r(t_n) [m].
        real(dp), intent(in) :: road
        !> The body's displacement u(t_n) [m] from static equilibrium; 0 on failure.
        real(dp), intent(out) :: u
        !> The contact force F(t_n) [N], >= 0; 0 on failure.
        real(dp), intent(out) :: f
        !> The spring's compression delta(t_n) [m] (<= 0: no contact); 0 on failure.
        real(dp), intent(out) :: delta
        !> Status: 0 success, 2 null or multi-point handle, no run going on or a step past a cut
        !> kernel's validity, 3 a step that diverged (the run ends).
        integer, intent(out) :: ierr
        !> Message on failure, blank on success.
        character(len=*), intent(out) :: errmsg

        character(len=*), parameter :: caller = 'gcladv'
        type(convolver_box), pointer :: box
        type(error_type), allocatable :: error
        real(dp) :: step_u(1), step_f(1), step_delta(1)

        u = 0.0_dp
        f = 0.0_dp
        delta = 0.0_dp
        box => stepped_box(caller, handle, error)
        if (.not. allocated(error)) then
            if (.not. box%stepping) call fatal_error(error, caller//': no contact run is going on with this ' &
                                                     //'convolver: call GCLBEG first (a fault or a reset ends a run)')
        end if
        if (.not. allocated(error)) call check_steps(box, caller, 1_int64, error)
        if (.not. allocated(error)) call advance_multi_box(caller, box, [road], step_u, step_f, step_delta, error)
        if (.not. allocated(error)) then
            u = step_u(1)
            f = step_f(1)
            delta = step_delta(1)
        else if (associated(box)) then
            box%stepping = .false.
        end if
        call named(caller, error)
        call report(error, ierr, errmsg)
    end subroutine gcladv

    !> A whole contact run of nstep steps on a road profile (the convolver is reset first),
    !> the same loop as the driver's: u, F and delta at t_n = n*dt, n = 0..nstep-1. GCLCON
    !> with the law 'power' of (KC, P).
    subroutine gccont(handle, kc, p, f0, nstep, road, u, f, delta, ierr, errmsg)
        !> The convolver's handle.
        integer(int64), intent(in) :: handle
        !> Contact stiffness k_c [N/m^p], > 0.
        real(dp), intent(in) :: kc
        !> Contact exponent p (1.5: Hertz, 1: linear), > 0.
        real(dp), intent(in) :: p
        !> Static preload F0 [N], >= 0.
        real(dp), intent(in) :: f0
        !> Number of steps N_t, >= 1.
        integer, intent(in) :: nstep
        !> Road heights u_r(t_n) [m].
        real(dp), intent(in) :: road(nstep)
        !> Body displacements u(t_n) [m] from static equilibrium.
        real(dp), intent(out) :: u(nstep)
        !> Contact forces F(t_n) [N], >= 0.
        real(dp), intent(out) :: f(nstep)
        !> Compressions delta(t_n) [m] of the contact spring (<= 0: no contact).
        real(dp), intent(out) :: delta(nstep)
        !> Status: 0 success, 2 bad input, 3 the run diverged (the message names the step and
        !> its time; u, F and delta are those of the steps before it, then 0).
        integer, intent(out) :: ierr
        !> Message on failure, blank on success.
        character(len=*), intent(out) :: errmsg

        call run_point('gccont', handle, f0, nstep, road, u, f, delta, ierr, errmsg, kc=[kc], p=[p])
    end subroutine gccont

    !> A whole contact run as GCCONT makes it, on the contact law NAME of the registry
    !> ('power': k_c [N/m^p], p; 'exponential': F_s [N], delta_s [m]; any case) of the NPAR
    !> parameter values PAR.
    subroutine gclcon(handle, name, npar, par, f0, nstep, road, u, f, delta, ierr, errmsg)
        !> The convolver's handle.
        integer(int64), intent(in) :: handle
        !> The law's name, e.g. 'power' or 'exponential' (any case, trailing blanks ignored).
        character(len=*), intent(in) :: name
        !> Number of parameter values (the law's: 2 for both laws).
        integer, intent(in) :: npar
        !> Parameter values in the registry's order and SI units (NPAR).
        real(dp), intent(in) :: par(*)
        !> Static preload F0 [N], >= 0.
        real(dp), intent(in) :: f0
        !> Number of steps N_t, >= 1.
        integer, intent(in) :: nstep
        !> Road heights u_r(t_n) [m].
        real(dp), intent(in) :: road(nstep)
        !> Body displacements u(t_n) [m] from static equilibrium.
        real(dp), intent(out) :: u(nstep)
        !> Contact forces F(t_n) [N], >= 0.
        real(dp), intent(out) :: f(nstep)
        !> Compressions delta(t_n) [m] of the contact spring (<= 0: no contact).
        real(dp), intent(out) :: delta(nstep)
        !> Status: 0 success, 2 bad input (a law's name, count or parameter: the message names the
        !> door, the law, the parameter with its unit, its range and the value found), 3 the run
        !> diverged (the message names the step and its time; u, F and delta are those of the
        !> steps before it, then 0).
        integer, intent(out) :: ierr
        !> Message on failure, blank on success.
        character(len=*), intent(out) :: errmsg

        call run_point('gclcon', handle, f0, nstep, road, u, f, delta, ierr, errmsg, name=name, npar=npar, par=par)
    end subroutine gclcon

    !> What GCCONT and GCLCON do: the handle and NSTEP checked, the law made (`door_laws`), the
    !> run with its error budget; u, F and delta 0 when the run did not start.
    subroutine run_point(caller, handle, f0, nstep, road, u, f, delta, ierr, errmsg, kc, p, name, npar, par)
        character(len=*), intent(in) :: caller
        integer(int64), intent(in) :: handle
        real(dp), intent(in) :: f0
        integer, intent(in) :: nstep
        real(dp), intent(in) :: road(*)
        real(dp), intent(out) :: u(*), f(*), delta(*)
        integer, intent(out) :: ierr
        character(len=*), intent(out) :: errmsg
        real(dp), intent(in), optional :: kc(*), p(*), par(*)
        character(len=*), intent(in), optional :: name
        integer, intent(in), optional :: npar

        type(convolver_box), pointer :: box
        type(error_type), allocatable :: error
        class(contact_law), allocatable :: laws(:)
        integer :: n

        n = max(nstep, 0)
        box => point_box(caller, handle, error)
        if (.not. allocated(error) .and. nstep < 1) then
            call fatal_error(error, caller//': the number of steps must be >= 1')
        end if
        call door_laws(caller, 1, laws, error, kc, p, name, npar, 1, par)
        if (allocated(error)) then
            u(1:n) = 0.0_dp
            f(1:n) = 0.0_dp
            delta(1:n) = 0.0_dp
        else
            call run_point_budget(caller, box, laws(1), f0, road(1:n), contact_options(), u(1:n), f(1:n), &
                                  delta(1:n), error)
        end if
        call report(error, ierr, errmsg)
    end subroutine run_point

    !> Identify modes from a receptance file by LSCE: poles and residues of the smallest model
    !> whose E (eq. 7) meets tole, or the best up to maxmod modes, lowest frequency first.
    subroutine gcid(path, tole, maxmod, ncap, nmode, polre, polim, resre, resim, e, ierr, errmsg)
        !> Path of the receptance file (`#` comments, then f [Hz], Re G, Im G [m/N]).
        character(len=*), intent(in) :: path
        !> Target of the identification error E of eq. (7), > 0.
        real(dp), intent(in) :: tole
        !> Largest number of modes the order scan tries, >= 1.
        integer, intent(in) :: maxmod
        !> Capacity of the output arrays.
        integer, intent(in) :: ncap
        !> Number of modes found (also when it exceeds ncap, then with status 2).
        integer, intent(out) :: nmode
        !> Real parts of the poles [rad/s].
        real(dp), intent(out) :: polre(ncap)
        !> Imaginary parts of the poles [rad/s].
        real(dp), intent(out) :: polim(ncap)
        !> Real parts of the residues [m/(N*s)].
        real(dp), intent(out) :: resre(ncap)
        !> Imaginary parts of the residues [m/(N*s)].
        real(dp), intent(out) :: resim(ncap)
        !> Error E of eq. (7) of the model.
        real(dp), intent(out) :: e
        !> Status: 0 success, 2 bad input or too small ncap, 3 failed identification.
        integer, intent(out) :: ierr
        !> Message on failure, blank on success.
        character(len=*), intent(out) :: errmsg

        type(error_type), allocatable :: error
        type(modal_set) :: modes

        nmode = 0
        call identify_file(trim(path), tole, maxmod, modes, e, error)
        if (.not. allocated(error)) then
            nmode = modes%n_modes()
            if (nmode > ncap) call fatal_error(error, 'gcid: more modes found than the arrays hold (ncap): ' &
                                                  //'pass arrays of at least NMODE elements')
        end if
        call report(error, ierr, errmsg)
        if (allocated(error)) return
        polre(1:nmode) = real(modes%pole, dp)
        polim(1:nmode) = aimag(modes%pole)
        resre(1:nmode) = real(modes%residue, dp)
        resim(1:nmode) = aimag(modes%residue)
    end subroutine gcid

    !> Identify modes from a receptance file by maximum likelihood (order by MDL, noise model
    !> NOISE, 'auto' for the one of the highest likelihood), lowest frequency first, with their
    !> standard deviations and IDET(k) = 1 when the data determine mode k, 0 for a pole of the
    !> fitted receptance they do not (the column `determined` of a scene's modes file).
    subroutine gcidml(path, noise, maxord, ncap, nmode, ndet, polre, polim, resre, resim, sigf, sigxi, idet, ierr, &
                      errmsg)
        !> Path of the receptance file (columns f [Hz], Re G, Im G [m/N], or a universal file).
        character(len=*), intent(in) :: path
        !> Noise model: 'auto', 'relative', 'absolute', 'floor' or 'band'.
        character(len=*), intent(in) :: noise
        !> Highest order of the stabilisation diagram (modes), 1 to 200.
        integer, intent(in) :: maxord
        !> Capacity of the output arrays.
        integer, intent(in) :: ncap
        !> Number of modes found (also when it exceeds ncap, then with status 2).
        integer, intent(out) :: nmode
        !> Number of modes the data determine.
        integer, intent(out) :: ndet
        !> Real parts of the poles [rad/s].
        real(dp), intent(out) :: polre(ncap)
        !> Imaginary parts of the poles [rad/s].
        real(dp), intent(out) :: polim(ncap)
        !> Real parts of the residues [m/(N*s)].
        real(dp), intent(out) :: resre(ncap)
        !> Imaginary parts of the residues [m/(N*s)].
        real(dp), intent(out) :: resim(ncap)
        !> Standard deviations of the natural frequencies [Hz].
        real(dp), intent(out) :: sigf(ncap)
        !> Standard deviations of the damping ratios.
        real(dp), intent(out) :: sigxi(ncap)
        !> 1 when the data determine the mode, 0 when not.
        integer, intent(out) :: idet(ncap)
        !> Status: 0 success, 2 bad input or too small ncap, 3 failed identification.
        integer, intent(out) :: ierr
        !> Message on failure, blank on success.
        character(len=*), intent(out) :: errmsg

        type(error_type), allocatable :: error
        type(ml_result) :: result

        nmode = 0
        ndet = 0
        call identify_file_ml(trim(path), trim(noise), maxord, result, error)
        if (.not. allocated(error)) then
            nmode = result%modes%n_modes()
            ndet = count(result%determined_modes())
            if (nmode > ncap) call fatal_error(error, 'gcidml: more modes found than the arrays hold (ncap): ' &
                                                  //'pass arrays of at least NMODE elements')
        end if
        call report(error, ierr, errmsg)
        if (allocated(error)) return
        polre(1:nmode) = real(result%modes%pole, dp)
        polim(1:nmode) = aimag(result%modes%pole)
        resre(1:nmode) = real(result%modes%residue, dp)
        resim(1:nmode) = aimag(result%modes%residue)
        sigf(1:nmode) = result%sigma_frequency
        sigxi(1:nmode) = result%sigma_damping
        idet(1:nmode) = merge(1, 0, result%determined_modes())
    end subroutine gcidml

    !> Run a scene file as the driver does: column files in its output_dir, a summary line
    !> per method on standard output.
    subroutine gcscen(path, ierr, errmsg)
        !> Path of the namelist scene file.
        character(len=*), intent(in) :: path
        !> Status: 0 success, 2 bad scene or file, 3 numerical failure.
        integer, intent(out) :: ierr
        !> Message on failure, blank on success.
        character(len=*), intent(out) :: errmsg

        type(error_type), allocatable :: error

        call run_scene_file(trim(path), output_unit, error)
        flush (output_unit)
        call report(error, ierr, errmsg)
    end subroutine gcscen


    !> The object a handle points to, with status 0, or null with status `stat_input`.
    function checked_box(handle, ierr) result(box)
        integer(int64), intent(in) :: handle
        integer, intent(out) :: ierr
        type(convolver_box), pointer :: box

        box => box_at(handle_address(handle))
        ierr = stat_ok
        if (.not. associated(box)) ierr = stat_input
    end function checked_box

    !> The object a single-point contact door's handle points to, or null with `error` set.
    function point_box(caller, handle, error) result(box)
        character(len=*), intent(in) :: caller
        integer(int64), intent(in) :: handle
        type(error_type), allocatable, intent(out) :: error
        type(convolver_box), pointer :: box

        box => box_at(handle_address(handle))
        if (.not. associated(box)) then
            call fatal_error(error, caller//': null convolver handle: make one with GCSDOF, GCMODE, GCSAMP or GCFRF')
        end if
    end function point_box

    !> The single-point convolver a stepped contact run's handle points to (GCLBEG, GCLADV), or
    !> null with `error` set for handle 0 or a multi-point convolver.
    function stepped_box(caller, handle, error) result(box)
        character(len=*), intent(in) :: caller
        integer(int64), intent(in) :: handle
        type(error_type), allocatable, intent(out) :: error
        type(convolver_box), pointer :: box

        box => point_box(caller, handle, error)
        if (.not. associated(box)) return
        select type (matrix => box%conv)
        type is (point_matrix)
        class default
            call fatal_error(error, caller//': the handle is a convolver of '//int_text(box%conv%n_points()) &
                             //' points: step its contact run with GCMBEG or GCMLBG and GCMSTP')
            box => null()
        end select
    end function stepped_box

    !> The door's name first in a message that does not begin with it.
    subroutine named(caller, error)
        character(len=*), intent(in) :: caller
        type(error_type), allocatable, intent(inout) :: error

        if (.not. allocated(error)) return
        if (index(error%message, caller//': ') /= 1) error%message = caller//': '//error%message
    end subroutine named

end module greenconv_legacy
