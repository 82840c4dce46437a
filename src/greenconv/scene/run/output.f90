!> Column files of the contact runs: the layout of a multi-point run's histories (one row
!> per step and point) that the multi-point scenes stream and `write_multi_contact` writes
!> whole; a 2D patch (a Green's matrix file's points) adds the column y [m] last. And the
!> totals of a multi-point run (one row per kept step: t, the total force, the contact area,
!> the points in contact), which it writes whatever its per-point histories.
module greenconv_scene_run_output
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type
    use greenconv_io_files, only: write_columns, check_input_kept
    use greenconv_scene_read_facade, only: scene_type, place_error
    use greenconv_contact_multi, only: multi_contact_response
    implicit none
    private

    public :: write_multi_contact, multi_contact_header, multi_contact_table, check_inputs_kept
    public :: totals_header, totals_table

contains

    !> Refuse (`stat_input`, both names in the message) a scene whose input files (the scene
    !> file, the receptance or Green's matrix file, the road file or texture) lie where its
    !> outputs go, `<output_dir>/<name>_*.dat` and the like (greenconv_io_files's
    !> `check_input_kept`): the run would replace them. Called before anything
    !> is written, by the run, by `--check` and for every variant of a sweep.
    subroutine check_inputs_kept(scene, error)
        !> The scene, as `read_scene` returned it.
        type(scene_type), intent(in) :: scene
        !> Set when an input would be overwritten.
        type(error_type), allocatable, intent(out) :: error

        character(len=:), allocatable :: prefix

        prefix = scene%name//'_'
        call check_input_kept(scene%file, scene%output_dir, prefix, error)
        if (allocated(error)) then
            error%message = scene%file//': the scene file '//error%message
            return
        end if
        call check_named(scene%frf_file, 'structure', 'frf_file')
        call check_named(scene%green_file, 'structure', 'green_file')
        call check_named(scene%road_data%path, 'road', 'road_file')
        call check_named(scene%texture%path, 'road', 'texture_file')

    contains

        !> The input a scene variable names, its place put before a refusal.
        subroutine check_named(path, group, variable)
            !> The input's path (not allocated: the scene names none).
            character(len=:), allocatable, intent(in) :: path
            !> Group and variable that name it, lower case.
            character(len=*), intent(in) :: group, variable

            if (allocated(error) .or. .not. allocated(path)) return
            call check_input_kept(path, scene%output_dir, prefix, error)
            if (allocated(error)) call place_error(error, scene, group, variable)
        end subroutine check_named
    end subroutine check_inputs_kept

    !> Write a run as one row per step and point, time-major, with a blank-free layout that
    !> gnuplot maps directly (`plot FILE using 2:1:5 with image` gives F over x and t):
    !> columns t [s], x [m], u_road [m], u [m], f_contact [N], delta [m], f_total [N].
    subroutine write_multi_contact(path, title, positions, response, error)
        !> Target file (written atomically).
        character(len=*), intent(in) :: path
        !> First header line, e.g. the scene and method.
        character(len=*), intent(in) :: title
        !> Position x_i [m] of each point, for the second column.
        real(dp), intent(in) :: positions(:)
        !> Histories of the run.
        type(multi_contact_response), intent(in) :: response
        !> Set when the file cannot be written.
        type(error_type), allocatable, intent(out) :: error

        call write_columns(path, multi_contact_header(title), multi_contact_table(positions, response, 0, 1), error)
    end subroutine write_multi_contact

    !> The header lines of `write_multi_contact`'s files: the title, the units, the columns.
    pure function multi_contact_header(title, with_y) result(comments)
        !> First header line, e.g. the scene and method.
        character(len=*), intent(in) :: title
        !> Whether the rows end with the column y [m] (`multi_contact_table` given `across`).
        logical, intent(in), optional :: with_y
        character(len=200) :: comments(3)

        comments(1) = title
        comments(2) = 'units: s m m m N m N'
        comments(3) = 't x u_road u f_contact delta f_total'
        if (present(with_y)) then
            if (with_y) then
                comments(2) = trim(comments(2))//' m'
                comments(3) = trim(comments(3))//' y'
            end if
        end if
    end function multi_contact_header

    !> The rows of `write_multi_contact` for the steps j = first, first + stride, ... of
    !> `response` (N_c rows per step: t, x, u_road, u, f_contact, delta, f_total, and y when
    !> `across` is given).
    pure function multi_contact_table(positions, response, first, stride, across) result(table)
        !> Position x_i [m] of each point, for the second column.
        real(dp), intent(in) :: positions(:)
        !> Histories (of a run or of one block).
        type(multi_contact_response), intent(in) :: response
        !> Index (from 0) of the first step written.
        integer, intent(in) :: first
        !> Steps between two rows written, >= 1.
        integer, intent(in) :: stride
        !> Position y_i [m] of each point across, for an eighth column.
        real(dp), intent(in), optional :: across(:)
        real(dp), allocatable :: table(:, :)

        integer :: n_c, n, row

        n_c = size(positions)
        allocate (table(n_c*size(response%time(first::stride)), merge(8, 7, present(across))))
        row = 0
        do n = first, size(response%time) - 1, stride
            table(row + 1:row + n_c, 1) = response%time(n)
            table(row + 1:row + n_c, 2) = positions
            table(row + 1:row + n_c, 3) = response%road(n, :)
            table(row + 1:row + n_c, 4) = response%displacement(n, :)
            table(row + 1:row + n_c, 5) = response%force(n, :)
            table(row + 1:row + n_c, 6) = response%compression(n, :)
            table(row + 1:row + n_c, 7) = response%total_force(n)
            if (present(across)) table(row + 1:row + n_c, 8) = across
            row = row + n_c
        end do
    end function multi_contact_table


    !> The header lines of a totals file: the title, the units, the columns.
    pure function totals_header(title, share) result(comments)
        !> First header line, e.g. the scene and method.
        character(len=*), intent(in) :: title
        !> Area [m^2] each point in contact counts.
        real(dp), intent(in) :: share
        character(len=200) :: comments(4)

        comments(1) = title
        write (comments(2), '(a,es24.17,a)') 'contact area: the points with a force > 0, each counting ', share, &
            ' m^2 (its share of the patch)'
        comments(3) = 'units: s N m^2 1'
        comments(4) = 't f_total area n_contact'
    end function totals_header

    !> The totals of the steps j = first, first + stride, ... of `response`: t [s], the total
    !> contact force [N], the contact area [m^2] (`share` times the points in contact) and the
    !> number of points in contact (a force > 0).
    pure function totals_table(response, first, stride, share) result(table)
        !> Histories (of a run or of one block).
        type(multi_contact_response), intent(in) :: response
        !> Index (from 0) of the first step written.
        integer, intent(in) :: first
        !> Steps between two rows written, >= 1.
        integer, intent(in) :: stride
        !> Area [m^2] each point in contact counts.
        real(dp), intent(in) :: share
        real(dp), allocatable :: table(:, :)

        integer :: n, row

        allocate (table(size(response%time(first::stride)), 4))
        row = 0
        do n = first, size(response%time) - 1, stride
            row = row + 1
            table(row, 1) = response%time(n)
            table(row, 2) = response%total_force(n)
            table(row, 4) = real(count(response%force(n, :) > 0.0_dp), dp)
            table(row, 3) = share*table(row, 4)
        end do
    end function totals_table

end module greenconv_scene_run_output
