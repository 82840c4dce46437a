!> The C interface of greenconv: `bind(c)` functions declared in include/greenconv.h, usable
!> from C and C++, written directly on the Fortran API (greenconv_api_library and
!> greenconv_api_handle), as minpack's C API and dftd4's api.f90 are.
!>
!> A `gc_convolver *` is an opaque handle: the C address of greenconv_api_handle's
!> `convolver_box`, the one object behind every handle, single- or multi-point; a single-point
!> structure's convolver sits in it as the 1 x 1 case of a Green's matrix, with what its model
!> neglects and the state of a contact run stepped one call at a time. The work is done by
!> greenconv_api_handle's procedures, shared with the Fortran 77 layer; these functions only
!> convert arguments and messages. No function keeps state outside the handles it is given.
!> The doors that are another door with a fixed argument (the constructors and the run without
!> options, the single-point history, push, weight and reset as the multi-point doors of one
!> point) are one-line C functions in capi_aliases.c.
!>
!> Conventions (see the header): functions return a status, 0 (`GC_OK`), 2 (`GC_ERROR_INPUT`)
!> or 3 (`GC_ERROR_NUMERICAL`), the codes of greenconv_core_error. A message buffer `errmsg`
!> of `errmsg_len` bytes (a `size_t`) receives the whole message when it fits, else its first
!> errmsg_len - 1 bytes; it is always NUL-terminated when errmsg_len >= 1, left untouched when
!> errmsg_len = 0 or errmsg is NULL, and holds "" on success. Pointers that must not be NULL
!> are checked: NULL gives status 2 (with a message where the function takes a buffer), never
!> a crash. SI units throughout.
module greenconv_capi
    use, intrinsic :: iso_c_binding, only: c_int, c_double, c_size_t, c_ptr, c_null_ptr, c_associated, c_f_pointer, &
                                           c_loc
    use, intrinsic :: iso_fortran_env, only: output_unit, int64
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type, fatal_error, stat_input
    use greenconv_core_text, only: int_text
    use greenconv_model_modal_set, only: modal_set
    use greenconv_ident_structure, only: structure_model
    use greenconv_contact_single, only: contact_options
    use greenconv_capi_law, only: law_box, law_at, door_name
    use greenconv_api_library, only: check_contact_law, run_scene_file, default_truncation_tol, default_accuracy
    use greenconv_ident_mlfit, only: ml_result
    use greenconv_api_handle, only: convolver_box, new_box, free_box, box_at, sdof_structure, modes_structure, &
                                    samples_structure, frf_file_structure, identify_file, identify_file_ml, check_steps, &
                                    step_box, describe_box, refuse_multi_point
    use greenconv_api_budget, only: run_point_budget, start_point_budget
    use greenconv_api_multi_handle, only: advance_multi_box
    use greenconv_api_doors, only: finish, from_c, to_c, put, put_if, need_pointer, need_pointers, need_count, &
                                   start_door, need_capacity, modes_to_c
    implicit none
    private

    public :: gc_contact_options, gc_build_options, gc_scheme_explicit, gc_scheme_implicit
    public :: gc_build_options_init, gc_convolver_new_sdof_opts, gc_convolver_new_modes_opts
    public :: gc_convolver_new_samples_opts, gc_convolver_new_frf_file_ident
    public :: gc_convolver_free, gc_convolver_delete, gc_convolver_model_size, gc_convolver_describe
    public :: gc_convolver_warnings
    public :: gc_contact_step_law, gc_contact_options_init, gc_run_contact_law
    public :: gc_contact_start_law, gc_contact_advance
    public :: gc_identify_frf_file, gc_identify_ml_file, gc_run_scene, point_null_handle
    !> The message and string conversions of greenconv_api_doors, named here too for the
    !> callers that took them from this module.
    public :: finish, from_c, to_c

    !> What the single-point doors say of a NULL handle.
    character(len=*), parameter :: point_null_handle = 'conv is NULL: make a convolver with gc_convolver_new_*'

    !> `GC_SCHEME_EXPLICIT`: the paper's explicit contact step (`contact_options%scheme = 'explicit'`).
    integer(c_int), parameter :: gc_scheme_explicit = 0
    !> `GC_SCHEME_IMPLICIT`: force, compression and displacement of a step solved together.
    integer(c_int), parameter :: gc_scheme_implicit = 1

    !> C `gc_contact_options`: how a contact run steps and when it gives up (`contact_options`).
    type, bind(c) :: gc_contact_options
        !> `GC_SCHEME_EXPLICIT` (0) or `GC_SCHEME_IMPLICIT` (1).
        integer(c_int) :: scheme
        !> Implicit step: most Newton or bisection iterations per step, >= 1.
        integer(c_int) :: max_iterations
        !> Largest |u| [m] accepted; a larger, infinite or NaN u stops the run as divergent.
        real(c_double) :: divergence_bound
        !> Implicit step: relative tolerance on the compression residual (dimensionless), > 0.
        real(c_double) :: tolerance
    end type gc_contact_options

    !> C `gc_build_options`: settings of a new convolver (`new_convolver`'s optional arguments).
    type, bind(c) :: gc_build_options
        !> Truncation fraction of max |g| for "direct" and "fft", in (0, 1).
        real(c_double) :: truncation_tol
        !> Relative accuracy "auto" must meet (the largest E of eq. 7 it accepts), > 0.
        real(c_double) :: accuracy
    end type gc_build_options


contains

    ! ---- creating and freeing convolvers -------------------------------------------------

    !> int gc_build_options_init(gc_build_options *options): the library's defaults.
    function gc_build_options_init(options) bind(c, name='gc_build_options_init') result(status)
        !> The options to fill (status 2 for NULL).
        type(c_ptr), value, intent(in) :: options
        integer(c_int) :: status

        type(gc_build_options), pointer :: settings

        status = stat_input
        if (.not. c_associated(options)) return
        call c_f_pointer(options, settings)
        settings = gc_build_options(default_truncation_tol, default_accuracy)
        status = 0
    end function gc_build_options_init

    !> int gc_convolver_new_sdof_opts(double mass, double stiffness, double damping_ratio,
    !> double dt, const char *method, int n_steps, const gc_build_options *options,
    !> gc_convolver **conv, char *errmsg, size_t errmsg_len)
    function gc_convolver_new_sdof_opts(mass, stiffness, damping_ratio, dt, method, n_steps, options, conv, errmsg, &
                                        errmsg_len) bind(c, name='gc_convolver_new_sdof_opts') result(status)
        !> Mass M [kg], > 0.
        real(c_double), value, intent(in) :: mass
        !> Stiffness K [N/m], > 0.
        real(c_double), value, intent(in) :: stiffness
        !> Damping ratio xi, 0 <= xi < 1.
        real(c_double), value, intent(in) :: damping_ratio
        !> Time step dt [s], > 0.
        real(c_double), value, intent(in) :: dt
        !> Method name, a NUL-terminated string.
        type(c_ptr), value, intent(in) :: method
        !> Number of steps N_t of the run, >= 1.
        integer(c_int), value, intent(in) :: n_steps
        !> Build options, or NULL for the defaults.
        type(c_ptr), value, intent(in) :: options
        !> Where the new convolver goes (NULL there on failure).
        type(c_ptr), value, intent(in) :: conv
        !> Message buffer, or NULL.
        type(c_ptr), value, intent(in) :: errmsg
        !> Size of the message buffer [bytes].
        integer(c_size_t), value, intent(in) :: errmsg_len
        integer(c_int) :: status

        type(structure_model) :: structure
        type(error_type), allocatable :: error

        call sdof_structure('gc_convolver_new_sdof', mass, stiffness, damping_ratio, structure, error)
        status = made('gc_convolver_new_sdof', method, structure, dt, n_steps, options, conv, error, errmsg, &
                      errmsg_len)
    end function gc_convolver_new_sdof_opts

    !> int gc_convolver_new_modes_opts(int n_modes, const double *pole_re, const double *pole_im,
    !> const double *residue_re, const double *residue_im, double dt, const char *method,
    !> int n_steps, const gc_build_options *options, gc_convolver **conv, char *errmsg,
    !> size_t errmsg_len)
    function gc_convolver_new_modes_opts(n_modes, pole_re, pole_im, residue_re, residue_im, dt, method, n_steps, &
                                         options, conv, errmsg, errmsg_len) &
        bind(c, name='gc_convolver_new_modes_opts') result(status)
        !> Number of modes (conjugate pairs), >= 1.
        integer(c_int), value, intent(in) :: n_modes
        !> Real parts of the poles lambda_k [rad/s], < 0.
        type(c_ptr), value, intent(in) :: pole_re
        !> Imaginary parts of the poles [rad/s], > 0.
        type(c_ptr), value, intent(in) :: pole_im
        !> Real parts of the residues r_k [m/(N*s)].
        type(c_ptr), value, intent(in) :: residue_re
        !> Imaginary parts of the residues [m/(N*s)].
        type(c_ptr), value, intent(in) :: residue_im
        !> Time step dt [s], > 0.
        real(c_double), value, intent(in) :: dt
        !> Method name, a NUL-terminated string.
        type(c_ptr), value, intent(in) :: method
        !> Number of steps N_t of the run, >= 1.
        integer(c_int), value, intent(in) :: n_steps
        !> Build options, or NULL for the defaults.
        type(c_ptr), value, intent(in) :: options
        !> Where the new convolver goes (NULL there on failure).
        type(c_ptr), value, intent(in) :: conv
        !> Message buffer, or NULL.
        type(c_ptr), value, intent(in) :: errmsg
        !> Size of the message buffer [bytes].
        integer(c_size_t), value, intent(in) :: errmsg_len
        integer(c_int) :: status

        type(structure_model) :: structure
        type(error_type), allocatable :: error
        real(c_double), pointer :: p_re(:), p_im(:), r_re(:), r_im(:)
        integer :: n

        n = max(int(n_modes), 0)
        call need_count('gc_convolver_new_modes', 'n_modes', int(n_modes), 1, 'mode', error)
        call need_pointers('gc_convolver_new_modes', [pole_re, pole_im, residue_re, residue_im], &
                           'pole_re, pole_im, residue_re and residue_im', 'pass arrays of n_modes values', error)
        if (.not. allocated(error)) then
            call c_f_pointer(pole_re, p_re, [n])
            call c_f_pointer(pole_im, p_im, [n])
            call c_f_pointer(residue_re, r_re, [n])
            call c_f_pointer(residue_im, r_im, [n])
            call modes_structure('gc_convolver_new_modes', p_re, p_im, r_re, r_im, structure, error)
        end if
        status = made('gc_convolver_new_modes', method, structure, dt, n_steps, options, conv, error, errmsg, &
                      errmsg_len)
    end function gc_convolver_new_modes_opts

    !> int gc_convolver_new_samples_opts(int n_samples, const double *g, double dt,
    !> const char *method, int n_steps, const gc_build_options *options, gc_convolver **conv,
    !> char *errmsg, size_t errmsg_len)
    function gc_convolver_new_samples_opts(n_samples, g, dt, method, n_steps, options, conv, errmsg, errmsg_len) &
        bind(c, name='gc_convolver_new_samples_opts') result(status)
        !> Number of samples, >= 2.
        integer(c_int), value, intent(in) :: n_samples
        !> Samples g(n*dt), n = 0..n_samples-1 [m/(N*s)].
        type(c_ptr), value, intent(in) :: g
        !> Time step dt [s] of the samples and of the run, > 0.
        real(c_double), value, intent(in) :: dt
        !> Method name, "direct" or "fft".
        type(c_ptr), value, intent(in) :: method
        !> Number of steps N_t of the run, >= 1.
        integer(c_int), value, intent(in) :: n_steps
        !> Build options, or NULL for the defaults.
        type(c_ptr), value, intent(in) :: options
        !> Where the new convolver goes (NULL there on failure).
        type(c_ptr), value, intent(in) :: conv
        !> Message buffer, or NULL.
        type(c_ptr), value, intent(in) :: errmsg
        !> Size of the message buffer [bytes].
        integer(c_size_t), value, intent(in) :: errmsg_len
        integer(c_int) :: status

        type(structure_model) :: structure
        type(error_type), allocatable :: error
        real(c_double), pointer :: samples(:)

        if (.not. c_associated(g) .and. n_samples > 0) then
            call fatal_error(error, 'gc_convolver_new_samples: g is NULL: pass an array of n_samples values')
        else
            call c_f_pointer(g, samples, [max(int(n_samples), 0)])
            call samples_structure('gc_convolver_new_samples', samples, structure, error)
        end if
        status = made('gc_convolver_new_samples', method, structure, dt, n_steps, options, conv, error, errmsg, &
                      errmsg_len)
    end function gc_convolver_new_samples_opts

    !> int gc_convolver_new_frf_file_ident(const char *path, double dt, const char *method,
    !> int n_steps, const char *identification, double tol_e, int max_modes,
    !> const gc_build_options *options, gc_convolver **conv, char *errmsg, size_t errmsg_len)
    function gc_convolver_new_frf_file_ident(path, dt, method, n_steps, identification, tol_e, max_modes, options, &
                                             conv, errmsg, errmsg_len) &
        bind(c, name='gc_convolver_new_frf_file_ident') result(status)
        !> Path of the receptance file (f [Hz], Re G, Im G [m/N]), NUL-terminated.
        type(c_ptr), value, intent(in) :: path
        !> Time step dt [s], > 0.
        real(c_double), value, intent(in) :: dt
        !> Method name, a NUL-terminated string.
        type(c_ptr), value, intent(in) :: method
        !> Number of steps N_t of the run, >= 1.
        integer(c_int), value, intent(in) :: n_steps
        !> Identification method, "ml" or "lsce" (NUL-terminated); NULL or "": "ml", as a scene's.
        type(c_ptr), value, intent(in) :: identification
        !> Target of the identification error E of eq. (7), > 0 (LSCE's).
        real(c_double), value, intent(in) :: tol_e
        !> Largest number of modes the order search tries, >= 1.
        integer(c_int), value, intent(in) :: max_modes
        !> Build options, or NULL for the defaults.
        type(c_ptr), value, intent(in) :: options
        !> Where the new convolver goes (NULL there on failure).
        type(c_ptr), value, intent(in) :: conv
        !> Message buffer, or NULL.
        type(c_ptr), value, intent(in) :: errmsg
        !> Size of the message buffer [bytes].
        integer(c_size_t), value, intent(in) :: errmsg_len
        integer(c_int) :: status

        type(structure_model) :: structure
        type(error_type), allocatable :: error

        call frf_file_structure(from_c(path), from_c(method), dt, tol_e, int(max_modes), structure, error, &
                                from_c(identification))
        status = made('gc_convolver_new_frf_file', method, structure, dt, n_steps, options, conv, error, errmsg, &
                      errmsg_len)
    end function gc_convolver_new_frf_file_ident

    !> void gc_convolver_free(gc_convolver *conv): free a convolver (NULL: nothing).
    subroutine gc_convolver_free(conv) bind(c, name='gc_convolver_free')
        !> The convolver.
        type(c_ptr), value, intent(in) :: conv

        type(convolver_box), pointer :: box

        box => box_at(conv)
        call free_box(box)
    end subroutine gc_convolver_free

    !> void gc_convolver_delete(gc_convolver **conv): free *conv and set it to NULL, so that a
    !> second call does nothing (conv NULL or *conv NULL: nothing).
    subroutine gc_convolver_delete(conv) bind(c, name='gc_convolver_delete')
        !> Address of the caller's handle.
        type(c_ptr), value, intent(in) :: conv

        type(c_ptr), pointer :: handle
        type(c_ptr) :: object

        if (.not. c_associated(conv)) return
        call c_f_pointer(conv, handle)
        ! A copy: gfortran's -fcheck=pointer takes a pointer to a C NULL for a disassociated one.
        object = handle
        call gc_convolver_free(object)
        handle = c_null_ptr
    end subroutine gc_convolver_delete

    ! ---- stepping a convolver ---------------------------------------------------------------

    !> int gc_convolver_model_size(const gc_convolver *conv, int *size)
    function gc_convolver_model_size(conv, size) bind(c, name='gc_convolver_model_size') result(status)
        !> The convolver.
        type(c_ptr), value, intent(in) :: conv
        !> Where N_g kernel samples ("direct", "fft") or N_m modes go.
        type(c_ptr), value, intent(in) :: size
        integer(c_int) :: status

        type(convolver_box), pointer :: box
        character(len=:), allocatable :: label
        integer :: n

        box => box_at(conv)
        status = stat_input
        if (.not. (associated(box) .and. c_associated(size))) return
        call box%conv%model_size(n, label)
        call put_if(size, n)
        status = 0
    end function gc_convolver_model_size

    !> int gc_convolver_describe(const gc_convolver *conv, char *text, size_t text_len)
    function gc_convolver_describe(conv, text, text_len) bind(c, name='gc_convolver_describe') result(status)
        !> The convolver.
        type(c_ptr), value, intent(in) :: conv
        !> Buffer for "method: what the model neglects", or NULL.
        type(c_ptr), value, intent(in) :: text
        !> Size of the buffer [bytes].
        integer(c_size_t), value, intent(in) :: text_len
        integer(c_int) :: status

        type(convolver_box), pointer :: box
        character(len=:), allocatable :: description

        box => box_at(conv)
        status = stat_input
        if (.not. associated(box)) then
            call to_c('', text, text_len)
            return
        end if
        call describe_box(box, description)
        call to_c(description, text, text_len)
        status = 0
    end function gc_convolver_describe

    !> int gc_convolver_warnings(const gc_convolver *conv, char *text, size_t text_len): the
    !> warnings of the identification the convolver's structure came from ("" when none).
    function gc_convolver_warnings(conv, text, text_len) bind(c, name='gc_convolver_warnings') result(status)
        !> The convolver.
        type(c_ptr), value, intent(in) :: conv
        !> Buffer for the warnings, "; " between them, or NULL.
        type(c_ptr), value, intent(in) :: text
        !> Size of the buffer [bytes].
        integer(c_size_t), value, intent(in) :: text_len
        integer(c_int) :: status

        type(convolver_box), pointer :: box

        box => box_at(conv)
        status = stat_input
        call to_c('', text, text_len)
        if (.not. associated(box)) return
        if (allocated(box%warning)) call to_c(box%warning, text, text_len)
        status = 0
    end function gc_convolver_warnings

    ! ---- dynamic contact --------------------------------------------------------------------

    !> int gc_contact_step_law(gc_convolver *conv, const gc_law *law, double preload, double road,
    !> double *displacement, double *force, double *compression): one explicit step; status 3,
    !> the outputs 0 and the convolver not advanced, when u, F or delta of the step is not finite
    !> (a road height that is NaN or infinite, a step that diverged), as gc_multi_contact_step.
    function gc_contact_step_law(conv, law, preload, road, displacement, force, compression) &
        bind(c, name='gc_contact_step_law') result(status)
        !> The convolver, advanced by one step (not on a fault).
        type(c_ptr), value, intent(in) :: conv
        !> The contact law (gc_law_new).
        type(c_ptr), value, intent(in) :: law
        !> Static preload F0 [N], >= 0.
        real(c_double), value, intent(in) :: preload
        !> Road height u_r(t_n) [m].
        real(c_double), value, intent(in) :: road
        !> Where the body displacement u(t_n) [m] goes (0 on a fault).
        type(c_ptr), value, intent(in) :: displacement
        !> Where the contact force F(t_n) [N] goes (0 on a fault).
        type(c_ptr), value, intent(in) :: force
        !> Where the compression delta(t_n) [m] goes (0 on a fault), or NULL.
        type(c_ptr), value, intent(in) :: compression
        integer(c_int) :: status

        type(convolver_box), pointer :: box
        type(law_box), pointer :: spring
        character(len=:), allocatable :: caller
        type(error_type), allocatable :: error
        real(dp) :: u, f, delta

        box => box_at(conv)
        spring => law_at(law)
        status = stat_input
        if (.not. (associated(box) .and. associated(spring) .and. c_associated(displacement) .and. &
                   c_associated(force))) return
        call door_name(spring, 'gc_contact_step_law', caller)
        call step_box(caller, box, spring%law, preload, road, u, f, delta, error)
        status = 0
        if (allocated(error)) status = int(error%stat, c_int)
        if (status == stat_input) return
        call put(displacement, u)
        call put(force, f)
        call put_if(compression, delta)
    end function gc_contact_step_law

    !> int gc_contact_options_init(gc_contact_options *options): the library's defaults (the
    !> paper's explicit step).
    function gc_contact_options_init(options) bind(c, name='gc_contact_options_init') result(status)
        !> The options to fill (status 2 for NULL).
        type(c_ptr), value, intent(in) :: options
        integer(c_int) :: status

        type(gc_contact_options), pointer :: settings
        type(contact_options) :: defaults

        status = stat_input
        if (.not. c_associated(options)) return
        call c_f_pointer(options, settings)
        settings%scheme = gc_scheme_explicit
        if (defaults%scheme == 'implicit') settings%scheme = gc_scheme_implicit
        settings%max_iterations = int(defaults%max_iterations, c_int)
        settings%divergence_bound = defaults%divergence_bound
        settings%tolerance = defaults%tolerance
        status = 0
    end function gc_contact_options_init

    !> int gc_run_contact_law(gc_convolver *conv, const gc_law *law, double preload, int n_steps,
    !> const double *road, const gc_contact_options *options, double *displacement, double *force,
    !> double *compression, char *errmsg, size_t errmsg_len): a whole run (the convolver reset first).
    function gc_run_contact_law(conv, law, preload, n_steps, road, options, displacement, force, compression, &
                                errmsg, errmsg_len) bind(c, name='gc_run_contact_law') result(status)
        !> The convolver (reset first).
        type(c_ptr), value, intent(in) :: conv
        !> The contact law (gc_law_new).
        type(c_ptr), value, intent(in) :: law
        !> Static preload F0 [N], >= 0.
        real(c_double), value, intent(in) :: preload
        !> Number of steps N_t, >= 1.
        integer(c_int), value, intent(in) :: n_steps
        !> Road heights u_r(t_n) [m], n_steps values.
        type(c_ptr), value, intent(in) :: road
        !> Contact options, or NULL for the defaults.
        type(c_ptr), value, intent(in) :: options
        !> Body displacements u(t_n) [m], n_steps values (0 after a fault).
        type(c_ptr), value, intent(in) :: displacement
        !> Contact forces F(t_n) [N], n_steps values (0 after a fault).
        type(c_ptr), value, intent(in) :: force
        !> Compressions delta(t_n) [m], n_steps values (0 after a fault), or NULL.
        type(c_ptr), value, intent(in) :: compression
        !> Message buffer, or NULL.
        type(c_ptr), value, intent(in) :: errmsg
        !> Size of the message buffer [bytes].
        integer(c_size_t), value, intent(in) :: errmsg_len
        integer(c_int) :: status

        type(convolver_box), pointer :: box
        type(law_box), pointer :: spring
        character(len=:), allocatable :: caller
        type(error_type), allocatable :: error
        type(contact_options) :: settings
        real(c_double), pointer :: heights(:), u(:), f(:)
        real(dp), allocatable :: delta(:)
        integer :: n

        call point_and_law(conv, law, 'gc_run_contact_law', box, spring, caller, error)
        n = max(int(n_steps), 0)
        allocate (delta(n))
        delta(:) = 0.0_dp
        if (allocated(error)) then
            continue
        else if (n_steps < 1) then
            call fatal_error(error, caller//': n_steps = '//int_text(int(n_steps))//': give at least 1 step')
        else if (.not. (c_associated(road) .and. c_associated(displacement) .and. c_associated(force))) then
            call fatal_error(error, caller//': road, displacement and force must not be NULL: pass arrays ' &
                             //'of n_steps values')
        else
            call options_from_c(options, settings, error)
            call c_f_pointer(displacement, u, [n])
            call c_f_pointer(force, f, [n])
            if (allocated(error)) then
                u(:) = 0.0_dp
                f(:) = 0.0_dp
            else
                call c_f_pointer(road, heights, [n])
                call run_point_budget(caller, box, spring%law, preload, heights, settings, u, f, delta, error)
            end if
        end if
        call put_if(compression, delta)
        status = finish(error, errmsg, errmsg_len)
    end function gc_run_contact_law

    !> int gc_contact_start_law(gc_convolver *conv, const gc_law *law, double preload,
    !> const gc_contact_options *options, char *errmsg, size_t errmsg_len): reset the convolver
    !> and start a contact run stepped by gc_contact_advance.
    function gc_contact_start_law(conv, law, preload, options, errmsg, errmsg_len) &
        bind(c, name='gc_contact_start_law') result(status)
        !> The convolver; reset here.
        type(c_ptr), value, intent(in) :: conv
        !> The contact law (gc_law_new).
        type(c_ptr), value, intent(in) :: law
        !> Static preload F0 [N], >= 0.
        real(c_double), value, intent(in) :: preload
        !> Contact options, or NULL for the defaults.
        type(c_ptr), value, intent(in) :: options
        !> Message buffer, or NULL.
        type(c_ptr), value, intent(in) :: errmsg
        !> Size of the message buffer [bytes].
        integer(c_size_t), value, intent(in) :: errmsg_len
        integer(c_int) :: status

        type(convolver_box), pointer :: box
        type(law_box), pointer :: spring
        character(len=:), allocatable :: caller
        type(error_type), allocatable :: error
        type(contact_options) :: settings

        call point_and_law(conv, law, 'gc_contact_start_law', box, spring, caller, error)
        if (associated(box)) box%stepping = .false.
        if (.not. allocated(error)) then
            call check_contact_law(spring%law, preload, error)
            if (allocated(error)) error%message = caller//': '//error%message
            if (.not. allocated(error)) call options_from_c(options, settings, error)
            if (.not. allocated(error)) call start_point_budget(caller, box, spring%law, preload, settings, error)
        end if
        status = finish(error, errmsg, errmsg_len)
    end function gc_contact_start_law

    !> int gc_contact_advance(gc_convolver *conv, double road, double *displacement,
    !> double *force, double *compression, char *errmsg, size_t errmsg_len): the next step of
    !> the run gc_contact_start began, with its scheme.
    function gc_contact_advance(conv, road, displacement, force, compression, errmsg, errmsg_len) &
        bind(c, name='gc_contact_advance') result(status)
        !> The convolver, advanced by one step.
        type(c_ptr), value, intent(in) :: conv
        !> Road height u_r(t_n) [m] of this step.
        real(c_double), value, intent(in) :: road
        !> Where the body displacement u(t_n) [m] goes (0 on a fault).
        type(c_ptr), value, intent(in) :: displacement
        !> Where the contact force F(t_n) [N] goes (0 on a fault).
        type(c_ptr), value, intent(in) :: force
        !> Where the compression delta(t_n) [m] goes (0 on a fault), or NULL.
        type(c_ptr), value, intent(in) :: compression
        !> Message buffer, or NULL.
        type(c_ptr), value, intent(in) :: errmsg
        !> Size of the message buffer [bytes].
        integer(c_size_t), value, intent(in) :: errmsg_len
        integer(c_int) :: status

        type(convolver_box), pointer :: box
        type(error_type), allocatable :: error
        real(dp) :: u(1), f(1), delta(1)

        box => box_at(conv)
        u = 0.0_dp
        f = 0.0_dp
        delta = 0.0_dp
        if (.not. associated(box)) then
            call fatal_error(error, 'gc_contact_advance: '//point_null_handle)
        else if (.not. (c_associated(displacement) .and. c_associated(force))) then
            call fatal_error(error, 'gc_contact_advance: displacement and force must not be NULL')
        else if (.not. box%stepping) then
            call fatal_error(error, 'gc_contact_advance: no contact run is going on with this convolver: call ' &
                             //'gc_contact_start first (a fault or a reset ends a run)')
        else if (box%conv%n_points() /= 1) then
            call refuse_multi_point('gc_contact_advance', box, error)
        else
            call check_steps(box, 'gc_contact_advance', 1_int64, error)
            if (allocated(error)) then
                box%stepping = .false.
            else
                call advance_multi_box('gc_contact_advance', box, [real(road, dp)], u, f, delta, error)
            end if
        end if
        call put_if(displacement, u(1))
        call put_if(force, f(1))
        call put_if(compression, delta(1))
        status = finish(error, errmsg, errmsg_len)
    end function gc_contact_advance

    ! ---- identification and scenes -------------------------------------------------------

    !> int gc_identify_frf_file(const char *path, double tol_e, int max_modes, int capacity,
    !> int *n_modes, double *pole_re, double *pole_im, double *residue_re, double *residue_im,
    !> double *error_e, char *errmsg, size_t errmsg_len)
    function gc_identify_frf_file(path, tol_e, max_modes, capacity, n_modes, pole_re, pole_im, residue_re, &
                                  residue_im, error_e, errmsg, errmsg_len) &
        bind(c, name='gc_identify_frf_file') result(status)
        !> Path of the receptance file, NUL-terminated.
        type(c_ptr), value, intent(in) :: path
        !> Target of the identification error E of eq. (7), > 0.
        real(c_double), value, intent(in) :: tol_e
        !> Largest number of modes the LSCE scan tries, >= 1.
        integer(c_int), value, intent(in) :: max_modes
        !> Capacity of the four output arrays, >= 0.
        integer(c_int), value, intent(in) :: capacity
        !> Where the number of modes found goes (an int).
        type(c_ptr), value, intent(in) :: n_modes
        !> Where the real parts of the poles [rad/s] go (capacity values).
        type(c_ptr), value, intent(in) :: pole_re
        !> Where the imaginary parts of the poles [rad/s] go (capacity values).
        type(c_ptr), value, intent(in) :: pole_im
        !> Where the real parts of the residues [m/(N*s)] go (capacity values).
        type(c_ptr), value, intent(in) :: residue_re
        !> Where the imaginary parts of the residues [m/(N*s)] go (capacity values).
        type(c_ptr), value, intent(in) :: residue_im
        !> Where the error E of eq. (7) of the model goes (a double).
        type(c_ptr), value, intent(in) :: error_e
        !> Message buffer, or NULL.
        type(c_ptr), value, intent(in) :: errmsg
        !> Size of the message buffer [bytes].
        integer(c_size_t), value, intent(in) :: errmsg_len
        integer(c_int) :: status

        character(len=*), parameter :: caller = 'gc_identify_frf_file'
        type(error_type), allocatable :: error
        type(modal_set) :: modes
        real(dp) :: e_value

        call check_outputs(caller, [n_modes, pole_re, pole_im, residue_re, residue_im, error_e], &
                           [character(len=10) :: 'n_modes', 'pole_re', 'pole_im', 'residue_re', 'residue_im', &
                            'error_e'], error)
        call need_pointer(caller, path, 'path', 'pass the name of a receptance file', error)
        call need_capacity(caller, int(capacity), error)
        if (allocated(error)) then
            status = finish(error, errmsg, errmsg_len)
            return
        end if
        call put_if(n_modes, 0)
        call identify_file(from_c(path), tol_e, int(max_modes), modes, e_value, error)
        call put(error_e, e_value)
        if (.not. allocated(error)) call put_if(n_modes, modes%n_modes())
        call modes_to_c(caller, modes, int(capacity), pole_re, pole_im, residue_re, residue_im, error)
        status = finish(error, errmsg, errmsg_len)
    end function gc_identify_frf_file

    !> int gc_run_scene(const char *path, char *errmsg, size_t errmsg_len)
    function gc_run_scene(path, errmsg, errmsg_len) bind(c, name='gc_run_scene') result(status)
        !> Path of the namelist scene file, NUL-terminated.
        type(c_ptr), value, intent(in) :: path
        !> Message buffer, or NULL.
        type(c_ptr), value, intent(in) :: errmsg
        !> Size of the message buffer [bytes].
        integer(c_size_t), value, intent(in) :: errmsg_len
        integer(c_int) :: status

        type(error_type), allocatable :: error

        call run_scene_file(from_c(path), output_unit, error)
        flush (output_unit)
        status = finish(error, errmsg, errmsg_len)
    end function gc_run_scene

    ! ---- conversions -------------------------------------------------------------------------

    !> The box and the law behind the handles of a single-point door that takes a law, and the
    !> name its messages give (that of the (k_c, p) door for a law it made); a NULL handle
    !> refused (status 2), the convolver's first.
    subroutine point_and_law(conv, law, door, box, spring, caller, error)
        !> The `gc_convolver *` and the `const gc_law *`.
        type(c_ptr), intent(in) :: conv, law
        !> The door's own name.
        character(len=*), intent(in) :: door
        !> The box behind conv, or null.
        type(convolver_box), pointer, intent(out) :: box
        !> The law behind law, or null.
        type(law_box), pointer, intent(out) :: spring
        !> The name the door's messages give.
        character(len=:), allocatable, intent(out) :: caller
        !> Set (`stat_input`) for a NULL handle.
        type(error_type), allocatable, intent(out) :: error

        box => box_at(conv)
        spring => law_at(law)
        call door_name(spring, door, caller)
        if (.not. associated(box)) then
            call fatal_error(error, caller//': '//point_null_handle)
        else if (.not. associated(spring)) then
            call fatal_error(error, caller//': law is NULL: make a law with gc_law_new')
        end if
    end subroutine point_and_law

    !> Build the convolver `method` for a structure into *conv, unless `error` is already set;
    !> the status, with the message copied to the caller's buffer.
    function made(caller, method, structure, dt, n_steps, options, conv, error, errmsg, errmsg_len) result(status)
        character(len=*), intent(in) :: caller
        type(c_ptr), intent(in) :: method, options, conv, errmsg
        type(structure_model), intent(in) :: structure
        real(c_double), intent(in) :: dt
        integer(c_int), intent(in) :: n_steps
        type(error_type), allocatable, intent(inout) :: error
        integer(c_size_t), intent(in) :: errmsg_len
        integer(c_int) :: status

        type(c_ptr), pointer :: handle
        type(gc_build_options), pointer :: settings
        type(gc_build_options), target :: defaults
        type(convolver_box), pointer :: box

        call start_door(caller, conv, 'gc_convolver', method, error)
        if (.not. allocated(error)) then
            defaults = gc_build_options(default_truncation_tol, default_accuracy)
            settings => defaults
            if (c_associated(options)) call c_f_pointer(options, settings)
            call new_box(from_c(method), structure, dt, int(n_steps), box, error, settings%truncation_tol, &
                         settings%accuracy)
            if (allocated(error)) error%message = caller//': '//error%message
        end if
        if (.not. allocated(error)) then
            call c_f_pointer(conv, handle)
            handle = c_loc(box)
        end if
        status = finish(error, errmsg, errmsg_len)
    end function made

    !> Refuse (`stat_input`) the first NULL among a door's output pointers, by its name.
    subroutine check_outputs(caller, pointers, names, error)
        character(len=*), intent(in) :: caller
        type(c_ptr), intent(in) :: pointers(:)
        character(len=*), intent(in) :: names(:)
        type(error_type), allocatable, intent(out) :: error

        integer :: i

        do i = 1, size(pointers)
            call need_pointer(caller, pointers(i), trim(names(i)), 'pass where it should go', error)
        end do
    end subroutine check_outputs

    !> The Fortran contact options from a C `gc_contact_options *` (defaults for NULL).
    subroutine options_from_c(options, settings, error)
        type(c_ptr), intent(in) :: options
        type(contact_options), intent(out) :: settings
        type(error_type), allocatable, intent(out) :: error

        type(gc_contact_options), pointer :: given

        if (.not. c_associated(options)) return
        call c_f_pointer(options, given)
        select case (given%scheme)
        case (gc_scheme_explicit)
            settings%scheme = 'explicit'
        case (gc_scheme_implicit)
            settings%scheme = 'implicit'
        case default
            call fatal_error(error, 'options->scheme = '//int_text(int(given%scheme))//': expected ' &
                             //'GC_SCHEME_EXPLICIT (0) or GC_SCHEME_IMPLICIT (1)')
            return
        end select
        settings%max_iterations = int(given%max_iterations)
        settings%divergence_bound = given%divergence_bound
        settings%tolerance = given%tolerance
    end subroutine options_from_c


    !> int gc_identify_ml_file(const char *path, const char *noise_model, int max_order, int capacity,
    !> int *n_modes, int *n_determined, double *pole_re, double *pole_im, double *residue_re,
    !> double *residue_im, double *sigma_f, double *sigma_xi, int *determined, char *errmsg,
    !> size_t errmsg_len): the modes of a receptance file by maximum likelihood (order by MDL,
    !> noise model "auto" from the data), lowest natural frequency first, each with its standard
    !> deviations and determined[k] = 1 when the data determine it, 0 for a pole of the fitted
    !> receptance they do not (as the column `determined` of a scene's modes file).
    function gc_identify_ml_file(path, noise_model, max_order, capacity, n_modes, n_determined, pole_re, pole_im, &
                                 residue_re, residue_im, sigma_f, sigma_xi, determined, errmsg, errmsg_len) &
        bind(c, name='gc_identify_ml_file') result(status)
        !> Path of the receptance file (columns or a universal file), NUL-terminated.
        type(c_ptr), value, intent(in) :: path
        !> "auto", "relative", "absolute", "floor" or "band", NUL-terminated; NULL for "auto".
        type(c_ptr), value, intent(in) :: noise_model
        !> Highest order of the stabilisation diagram (modes), 1 to 200 (30 is usual).
        integer(c_int), value, intent(in) :: max_order
        !> Capacity of the seven output arrays, >= 0.
        integer(c_int), value, intent(in) :: capacity
        !> Where the number of modes found goes (an int; set also when it exceeds capacity).
        type(c_ptr), value, intent(in) :: n_modes
        !> Where the number of modes the data determine goes (an int).
        type(c_ptr), value, intent(in) :: n_determined
        !> Where the real parts of the poles [rad/s] go (capacity values).
        type(c_ptr), value, intent(in) :: pole_re
        !> Where the imaginary parts of the poles [rad/s] go.
        type(c_ptr), value, intent(in) :: pole_im
        !> Where the real parts of the residues [m/(N*s)] go.
        type(c_ptr), value, intent(in) :: residue_re
        !> Where the imaginary parts of the residues [m/(N*s)] go.
        type(c_ptr), value, intent(in) :: residue_im
        !> Where the standard deviations of the natural frequencies [Hz] go.
        type(c_ptr), value, intent(in) :: sigma_f
        !> Where the standard deviations of the damping ratios go.
        type(c_ptr), value, intent(in) :: sigma_xi
        !> Where the flags go (ints): 1 determined by the data, 0 not.
        type(c_ptr), value, intent(in) :: determined
        !> Message buffer, or NULL.
        type(c_ptr), value, intent(in) :: errmsg
        !> Size of the message buffer [bytes].
        integer(c_size_t), value, intent(in) :: errmsg_len
        integer(c_int) :: status

        character(len=*), parameter :: caller = 'gc_identify_ml_file'
        type(error_type), allocatable :: error
        type(ml_result) :: result
        character(len=:), allocatable :: model

        call need_pointer(caller, path, 'path', 'pass the name of a receptance file', error)
        call need_pointers(caller, [n_modes, n_determined, pole_re, pole_im, residue_re, residue_im, sigma_f, &
                                    sigma_xi, determined], 'n_modes, n_determined, pole_re, pole_im, residue_re, ' &
                           //'residue_im, sigma_f, sigma_xi and determined', 'pass where they should go', error)
        call need_capacity(caller, int(capacity), error)
        if (allocated(error)) then
            status = finish(error, errmsg, errmsg_len)
            return
        end if
        call put_if(n_modes, 0)
        call put_if(n_determined, 0)
        model = 'auto'
        if (c_associated(noise_model)) model = from_c(noise_model)
        call identify_file_ml(from_c(path), model, int(max_order), result, error)
        if (.not. allocated(error)) then
            call put_if(n_modes, result%modes%n_modes())
            call put_if(n_determined, count(result%determined_modes()))
            call modes_to_c(caller, result%modes, int(capacity), pole_re, pole_im, residue_re, residue_im, error)
            if (.not. allocated(error)) then
                call put_if(sigma_f, result%sigma_frequency)
                call put_if(sigma_xi, result%sigma_damping)
                call put_if(determined, merge(1, 0, result%determined_modes()))
            end if
        end if
        status = finish(error, errmsg, errmsg_len)
    end function gc_identify_ml_file

end module greenconv_capi
