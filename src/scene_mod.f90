!> A contact scene read from a namelist file: time grid, structure, road, contact law and
!> convolution methods. Every variable has a default (the paper's Tab. 1 and section 3.1),
!> so a scene file states only what differs, and every group is optional:
!>
!>     &scene       name = 'sdof_sine', output_dir = 'out', dt = 1.0e-4 [s], n_steps = 2000 /
!>     &structure   model = 'sdof', mass = 1.0 [kg], stiffness = 1.0e6 [N/m], damping_ratio = 0.02 /
!>     &road        profile = 'sine', amplitude = 1.0e-3 [m], omega = 100.0 [rad/s] /
!>     &contact     stiffness = 1.0e6 [N/m^p], exponent = 1.5, gravity = 9.81 [m/s^2],
!>                  preload = mass*gravity [N] (any negative value selects this default) /
!>     &convolution methods = 'direct', 'modal', truncation_tol = 0.01 /
module scene_mod
    use, intrinsic :: iso_fortran_env, only: iostat_end
    use kinds_mod, only: dp
    use error_mod, only: error_type, fatal_error
    use road_mod, only: road_profile, sine_road
    use contact_mod, only: contact_law
    implicit none
    private

    public :: scene_type, read_scene

    !> Length of names read from a namelist.
    integer, parameter :: name_length = 64
    !> Length of paths read from a namelist.
    integer, parameter :: path_length = 1024
    !> Largest number of methods one scene may list.
    integer, parameter :: max_methods = 8

    !> Everything a contact run needs, in SI units.
    type :: scene_type
        !> The namelist file the scene came from.
        character(len=:), allocatable :: file
        !> Base name of the output files.
        character(len=:), allocatable :: name
        !> Directory the column files are written to.
        character(len=:), allocatable :: output_dir
        !> Time step [s].
        real(dp) :: dt = 1.0e-4_dp
        !> Number of time steps N_t.
        integer :: n_steps = 2000
        !> Structure model (`sdof`).
        character(len=:), allocatable :: model
        !> Mass M [kg] of the sdof model.
        real(dp) :: mass = 1.0_dp
        !> Stiffness K [N/m] of the sdof model.
        real(dp) :: stiffness = 1.0e6_dp
        !> Damping ratio xi of the sdof model.
        real(dp) :: damping_ratio = 0.02_dp
        !> Road profile.
        class(road_profile), allocatable :: road
        !> Contact law.
        type(contact_law) :: law
        !> Static preload F0 [N].
        real(dp) :: preload = 9.81_dp
        !> Convolution methods to run, in order.
        character(len=name_length), allocatable :: methods(:)
        !> Truncation fraction of max |g| for the direct method.
        real(dp) :: truncation_tol = 0.01_dp
    end type scene_type

contains

    !> Read and check a scene namelist file.
    subroutine read_scene(path, scene, error)
        !> Path of the namelist file.
        character(len=*), intent(in) :: path
        !> The scene, with defaults where the file is silent.
        type(scene_type), intent(out) :: scene
        !> Set, naming the file, group and variable, when the input is unusable.
        type(error_type), allocatable, intent(out) :: error

        integer :: unit, stat
        character(len=512) :: message

        scene%file = path
        open (newunit=unit, file=path, status='old', action='read', iostat=stat, iomsg=message)
        if (stat /= 0) then
            call fatal_error(error, path//': cannot open the scene file: '//trim(message))
            return
        end if
        call read_scene_group(unit, scene, error)
        if (.not. allocated(error)) call read_structure_group(unit, scene, error)
        if (.not. allocated(error)) call read_road_group(unit, scene, error)
        if (.not. allocated(error)) call read_contact_group(unit, scene, error)
        if (.not. allocated(error)) call read_convolution_group(unit, scene, error)
        close (unit)
    end subroutine read_scene

    !> &scene: name, output_dir, dt [s], n_steps.
    subroutine read_scene_group(unit, this, error)
        integer, intent(in) :: unit
        type(scene_type), intent(inout) :: this
        type(error_type), allocatable, intent(out) :: error

        character(len=name_length) :: name
        character(len=path_length) :: output_dir
        real(dp) :: dt
        integer :: n_steps, stat
        character(len=512) :: message
        namelist /scene/ name, output_dir, dt, n_steps

        name = 'sdof_sine'
        output_dir = 'out'
        dt = this%dt
        n_steps = this%n_steps
        rewind (unit)
        read (unit, nml=scene, iostat=stat, iomsg=message)
        call group_status(this%file, 'scene', stat, message, error)
        if (allocated(error)) return
        call require(len_trim(name) > 0, expected(this%file, 'scene', 'name', 'a file base name'), error)
        call require(len_trim(output_dir) > 0, expected(this%file, 'scene', 'output_dir', 'a directory path'), error)
        call require(dt > 0.0_dp, expected(this%file, 'scene', 'dt', 'a time step > 0 s', dt), error)
        call require(n_steps > 0, expected(this%file, 'scene', 'n_steps', 'a step count > 0', n_steps), error)
        this%name = trim(name)
        this%output_dir = trim(output_dir)
        this%dt = dt
        this%n_steps = n_steps
    end subroutine read_scene_group

    !> &structure: model, mass [kg], stiffness [N/m], damping_ratio.
    subroutine read_structure_group(unit, this, error)
        integer, intent(in) :: unit
        type(scene_type), intent(inout) :: this
        type(error_type), allocatable, intent(out) :: error

        character(len=name_length) :: model
        real(dp) :: mass, stiffness, damping_ratio
        integer :: stat
        character(len=512) :: message
        namelist /structure/ model, mass, stiffness, damping_ratio

        model = 'sdof'
        mass = this%mass
        stiffness = this%stiffness
        damping_ratio = this%damping_ratio
        rewind (unit)
        read (unit, nml=structure, iostat=stat, iomsg=message)
        call group_status(this%file, 'structure', stat, message, error)
        if (allocated(error)) return
        call require(trim(model) == 'sdof', expected(this%file, 'structure', 'model', "'sdof'", model), error)
        call require(mass > 0.0_dp, &
            expected(this%file, 'structure', 'mass', 'a mass > 0 kg', mass), error)
        call require(stiffness > 0.0_dp, &
            expected(this%file, 'structure', 'stiffness', 'a stiffness > 0 N/m', stiffness), error)
        call require(damping_ratio >= 0.0_dp .and. damping_ratio < 1.0_dp, &
            expected(this%file, 'structure', 'damping_ratio', 'a ratio in [0, 1)', &
                                             damping_ratio), error)
        this%model = trim(model)
        this%mass = mass
        this%stiffness = stiffness
        this%damping_ratio = damping_ratio
    end subroutine read_structure_group

    !> &road: profile, amplitude [m], omega [rad/s].
    subroutine read_road_group(unit, this, error)
        integer, intent(in) :: unit
        type(scene_type), intent(inout) :: this
        type(error_type), allocatable, intent(out) :: error

        character(len=name_length) :: profile
        type(sine_road) :: sine
        real(dp) :: amplitude, omega
        integer :: stat
        character(len=512) :: message
        namelist /road/ profile, amplitude, omega

        profile = 'sine'
        amplitude = sine%amplitude
        omega = sine%omega
        rewind (unit)
        read (unit, nml=road, iostat=stat, iomsg=message)
        call group_status(this%file, 'road', stat, message, error)
        if (allocated(error)) return
        call require(trim(profile) == 'sine', expected(this%file, 'road', 'profile', "'sine'", profile), error)
        call require(abs(amplitude) < huge(amplitude), &
            expected(this%file, 'road', 'amplitude', 'a finite height in m', amplitude), error)
        call require(abs(omega) < huge(omega), &
            expected(this%file, 'road', 'omega', 'a finite angular frequency in rad/s', omega), error)
        sine%amplitude = amplitude
        sine%omega = omega
        this%road = sine
    end subroutine read_road_group

    !> &contact: stiffness [N/m^p], exponent, gravity [m/s^2], preload [N].
    subroutine read_contact_group(unit, this, error)
        integer, intent(in) :: unit
        type(scene_type), intent(inout) :: this
        type(error_type), allocatable, intent(out) :: error

        real(dp) :: stiffness, exponent, gravity, preload
        integer :: stat
        character(len=512) :: message
        namelist /contact/ stiffness, exponent, gravity, preload

        stiffness = this%law%stiffness
        exponent = this%law%exponent
        gravity = 9.81_dp
        preload = -1.0_dp
        rewind (unit)
        read (unit, nml=contact, iostat=stat, iomsg=message)
        call group_status(this%file, 'contact', stat, message, error)
        if (allocated(error)) return
        call require(stiffness > 0.0_dp, &
            expected(this%file, 'contact', 'stiffness', 'a stiffness k_c > 0 N/m^p', stiffness), error)
        call require(exponent > 0.0_dp, &
            expected(this%file, 'contact', 'exponent', 'an exponent p > 0', exponent), error)
        call require(gravity >= 0.0_dp, &
            expected(this%file, 'contact', 'gravity', 'an acceleration >= 0 m/s^2', gravity), error)
        call require(abs(preload) < huge(preload), expected(this%file, 'contact', 'preload', 'a finite force in N', preload), &
                     error)
        this%law = contact_law(stiffness=stiffness, exponent=exponent)
        this%preload = preload
        if (preload < 0.0_dp) this%preload = this%mass*gravity
    end subroutine read_contact_group

    !> &convolution: methods (list of names), truncation_tol.
    subroutine read_convolution_group(unit, this, error)
        integer, intent(in) :: unit
        type(scene_type), intent(inout) :: this
        type(error_type), allocatable, intent(out) :: error

        character(len=name_length) :: methods(max_methods)
        real(dp) :: truncation_tol
        integer :: stat, i
        character(len=512) :: message
        namelist /convolution/ methods, truncation_tol

        methods = ''
        methods(1:2) = [character(len=name_length) :: 'direct', 'modal']
        truncation_tol = this%truncation_tol
        rewind (unit)
        read (unit, nml=convolution, iostat=stat, iomsg=message)
        call group_status(this%file, 'convolution', stat, message, error)
        if (allocated(error)) return
        do i = 1, max_methods
            select case (trim(methods(i)))
            case ('', 'direct', 'modal')
            case default
                call fatal_error(error, expected(this%file, 'convolution', 'methods', "'direct' or 'modal'", methods(i)))
                return
            end select
        end do
        call require(truncation_tol > 0.0_dp .and. truncation_tol < 1.0_dp, &
            expected(this%file, 'convolution', 'truncation_tol', &
                                             'a fraction of max |g| in (0, 1)', truncation_tol), error)
        this%methods = pack(methods, methods /= '')
        call require(size(this%methods) > 0, expected(this%file, 'convolution', 'methods', 'at least one method'), error)
        this%truncation_tol = truncation_tol
    end subroutine read_convolution_group

    !> Turn the status of a namelist read into an error; a missing group is no error.
    subroutine group_status(file, group, stat, message, error)
        character(len=*), intent(in) :: file, group, message
        integer, intent(in) :: stat
        type(error_type), allocatable, intent(out) :: error

        if (stat == 0 .or. stat == iostat_end) return
        call fatal_error(error, file//': &'//group//': '//trim(message))
    end subroutine group_status

    !> "file: &group variable: expected what[, found value]"; value is a real, an integer or a text.
    function expected(file, group, variable, what, found) result(line)
        character(len=*), intent(in) :: file, group, variable, what
        class(*), intent(in), optional :: found
        character(len=:), allocatable :: line

        character(len=32) :: value

        line = file//': &'//group//' '//variable//': expected '//what
        if (.not. present(found)) return
        select type (found)
        type is (real(dp))
            write (value, '(g0.6)') found
            line = line//', found '//trim(value)
        type is (integer)
            write (value, '(i0)') found
            line = line//', found '//trim(value)
        type is (character(len=*))
            line = line//", found '"//trim(found)//"'"
        end select
    end function expected

    !> Record `message` as the error unless `ok` holds or an earlier check already failed.
    subroutine require(ok, message, error)
        logical, intent(in) :: ok
        character(len=*), intent(in) :: message
        type(error_type), allocatable, intent(inout) :: error

        if (ok .or. allocated(error)) return
        call fatal_error(error, message)
    end subroutine require

end module scene_mod
