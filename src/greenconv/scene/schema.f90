!> What a scene file may and must hold: its groups, the variables of each with the kind of
!> their values (for greenconv_scene_scan), and the values a scene must state because no
!> default would be a sensible guess. README.md's scene table marks them; everything else
!> keeps its default (the paper's Tab. 1).
!>
!> Required:
!>
!>     &scene                        always; dt and n_steps for task 'contact'
!>     &structure model              always
!>       mass, stiffness, damping_ratio      for model 'sdof'
!>       frf_file                            for model 'frf_file'
!>     &road profile                 for task 'contact' (road_file for profile 'file')
!>     &contact stiffness, exponent  for task 'contact'
!>     &convolution methods          for task 'contact'
module greenconv_scene_schema
    use greenconv_core_error, only: error_type, fatal_error
    use greenconv_core_text, only: int_text, lower_text
    use greenconv_scene_scan, only: namelist_variable, namelist_group, namelist_scan, scan_namelist, &
                                 value_real, value_integer, value_logical, value_text, value_text_list
    implicit none
    private

    public :: scan_scene, max_methods

    !> Largest number of methods one scene may list.
    integer, parameter :: max_methods = 8

contains

    !> Scan a scene file (greenconv_scene_scan), then check that it states every required value.
    subroutine scan_scene(path, scan, error)
        !> The scene file.
        character(len=*), intent(in) :: path
        !> Groups and assignments found, with their lines.
        type(namelist_scan), intent(out) :: scan
        !> Set, with one line naming the file, line, group and variable, when the file is unusable.
        type(error_type), allocatable, intent(out) :: error

        call scan_namelist(path, scene_groups(), scan, error)
        if (.not. allocated(error)) call check_required(scan, error)
    end subroutine scan_scene

    !> The groups of a scene file and their variables, each `name:kind` (kind real, integer,
    !> logical, text, or texts*N for a list of at most N texts).
    function scene_groups() result(groups)
        type(namelist_group), allocatable :: groups(:)

        groups = [group_of('scene', 'task:text name:text output_dir:text dt:real n_steps:integer ' &
                           //'output_every:integer progress:logical'), &
                  group_of('structure', 'model:text mass:real stiffness:real damping_ratio:real n_modes:integer ' &
                           //'seed:integer f_low:real f_high:real xi_low:real xi_high:real a_low:real a_high:real ' &
                           //'frf_file:text belt_length:real belt_mass:real belt_bending:real belt_tension:real ' &
                           //'belt_foundation:real f_modes:real'), &
                  group_of('identification', 'f_max:real n_freq:integer tol_e:real max_order:integer order:integer'), &
                  group_of('road', 'profile:text amplitude:real omega:real wavelength:real speed:real ' &
                           //'n_terms:integer seed:integer road_file:text x_start:real'), &
                  group_of('contact', 'stiffness:real exponent:real gravity:real preload:real n_points:integer ' &
                           //'patch_length:real scheme:text divergence_bound:real'), &
                  group_of('convolution', 'methods:texts*'//int_text(max_methods) &
                           //' truncation_tol:real accuracy:real')]
    end function scene_groups

    !> A group from its name and a blank-separated list of `variable:kind`.
    pure function group_of(name, list) result(group)
        character(len=*), intent(in) :: name, list
        type(namelist_group) :: group

        character(len=*), parameter :: kinds(4) = [character(len=8) :: 'real', 'integer', 'logical', 'text']
        integer, parameter :: codes(4) = [value_real, value_integer, value_logical, value_text]
        character(len=:), allocatable :: rest, item
        type(namelist_variable) :: variable
        integer :: blank, colon, k

        group%name = name
        allocate (group%variables(0))
        rest = trim(adjustl(list))
        do while (len(rest) > 0)
            blank = index(rest//' ', ' ')
            item = rest(:blank - 1)
            rest = trim(adjustl(rest(blank:)))
            colon = index(item, ':')
            variable%name = item(:colon - 1)
            variable%kind = value_text_list
            variable%size = 1
            do k = 1, size(kinds)
                if (item(colon + 1:) == trim(kinds(k))) variable%kind = codes(k)
            end do
            if (variable%kind == value_text_list) read (item(index(item, '*') + 1:), *) variable%size
            group%variables = [group%variables, variable]
        end do
    end function group_of

    !> The required values (module description), in the order of the file's groups.
    subroutine check_required(scan, error)
        type(namelist_scan), intent(in) :: scan
        type(error_type), allocatable, intent(out) :: error

        character(len=:), allocatable :: task, model
        logical :: contact

        task = lower_text(scan%value_of('scene', 'task'))
        if (len(task) == 0) task = 'contact'
        contact = task == 'contact'
        model = lower_text(scan%value_of('structure', 'model'))
        call need_group(scan, 'scene', "dt and n_steps for task 'contact'", .true., error)
        call need(scan, 'scene', 'dt', "a time step in s (required for task 'contact')", contact, error)
        call need(scan, 'scene', 'n_steps', "a number of steps (required for task 'contact')", contact, error)
        call need_group(scan, 'structure', 'model', .true., error)
        call need(scan, 'structure', 'model', "the structure model, 'sdof', 'random_modes', 'frf_file' or " &
                  //"'tyre' (required)", .true., error)
        call need(scan, 'structure', 'mass', "the mass M in kg (required for model 'sdof')", model == 'sdof', error)
        call need(scan, 'structure', 'stiffness', "the stiffness K in N/m (required for model 'sdof')", &
                  model == 'sdof', error)
        call need(scan, 'structure', 'damping_ratio', "the damping ratio in [0, 1) (required for model 'sdof')", &
                  model == 'sdof', error)
        call need(scan, 'structure', 'frf_file', "a receptance file (required for model 'frf_file')", &
                  model == 'frf_file', error)
        call need_group(scan, 'road', "profile, for task 'contact'", contact, error)
        call need(scan, 'road', 'profile', "the road profile, 'sine', 'random' or 'file' (required for task " &
                  //"'contact')", contact, error)
        call need(scan, 'road', 'road_file', "a road file (required for profile 'file')", &
                  contact .and. lower_text(scan%value_of('road', 'profile')) == 'file', error)
        call need_group(scan, 'contact', "stiffness and exponent, for task 'contact'", contact, error)
        call need(scan, 'contact', 'stiffness', "the contact stiffness k_c in N/m^p (required for task 'contact')", &
                  contact, error)
        call need(scan, 'contact', 'exponent', "the contact exponent p (required for task 'contact')", contact, error)
        call need_group(scan, 'convolution', "methods, for task 'contact'", contact, error)
        call need(scan, 'convolution', 'methods', "the methods to run, e.g. 'direct', 'modal' (required for task " &
                  //"'contact')", contact, error)
    end subroutine check_required

    !> A required group: `file: &group: expected the group (required: what), found none`.
    subroutine need_group(scan, group, what, required, error)
        type(namelist_scan), intent(in) :: scan
        character(len=*), intent(in) :: group, what
        logical, intent(in) :: required
        type(error_type), allocatable, intent(inout) :: error

        if (allocated(error) .or. .not. required .or. scan%has_group(group)) return
        call fatal_error(error, scan%file//': &'//group//': expected the group &'//group//' ... / (required: ' &
                         //what//'), found none')
    end subroutine need_group

    !> A required value: `file:line: &group variable: expected what, found no value` (the
    !> line of the group).
    subroutine need(scan, group, variable, what, required, error)
        type(namelist_scan), intent(in) :: scan
        character(len=*), intent(in) :: group, variable, what
        logical, intent(in) :: required
        type(error_type), allocatable, intent(inout) :: error

        if (allocated(error) .or. .not. required .or. scan%has_value(group, variable)) return
        call fatal_error(error, scan%file//':'//int_text(scan%line_of(group, ''))//': &'//group//' '//variable &
                         //': expected '//what//', found no value')
    end subroutine need

end module greenconv_scene_schema
