!> Scene files for tests: the paper's Tab. 1 scene with the values a scene must state
!> (greenconv_scene_read_schema), any group replaced or left out, a writer of small text files
!> and a FIFO fed with a file.
module scene_text_mod
    use, intrinsic :: iso_fortran_env, only: dp => real64
    use greenconv_io_files, only: make_directory
    use greenconv, only: scene_type, read_scene, error_type
    use greenconv_io_columns, only: read_columns
    use greenconv_scene_run_runner, only: run_scene
    implicit none
    private

    public :: tab1_scene, write_text, read_scene_text, omit, run_scene_text, read_table, message_of, feed_fifo

    !> Passed as a group's body: leave the group out.
    character(len=*), parameter :: omit = '-'

contains

    !> The Tab. 1 scene with each group's required values; a group given replaces the
    !> default body (`omit` leaves it out). &identification appears only when given.
    !> Each group is on its own line, in the order scene, structure, identification, road,
    !> contact, convolution.
    function tab1_scene(scene, structure, identification, road, contact, convolution) result(text)
        !> Body of &scene (default `dt = 1.0e-4, n_steps = 2000`).
        character(len=*), intent(in), optional :: scene
        !> Body of &structure (default the sdof M = 1 kg, K = 1e6 N/m, xi = 0.02).
        character(len=*), intent(in), optional :: structure
        !> Body of &identification (default: no group).
        character(len=*), intent(in), optional :: identification
        !> Body of &road (default the sine road).
        character(len=*), intent(in), optional :: road
        !> Body of &contact (default Hertz, k_c = 1e6 N/m^1.5).
        character(len=*), intent(in), optional :: contact
        !> Body of &convolution (default direct and modal).
        character(len=*), intent(in), optional :: convolution
        character(len=:), allocatable :: text

        text = group('scene', 'dt = 1.0e-4, n_steps = 2000', scene) &
               //group('structure', "model = 'sdof', mass = 1.0, stiffness = 1.0e6, damping_ratio = 0.02", &
                       structure) &
               //group('identification', omit, identification) &
               //group('road', "profile = 'sine'", road) &
               //group('contact', 'stiffness = 1.0e6, exponent = 1.5', contact) &
               //group('convolution', "methods = 'direct', 'modal'", convolution)
    end function tab1_scene

    !> `&name body /` and a line end, with the given body or the default; '' when omitted.
    function group(name, default, body) result(text)
        character(len=*), intent(in) :: name, default
        character(len=*), intent(in), optional :: body
        character(len=:), allocatable :: text

        character(len=:), allocatable :: chosen

        chosen = default
        if (present(body)) chosen = body
        text = ''
        if (chosen /= omit) text = '&'//name//' '//chosen//' /'//new_line('a')
    end function group

    !> Write text (lines separated by new_line) to a file, replacing it.
    subroutine write_text(path, text)
        !> The file.
        character(len=*), intent(in) :: path
        !> Its content.
        character(len=*), intent(in) :: text

        integer :: unit

        open (newunit=unit, file=path, status='replace', action='write', form='formatted')
        write (unit, '(a)') text
        close (unit)
    end subroutine write_text

    !> Write `text` as the scene file directory/name (the directory made if missing) and read it.
    subroutine read_scene_text(directory, name, text, scene, error)
        !> Directory of the file.
        character(len=*), intent(in) :: directory
        !> File name.
        character(len=*), intent(in) :: name
        !> The scene's text.
        character(len=*), intent(in) :: text
        !> The scene read.
        type(scene_type), intent(out) :: scene
        !> Set when read_scene refuses it.
        type(error_type), allocatable, intent(out) :: error

        call make_directory(directory, error)
        if (allocated(error)) return
        call write_text(directory//'/'//name, text)
        call read_scene(directory//'/'//name, scene, error)
    end subroutine read_scene_text

    !> Write `text` as the scene file directory/name, read it and run it (its summary thrown away).
    subroutine run_scene_text(directory, name, text, error)
        !> Directory of the file.
        character(len=*), intent(in) :: directory
        !> File name.
        character(len=*), intent(in) :: name
        !> The scene's text.
        character(len=*), intent(in) :: text
        !> Set when the scene is refused or its run fails.
        type(error_type), allocatable, intent(out) :: error

        type(scene_type) :: scene
        integer :: unit

        call read_scene_text(directory, name, text, scene, error)
        if (allocated(error)) return
        open (newunit=unit, status='scratch', action='readwrite')
        call run_scene(scene, unit, error)
        close (unit)
    end subroutine run_scene_text

    !> Read a table of `n_columns` numbers per row (comment lines skipped).
    subroutine read_table(path, n_columns, rows, error)
        !> The file.
        character(len=*), intent(in) :: path
        !> Numbers per row.
        integer, intent(in) :: n_columns
        !> The rows, rows(i, j) the j-th number of row i.
        real(dp), allocatable, intent(out) :: rows(:, :)
        !> Set when the file cannot be read as such a table.
        type(error_type), allocatable, intent(out) :: error

        character(len=8) :: names(n_columns)
        integer, allocatable :: line_of(:)
        integer :: k

        do k = 1, n_columns
            write (names(k), '(a,i0)') 'c', k
        end do
        call read_columns(path, names, [(' ', k=1, n_columns)], rows, line_of, error)
    end subroutine read_table

    !> The message of an error, '' when none.
    pure function message_of(error) result(text)
        !> The error, or none.
        type(error_type), allocatable, intent(in) :: error
        !> Its message.
        character(len=:), allocatable :: text

        text = ''
        if (allocated(error)) text = error%message
    end function message_of

    !> Make the FIFO `fifo` (its directory too when missing) and start one writer of the file
    !> `source` into it in the background (stopped after 60 s); `made` false when mkfifo fails.
    subroutine feed_fifo(fifo, source, made)
        !> The FIFO's path.
        character(len=*), intent(in) :: fifo
        !> The file written into it.
        character(len=*), intent(in) :: source
        !> Whether the FIFO was made and its writer started.
        logical, intent(out) :: made

        type(error_type), allocatable :: directory_error
        integer :: status

        call make_directory(fifo(:index(fifo, '/', back=.true.) - 1), directory_error)
        call execute_command_line('rm -f '//fifo//' && mkfifo '//fifo, exitstat=status)
        made = status == 0
        if (made) call execute_command_line('timeout 60 sh -c ''cat '//source//' > '//fifo//''' &')
    end subroutine feed_fifo

end module scene_text_mod
