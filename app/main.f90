!> greenconv driver: run the contact scene of a namelist file.
!>
!>     greenconv SCENE.nml
!>
!> Writes one column file per method into the scene's output directory and a summary
!> per method on standard output. Bad input: one line on standard error, exit status 2.
program greenconv_driver
    use, intrinsic :: iso_fortran_env, only: output_unit, error_unit
    use greenconv, only: scene_type, read_scene, run_scene, error_type
    implicit none

    type(scene_type) :: scene
    type(error_type), allocatable :: error
    character(len=:), allocatable :: path
    integer :: length

    if (command_argument_count() /= 1) then
        write (error_unit, '(a)') 'usage: greenconv SCENE.nml   (for example: greenconv data/sdof_sine.nml)'
        stop 2, quiet=.true.
    end if
    call get_command_argument(1, length=length)
    allocate (character(len=length) :: path)
    call get_command_argument(1, path)

    call read_scene(path, scene, error)
    if (.not. allocated(error)) call run_scene(scene, output_unit, error)
    if (allocated(error)) then
        write (error_unit, '(a)') 'greenconv: '//error%message
        stop error%stat, quiet=.true.
    end if
end program greenconv_driver
