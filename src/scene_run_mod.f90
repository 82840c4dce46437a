!> Run a scene: build the Green's function, one convolver per method, the contact loop,
!> the column files and a one-line summary per method.
module scene_run_mod
    use kinds_mod, only: dp
    use error_mod, only: error_type, fatal_error
    use modal_set_mod, only: modal_set
    use sdof_mod, only: sdof_modes
    use convolver_mod, only: convolver
    use conv_direct_mod, only: new_direct_convolver, sample_kernel
    use conv_modal_mod, only: new_modal_convolver
    use contact_mod, only: contact_response, run_contact
    use files_mod, only: write_columns, make_directory
    use scene_mod, only: scene_type
    implicit none
    private

    public :: run_scene, make_convolver, output_path

    !> Width of the text columns of the summary.
    character(len=*), parameter :: summary_format = '(a,t12,a,t24,i10,t36,f10.4,t48,a)'

contains

    !> Run every method of a scene, write `<output_dir>/<name>_<method>.dat` for each and
    !> print a summary line per method on `unit` (method, model size, steps, CPU seconds,
    !> what the model neglects).
    subroutine run_scene(scene, unit, error)
        !> The scene.
        type(scene_type), intent(in) :: scene
        !> Unit the summary is printed on.
        integer, intent(in) :: unit
        !> Set when a convolver cannot be built or a file cannot be written.
        type(error_type), allocatable, intent(out) :: error

        type(modal_set) :: modes
        class(convolver), allocatable :: conv
        type(contact_response) :: response
        character(len=:), allocatable :: accuracy, label
        real(dp), allocatable :: road(:)
        real(dp) :: start, finish
        integer :: i, n

        modes = sdof_modes(scene%mass, scene%stiffness, scene%damping_ratio)
        road = scene%road%sample(scene%dt, scene%n_steps)
        call make_directory(scene%output_dir, error)
        if (allocated(error)) return
        write (unit, '(a,i0,a,es10.3,a)') '# scene '//scene%name//': ', scene%n_steps, ' steps of ', scene%dt, ' s'
        write (unit, '(a,t12,a,t24,a,t36,a,t48,a)') '# method', 'size', 'steps', 'cpu_s', 'accuracy'
        do i = 1, size(scene%methods)
            call make_convolver(trim(scene%methods(i)), modes, scene%dt, scene%truncation_tol, scene%n_steps, &
                                conv, accuracy, error)
            if (allocated(error)) return
            call cpu_time(start)
            call run_contact(conv, scene%law, road, scene%preload, response)
            call cpu_time(finish)
            call conv%model_size(n, label)
            call write_response(output_path(scene, conv%name), scene, conv, response, error)
            if (allocated(error)) return
            write (unit, summary_format) conv%name, label//'='//itoa(n), scene%n_steps, finish - start, accuracy
        end do
    end subroutine run_scene

    !> Build the convolver called `method` for a modal Green's function.
    !>
    !> `accuracy` says in words how far the model is from the exact g: the neglected tail
    !> of the truncated kernel (`direct`) or the fit of the modes (`modal`).
    subroutine make_convolver(method, modes, dt, truncation_tol, n_steps, conv, accuracy, error)
        !> Method name: `direct` or `modal`.
        character(len=*), intent(in) :: method
        !> The Green's function as modes.
        type(modal_set), intent(in) :: modes
        !> Time step [s].
        real(dp), intent(in) :: dt
        !> Truncation fraction of max |g| for `direct`.
        real(dp), intent(in) :: truncation_tol
        !> Number of steps of the run.
        integer, intent(in) :: n_steps
        !> The convolver.
        class(convolver), allocatable, intent(out) :: conv
        !> What the model neglects, in words.
        character(len=:), allocatable, intent(out) :: accuracy
        !> Set for an unknown method.
        type(error_type), allocatable, intent(out) :: error

        real(dp), allocatable :: kernel(:)
        real(dp) :: tail
        character(len=16) :: text

        select case (method)
        case ('direct')
            call sample_kernel(modes, dt, truncation_tol, n_steps, kernel, tail)
            conv = new_direct_convolver(kernel, dt)
            if (tail > 0.0_dp) then
                write (text, '(es9.2)') tail
                accuracy = 'neglected tail <= '//trim(adjustl(text))//' of max|g|'
            else
                accuracy = 'exact: the kernel covers the whole run'
            end if
        case ('modal')
            conv = new_modal_convolver(modes, dt)
            accuracy = 'exact: the modes are the structure''s own'
        case default
            call fatal_error(error, "unknown convolution method '"//method//"': expected 'direct' or 'modal'")
        end select
    end subroutine make_convolver

    !> Path of the column file of one method: `<output_dir>/<name>_<method>.dat`.
    function output_path(scene, method) result(path)
        !> The scene.
        type(scene_type), intent(in) :: scene
        !> Method name.
        character(len=*), intent(in) :: method
        character(len=:), allocatable :: path

        path = scene%output_dir//'/'//scene%name//'_'//method//'.dat'
    end function output_path

    !> Write the histories of one run as columns t, u_road, u, f_contact, delta.
    subroutine write_response(path, scene, conv, response, error)
        character(len=*), intent(in) :: path
        type(scene_type), intent(in) :: scene
        class(convolver), intent(in) :: conv
        type(contact_response), intent(in) :: response
        type(error_type), allocatable, intent(out) :: error

        character(len=200) :: comments(3)
        character(len=:), allocatable :: label
        integer :: n

        call conv%model_size(n, label)
        write (comments(1), '(a,i0,a,es10.3,a)') 'greenconv scene '//scene%name//', method '//conv%name//' (' &
            //label//' = '//itoa(n)//'), ', scene%n_steps, ' steps of ', scene%dt, ' s'
        comments(2) = 'units: s m m N m'
        comments(3) = 't u_road u f_contact delta'
        call write_columns(path, comments, reshape([response%time, response%road, response%displacement, &
                                                    response%force, response%compression], &
                                                   [scene%n_steps, 5]), error)
    end subroutine write_response

    !> An integer as text.
    pure function itoa(i) result(text)
        integer, intent(in) :: i
        character(len=:), allocatable :: text

        character(len=16) :: buffer

        write (buffer, '(i0)') i
        text = trim(buffer)
    end function itoa

end module scene_run_mod
