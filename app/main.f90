!> greenconv driver: run the contact scene of a namelist file.
!>
!>     greenconv [--check] [--quiet] SCENE.nml
!>     greenconv --version | --help
!>
!> Writes one column file per method into the scene's output directory and a summary
!> per method on standard output. `--check` reads and checks the scene and the files it
!> names, prints one line saying what a run would do, and writes nothing. `--quiet` turns
!> the progress line off (it is shown on standard error only when that is a terminal).
!> `--version` prints "greenconv x.y.z" (fpm.toml's version) and `--help` the usage line, both
!> on standard output with status 0.
!> Exit status: 0 done; 2 bad input (one line on standard error naming the file, group and
!> variable, or an output file that could not be written, which is then absent, or standard
!> output that could not be written, e.g. a full device: the summary is then lost); 3 a
!> numerical fault (one line saying where; the rows before it are written); 4 done, every file
!> written, but a method's own error estimate exceeds the scene's `accuracy` (its summary line
!> says by how much, one line on standard error names the methods). SIGINT and
!> SIGTERM delete the temporary `<out>.<pid>.<n>.part` files in flight.
!> A sweep scene (`task = 'sweep'`, a `&sweep` group; greenconv_scene_sweep) runs its
!> variants one after the other into `<name>_sweep.dat` (mpi/greenconv_mpi.f90 shares them
!> among MPI ranks); it must be a regular file, as it is read once per variant.
program greenconv_driver
    use, intrinsic :: iso_fortran_env, only: output_unit, error_unit, int64
    use greenconv, only: scene_type, read_scene, run_scene, check_scene, error_type, greenconv_version
    use greenconv_io_files, only: remove_parts_on_signals, standard_output_is_terminal, relay_to_standard_output
    use greenconv_scene_sweep, only: is_sweep_file, run_sweep
    implicit none

    character(len=*), parameter :: usage = 'usage: greenconv [--check] [--quiet] SCENE.nml   ' &
                                           //'(for example: greenconv data/sdof_sine.nml), ' &
                                           //'or greenconv --version'
    type(scene_type) :: scene
    type(error_type), allocatable :: error, output_error
    character(len=:), allocatable :: path, argument
    logical :: check_only, quiet, sweep
    integer :: i, length, status, out
    integer(int64) :: file_size

    check_only = .false.
    quiet = .false.
    path = ''
    do i = 1, command_argument_count()
        call get_command_argument(i, length=length)
        allocate (character(len=length) :: argument)
        call get_command_argument(i, argument)
        select case (argument)
        case ('--check')
            check_only = .true.
        case ('--quiet')
            quiet = .true.
        case ('-h', '--help')
            write (output_unit, '(a)') usage
            stop
        case ('--version')
            write (output_unit, '(a)') 'greenconv '//greenconv_version()
            stop
        case default
            if (index(argument, '-') == 1 .or. len(path) > 0) call usage_error('unexpected argument '//argument)
            path = argument
        end select
        deallocate (argument)
    end do
    if (len(path) == 0) call usage_error('no scene file given')

    ! SIGINT/SIGTERM delete the temporary files of the outputs being written.
    call remove_parts_on_signals()
    ! Standard output that is no terminal (a file, a pipe, a full device) gets the summary at
    ! the end, through writes whose failure is seen (gfortran drops them on its own unit).
    out = output_unit
    if (.not. standard_output_is_terminal()) open (newunit=out, status='scratch', action='readwrite')
    ! A sweep is a regular file (size > 0); a pipe or a FIFO is read once, as one scene.
    inquire (file=path, size=file_size)
    sweep = .false.
    if (file_size > 0) sweep = is_sweep_file(path)
    if (sweep) then
        call run_sweep(path, out, check_only, error)
    else
        call read_scene(path, scene, error)
    end if
    ! Freed here and below (the scene keeps its own copy): the main program's variables are
    ! not freed at its end, and valgrind would count them as lost.
    deallocate (path)
    if (.not. allocated(error) .and. .not. sweep) then
        if (quiet) scene%progress = .false.
        if (check_only) then
            call check_scene(scene, out, error)
        else
            call run_scene(scene, out, error)
        end if
    end if
    if (out /= output_unit) then
        call relay_to_standard_output(out, output_error)
        ! A failed run keeps its own message and status; a run whose summary was lost fails.
        if (allocated(output_error) .and. .not. allocated(error)) call move_alloc(output_error, error)
        if (allocated(output_error)) deallocate (output_error)
    end if
    if (allocated(error)) then
        write (error_unit, '(a)') 'greenconv: '//error%message
        status = error%stat
        deallocate (error)
        stop status, quiet=.true.
    end if

contains

    !> One line on what is wrong with the command line and how to call the driver; exit 2.
    subroutine usage_error(what)
        character(len=*), intent(in) :: what

        write (error_unit, '(a)') 'greenconv: '//what//'; '//usage
        stop 2, quiet=.true.
    end subroutine usage_error

end program greenconv_driver
