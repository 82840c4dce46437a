!> Entry points for programs that embed greenconv rather than run the driver: build any
!> convolver from a structure with its inputs checked (`new_convolver`, from
!> greenconv_conv_builder, the methods and their defaults from the registry
!> greenconv_conv_methods), step a contact loop yourself one step at a time, free a
!> convolver, run a scene file.
!>
!> Every procedure here works only on its arguments: there is no module state, so two
!> simulations in one program (or in two threads, see greenconv_ext_fftw on FFTW's planner) do not
!> interfere. Failures come back as an allocated `error_type` (status and message), never
!> as a `stop`.
module greenconv_api_library
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type, fatal_error
    use greenconv_conv_convolver, only: convolver, free_convolver
    use greenconv_contact_laws, only: contact_law, replicate_law
    use greenconv_contact_step, only: contact_options, contact_state, start_state, step_contact, step_load
    use greenconv_conv_methods, only: default_truncation_tol, default_accuracy
    use greenconv_conv_builder, only: new_convolver
    use greenconv_scene_facade, only: scene_type, read_scene, run_scene
    implicit none
    private

    !> Re-exported: `new_convolver` (greenconv_conv_builder), `free_convolver`
    !> (greenconv_conv_convolver), the defaults of the methods (greenconv_conv_methods).
    public :: new_convolver, free_convolver, contact_step, check_contact_law, run_scene_file
    public :: default_truncation_tol, default_accuracy

    !> The paper's explicit step with no bound on |u| (`contact_step` stops only on a value
    !> that is not finite).
    type(contact_options), parameter :: unbounded = contact_options(divergence_bound=huge(1.0_dp))

contains

    !> One explicit step n of the contact loop, greenconv_contact_step's `step_contact` as
    !> `run_contact` takes it (eqs. 20-24): u_h = history, delta = delta0 + u_r - u_h with
    !> delta0 = (F0/k_c)^(1/p), F = k_c*delta^p (0 when delta <= 0), u = u_h + w0*(F - F0), the
    !> load F - F0 pushed (half of it at step 0, `step_load`). Start from a convolver at step 0
    !> (new or reset): the body rests in static equilibrium under F0. No divergence bound is set
    !> on |u|. When u, F or delta is not a finite number, the values of the step are returned as
    !> they came out and, with `error` present, the step is refused (the convolver not advanced);
    !> without it the step is pushed like any other.
    subroutine contact_step(conv, law, road, preload, displacement, force, compression, error)
        !> The convolver, advanced by one step.
        class(convolver), intent(inout) :: conv
        !> The contact law.
        class(contact_law), intent(in) :: law
        !> Road height u_r(t_n) [m] under the contact.
        real(dp), intent(in) :: road
        !> Static preload F0 [N], >= 0.
        real(dp), intent(in) :: preload
        !> Body displacement u(t_n) [m] from static equilibrium.
        real(dp), intent(out) :: displacement
        !> Contact force F(t_n) [N], >= 0.
        real(dp), intent(out) :: force
        !> Compression delta(t_n) [m] of the contact spring (<= 0: no contact).
        real(dp), intent(out), optional :: compression
        !> Set (`stat_numerical`, naming the step) when u, F or delta is not finite; the
        !> convolver is then not advanced. Absent: such a step is pushed as it came out.
        type(error_type), allocatable, intent(out), optional :: error

        type(contact_state) :: state
        type(error_type), allocatable :: fault
        class(contact_law), allocatable :: laws(:)
        real(dp) :: weight0(1, 1), u_h(1), step_force(1), u(1), load(1)
        integer :: iterations

        weight0(1, 1) = conv%instant_weight()
        displacement = 0.0_dp
        force = 0.0_dp
        if (present(compression)) compression = 0.0_dp
        call replicate_law(law, 1, laws)
        call start_state(laws, [preload], weight0, conv%dt, unbounded, state, fault)
        if (allocated(fault)) then
            if (present(error)) call move_alloc(fault, error)
            return
        end if
        state%step = conv%step
        u_h(1) = conv%history()
        call step_contact(state, weight0, u_h, [road], step_force, u, iterations, fault)
        displacement = u(1)
        force = step_force(1)
        if (present(compression)) compression = state%delta(1)
        if (allocated(fault) .and. present(error)) then
            call move_alloc(fault, error)
            return
        end if
        ! without `error` a step whose values are not finite is pushed as any other, as step n
        if (allocated(fault)) state%step = state%step + 1
        load = step_load(state, step_force)
        call conv%push(load(1))
    end subroutine contact_step

    !> Check a contact law (its own `check`) and a preload F0 >= 0, finite.
    subroutine check_contact_law(law, preload, error)
        !> The contact law.
        class(contact_law), intent(in) :: law
        !> Static preload F0 [N].
        real(dp), intent(in) :: preload
        !> Set (status `stat_input`) when a value is out of range.
        type(error_type), allocatable, intent(out) :: error

        call law%check(error)
        if (allocated(error)) return
        if (.not. (preload >= 0.0_dp .and. ieee_is_finite(preload))) then
            call fatal_error(error, 'contact: the preload F0 must be finite and >= 0 N')
        end if
    end subroutine check_contact_law

    !> Read a scene file and run it as the driver does: column files in its output_dir and
    !> a summary line per method on `unit`.
    subroutine run_scene_file(path, unit, error)
        !> Path of the namelist scene file.
        character(len=*), intent(in) :: path
        !> Unit the summary is printed on (an open formatted unit, e.g. output_unit).
        integer, intent(in) :: unit
        !> Set when the scene is unusable (status `stat_input`) or a run fails; status
        !> `stat_accuracy` (4) when all ran and wrote their files but a method's own error estimate
        !> exceeds the scene's `accuracy`.
        type(error_type), allocatable, intent(out) :: error

        type(scene_type) :: scene

        call read_scene(path, scene, error)
        if (allocated(error)) return
        call run_scene(scene, unit, error)
    end subroutine run_scene_file

end module greenconv_api_library
