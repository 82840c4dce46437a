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
    use greenconv_contact_single, only: contact_law
    use greenconv_conv_methods, only: default_truncation_tol, default_accuracy
    use greenconv_conv_builder, only: new_convolver
    use greenconv_scene_facade, only: scene_type, read_scene, run_scene
    implicit none
    private

    !> Re-exported: `new_convolver` (greenconv_conv_builder), `free_convolver`
    !> (greenconv_conv_convolver), the defaults of the methods (greenconv_conv_methods).
    public :: new_convolver, free_convolver, contact_step, check_contact_law, run_scene_file
    public :: default_truncation_tol, default_accuracy

contains

    !> One explicit step n of the contact loop, exactly as `run_contact` takes it (eqs. 20-24):
    !> u_h = history, delta = delta0 + u_r - u_h with delta0 = (F0/k_c)^(1/p), F = k_c*delta^p
    !> (0 when delta <= 0), the load F - F0 pushed (half of it at step 0, greenconv_contact_step's
    !> `step_load`), u = u_h + w0*(F - F0). Start from a convolver at step 0 (new or reset): the
    !> body rests in static equilibrium under F0.
    subroutine contact_step(conv, law, road, preload, displacement, force, compression)
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

        real(dp) :: u_h, delta, load

        u_h = conv%history()
        delta = law%compression(preload) + road - u_h
        force = law%force(delta)
        load = force - preload
        displacement = u_h + conv%instant_weight()*load
        ! half the first load: greenconv_contact_step's `step_load`
        if (conv%step == 0) load = 0.5_dp*load
        call conv%push(load)
        if (present(compression)) compression = delta
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
