!> Run a scene: build the structure (identifying it when only G is known), then either
!> write the identification (task `identify`) or run the contact loop with one convolver
!> per method (task `contact`), writing column files and a summary line per method.
!>
!> A contact run is streamed in blocks of greenconv_io_files's `block_rows` steps: the road is
!> sampled per block, the contact loop continues from the convolver's state (greenconv_contact_single's
!> `contact_block`), and the block's rows (every `output_every`-th step of the run) are
!> appended to the column file, so the memory a run needs does not grow with N_t. A
!> numerical fault closes the file with the rows before it; bad input or a failed write
!> deletes it. A progress line (greenconv_scene_progress) shows on standard error for long runs.
module greenconv_scene_runner
    use, intrinsic :: iso_fortran_env, only: int64
    use greenconv_core_kinds, only: dp
    use greenconv_core_text, only: int_text, sci_text
    use greenconv_core_error, only: error_type, fatal_error
    use greenconv_conv_convolver, only: convolver, free_convolver
    use greenconv_conv_direct, only: new_direct_convolver
    use greenconv_conv_kernel, only: sample_kernel, truncation_length
    use greenconv_conv_fft, only: new_fft_convolver
    use greenconv_conv_paper, only: new_paper_convolver
    use greenconv_conv_recursive, only: new_recursive_convolver, new_exact_convolver, new_backward_convolver
    use greenconv_contact_single, only: contact_response, contact_state, start_contact, contact_block
    use greenconv_io_files, only: column_writer, open_columns, append_rows, close_run_file, first_kept, block_rows, &
                         make_directory
    use greenconv_scene_progress, only: progress_meter, start_progress, update_progress, finish_progress
    use greenconv_scene_input, only: scene_type, output_path, input_place
    use greenconv_ident_structure, only: structure_model
    use greenconv_scene_structure, only: build_structure
    use greenconv_model_frf, only: frf_type, read_frf
    use greenconv_scene_report, only: write_identification, identification_summary
    use greenconv_scene_tyre, only: run_tyre_scene
    implicit none
    private

    public :: run_scene, check_scene, make_convolver, output_path

    !> `auto` runs the direct sum when N_t*N_g is at most this many multiply-adds (about
    !> 2 ms at the measured 6-7 GMAC/s): then no model is worth building.
    real(dp), parameter :: direct_work_limit = 1.0e7_dp

    !> Layout of the summary line of a method.
    character(len=*), parameter :: summary_format = '(a,t12,a,t24,i10,t36,f10.4,t48,a)'

contains

    !> Run a scene and print its summary on `unit`. Contact: for each method, the file
    !> `<output_dir>/<name>_<method>.dat` and a line (method, model size, steps, CPU seconds,
    !> what the model neglects). Identified structures also get their modes and G files.
    subroutine run_scene(scene, unit, error, block)
        !> The scene.
        type(scene_type), intent(in) :: scene
        !> Unit the summary is printed on.
        integer, intent(in) :: unit
        !> Set when the structure cannot be built or a file cannot be written.
        type(error_type), allocatable, intent(out) :: error
        !> Steps per block of the streamed run (>= 1); by default greenconv_io_files's `block_rows`
        !> (divided by N_c for the tyre scene). The files do not depend on it.
        integer, intent(in), optional :: block

        type(structure_model) :: structure
        integer :: block_size

        if (scene%model == 'tyre') then
            call make_directory(scene%output_dir, error)
            if (.not. allocated(error)) call run_tyre_scene(scene, unit, error, block)
            return
        end if
        block_size = block_rows
        if (present(block)) block_size = max(block, 1)
        call build_structure(scene, structure, error)
        if (allocated(error)) return
        call make_directory(scene%output_dir, error)
        if (allocated(error)) return
        if (structure%identified) then
            call identification_summary(structure, unit)
            call write_identification(scene, structure, error)
            if (allocated(error)) return
        end if
        if (scene%task == 'contact') call run_methods(scene, structure, unit, block_size, error)
    end subroutine run_scene

    !> Check a scene without running it: the scene file was read and checked by `read_scene`
    !> (with its road file); this also reads and checks a receptance file the structure
    !> names, then prints one line on `unit` saying what a run would do. Nothing is written.
    !>
    !>     greenconv: data/sdof_sine.nml: ok: task contact, model sdof, N_t = 2000 steps of 1.000E-04 s, ...
    subroutine check_scene(scene, unit, error)
        !> The scene, as `read_scene` returned it.
        type(scene_type), intent(in) :: scene
        !> Unit the line is printed on.
        integer, intent(in) :: unit
        !> Set when a file the scene names is unusable.
        type(error_type), allocatable, intent(out) :: error

        type(frf_type) :: frf
        character(len=:), allocatable :: line
        integer :: i

        line = 'greenconv: '//scene%file//': ok: task '//scene%task//', model '//scene%model
        if (scene%model == 'frf_file') then
            call read_frf(scene%frf_file, frf, error)
            if (allocated(error)) then
                error%message = input_place(scene, 'structure', 'frf_file')//': '//error%message
                return
            end if
            line = line//' ('//scene%frf_file//': '//int_text(size(frf%frequency))//' lines to ' &
                   //sci_text(frf%frequency(size(frf%frequency)))//' Hz)'
        end if
        if (scene%task == 'contact') then
            line = line//', N_t = '//int_text(scene%n_steps)//' steps of '//sci_text(scene%dt)//' s, ' &
                   //int_text(scene%n_points)//' contact point(s), '
            if (scene%model == 'tyre') then
                line = line//'Newton on all points'
            else
                line = line//trim(scene%contact%scheme)//' step'
            end if
            line = line//', a row every '//int_text(scene%output_every)//' step(s), methods'
            do i = 1, size(scene%methods)
                line = line//' '//trim(scene%methods(i))
            end do
        end if
        write (unit, '(a)') line
    end subroutine check_scene

    !> The contact loop once per method of the scene.
    subroutine run_methods(scene, structure, unit, block, error)
        type(scene_type), intent(in) :: scene
        type(structure_model), intent(in) :: structure
        integer, intent(in) :: unit, block
        type(error_type), allocatable, intent(out) :: error

        class(convolver), allocatable :: conv
        character(len=:), allocatable :: accuracy, label
        real(dp) :: seconds
        integer :: i, n

        write (unit, '(a,i0,a,es10.3,a)') '# scene '//scene%name//': ', scene%n_steps, ' steps of ', scene%dt, ' s'
        write (unit, '(a,t12,a,t24,a,t36,a,t48,a)') '# method', 'size', 'steps', 'cpu_s', 'accuracy'
        do i = 1, size(scene%methods)
            call make_convolver(trim(scene%methods(i)), structure, scene%dt, scene%truncation_tol, scene%n_steps, &
                                conv, accuracy, error, scene%accuracy)
            if (allocated(error)) return
            call stream_contact(scene, trim(scene%methods(i)), conv, block, seconds, error)
            call conv%model_size(n, label)
            call free_convolver(conv)
            if (allocated(error)) return
            write (unit, summary_format) trim(scene%methods(i)), label//'='//int_text(n), scene%n_steps, &
                seconds, accuracy
        end do
    end subroutine run_methods

    !> One method's contact run, streamed in blocks of `block` steps into its column file.
    !> `seconds` is the CPU time of the contact loop alone. A numerical fault keeps the rows
    !> written before it: the file is completed and `error` names it.
    subroutine stream_contact(scene, method, conv, block, seconds, error)
        type(scene_type), intent(in) :: scene
        character(len=*), intent(in) :: method
        class(convolver), intent(inout) :: conv
        integer, intent(in) :: block
        real(dp), intent(out) :: seconds
        type(error_type), allocatable, intent(out) :: error

        type(contact_state) :: state
        type(contact_response) :: response
        type(column_writer) :: writer
        type(progress_meter) :: meter
        type(error_type), allocatable :: fault
        real(dp), allocatable :: road(:)
        integer(int64) :: first
        real(dp) :: start, finish
        integer :: m

        seconds = 0.0_dp
        call start_contact(conv, scene%law, scene%preload, state, error, scene%contact)
        if (allocated(error)) then
            error%message = scene%file//': '//method//': '//error%message
            return
        end if
        call open_columns(writer, output_path(scene, method), response_header(scene, conv), 5, error)
        if (allocated(error)) return
        call start_progress(meter, method, int(scene%n_steps, int64), scene%progress)
        do while (state%step < scene%n_steps)
            first = state%step
            m = int(min(int(block, int64), scene%n_steps - first))
            road = scene%road%sample_steps(scene%dt, first, m)
            call cpu_time(start)
            call contact_block(conv, state, road, response, fault)
            call cpu_time(finish)
            seconds = seconds + (finish - start)
            call append_rows(writer, response_rows(response, first, scene%output_every), error)
            if (allocated(error) .or. allocated(fault)) exit
            call update_progress(meter, state%step)
        end do
        call finish_progress(meter, state%step)
        call close_run_file(writer, fault, scene%file//': '//method//' ('//trim(scene%contact%scheme)//' step): ', &
                            error)
    end subroutine stream_contact

    !> Build the convolver called `method` for a structure.
    !>
    !> `direct` convolves with the structure's own g (from its exact modes, or sampled from
    !> its FRF), truncated by the paper's rule; `fft` computes the same sum by partitioned FFT.
    !> The modal methods recur on the structure's model modes: `paper` (eqs. 15-17 as
    !> written), `recursive` (the same sum with decaying factors), `exact` (force linear
    !> within a step) and `backward` (force constant over the step ending at its sample, first
    !> order, for the implicit step of stiff contacts); `modal` is `recursive`. `auto` picks
    !> the cheapest of these that meets `requested` (see `choose_method`; never `backward`).
    !> `accuracy` says in words how far the model is from the exact g (and, for `auto`, what it
    !> chose and why).
    subroutine make_convolver(method, structure, dt, truncation_tol, n_steps, conv, accuracy, error, requested)
        !> Method name: `direct`, `fft`, `modal`, `paper`, `recursive`, `exact`, `backward` or `auto`.
        character(len=*), intent(in) :: method
        !> The structure.
        type(structure_model), intent(in) :: structure
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
        !> Relative accuracy `auto` must meet (default 1e-3): the largest E (eq. 7) it accepts.
        real(dp), intent(in), optional :: requested

        character(len=:), allocatable :: chosen, reason
        real(dp) :: target

        if (method /= 'auto') then
            call build_method(method, structure, dt, truncation_tol, n_steps, conv, accuracy, error)
            return
        end if
        target = 1.0e-3_dp
        if (present(requested)) target = requested
        call choose_method(structure, dt, truncation_tol, n_steps, target, chosen, reason)
        call build_method(chosen, structure, dt, truncation_tol, n_steps, conv, accuracy, error)
        if (allocated(error)) return
        conv%name = 'auto'
        accuracy = 'chose '//chosen//': '//reason//'; '//accuracy
    end subroutine make_convolver

    !> The cheapest method whose model meets a requested accuracy, and why, in words:
    !> - `direct` when N_t*N_g is at most `direct_work_limit` (the run costs a few ms and
    !>   its only approximation is the truncation of g);
    !> - otherwise `exact` (the first-order hold: a modal recursion's cost, second order in
    !>   dt, the static gain exact) on the structure's modes when they are its own, or on the
    !>   identified model when its E (eq. 7) meets the accuracy; the identification scan
    !>   stops at the smallest such order;
    !> - otherwise `fft` on the sampled g: no modal model up to the scan's largest order does.
    subroutine choose_method(structure, dt, truncation_tol, n_steps, requested, chosen, reason)
        type(structure_model), intent(in) :: structure
        real(dp), intent(in) :: dt, truncation_tol, requested
        integer, intent(in) :: n_steps
        character(len=:), allocatable, intent(out) :: chosen, reason

        real(dp), allocatable :: kernel(:)
        real(dp) :: tail, work

        call direct_kernel(structure, dt, truncation_tol, n_steps, kernel, tail)
        work = real(n_steps, dp)*(size(kernel) - 1)
        if (work <= direct_work_limit) then
            chosen = 'direct'
            reason = 'N_t*N_g = '//sci_text(work)//' <= '//sci_text(direct_work_limit)//' multiply-adds'
        else if (.not. structure%identified) then
            chosen = 'exact'
            reason = 'N_t*N_g = '//sci_text(work)//' and the '//int_text(structure%model%n_modes()) &
                     //' modes are the structure''s own'
        else if (structure%fit%e <= requested) then
            chosen = 'exact'
            reason = int_text(structure%model%n_modes())//' modes, the smallest LSCE model with E <= ' &
                     //sci_text(requested)//' (N_t*N_g = '//sci_text(work)//')'
        else
            chosen = 'fft'
            reason = 'no LSCE model meets E <= '//sci_text(requested)//' (best E = '//sci_text(structure%fit%e) &
                     //'), N_t*N_g = '//sci_text(work)
        end if
    end subroutine choose_method

    !> Build one named method (not `auto`).
    subroutine build_method(method, structure, dt, truncation_tol, n_steps, conv, accuracy, error)
        character(len=*), intent(in) :: method
        type(structure_model), intent(in) :: structure
        real(dp), intent(in) :: dt
        real(dp), intent(in) :: truncation_tol
        integer, intent(in) :: n_steps
        class(convolver), allocatable, intent(out) :: conv
        character(len=:), allocatable, intent(out) :: accuracy
        type(error_type), allocatable, intent(out) :: error

        real(dp), allocatable :: kernel(:)
        real(dp) :: tail, misfit
        integer :: j

        select case (method)
        case ('direct', 'fft')
            call direct_kernel(structure, dt, truncation_tol, n_steps, kernel, tail)
            if (method == 'direct') then
                conv = new_direct_convolver(kernel, dt)
            else
                conv = new_fft_convolver(kernel, dt)
            end if
            accuracy = 'exact: the kernel covers the whole run'
            if (tail > 0.0_dp) accuracy = 'neglected tail <= '//sci_text(tail)//' of max|g|'
            if (.not. structure%has_exact) then
                misfit = maxval(abs(kernel - structure%model%impulse([(j*dt, j=0, size(kernel) - 1)])))
                accuracy = accuracy//'; g by FFT of the band-limited G is off the LSCE modes'' g by ' &
                           //sci_text(misfit/maxval(abs(kernel)))//' of max|g|'
            end if
        case ('paper')
            conv = new_paper_convolver(structure%model, dt)
        case ('modal', 'recursive')
            conv = new_recursive_convolver(structure%model, dt)
        case ('exact')
            conv = new_exact_convolver(structure%model, dt)
        case ('backward')
            conv = new_backward_convolver(structure%model, dt)
        case default
            call fatal_error(error, "unknown convolution method '"//method// &
                             "': expected 'direct', 'fft', 'modal', 'paper', 'recursive', 'exact', 'backward' " &
                             //"or 'auto'")
            return
        end select
        if (method /= 'direct' .and. method /= 'fft') then
            accuracy = 'exact: the modes are the structure''s own'
            if (structure%identified) accuracy = 'LSCE fit of G: E = '//sci_text(structure%fit%e)//' (eq. 7)'
        end if
    end subroutine build_method

    !> The truncated kernel of the structure's own g and the largest neglected sample.
    subroutine direct_kernel(structure, dt, truncation_tol, n_steps, kernel, tail)
        type(structure_model), intent(in) :: structure
        real(dp), intent(in) :: dt, truncation_tol
        integer, intent(in) :: n_steps
        real(dp), allocatable, intent(out) :: kernel(:)
        real(dp), intent(out) :: tail

        integer :: last, n_g

        if (structure%has_exact) then
            call sample_kernel(structure%exact, dt, truncation_tol, n_steps, kernel, tail)
            return
        end if
        last = min(n_steps, size(structure%sampled_g)) - 1
        n_g = truncation_length(structure%sampled_g(1:last + 1), truncation_tol)
        allocate (kernel(0:n_g))
        kernel(:) = structure%sampled_g(1:n_g + 1)
        tail = 0.0_dp
        if (n_g < last) tail = maxval(abs(structure%sampled_g(n_g + 2:last + 1)))/maxval(abs(kernel))
    end subroutine direct_kernel

    !> The header of a method's column file: what ran, the units, the columns (t, u_road,
    !> u, f_contact, delta); with `output_every` > 1, which steps the rows are.
    function response_header(scene, conv) result(comments)
        type(scene_type), intent(in) :: scene
        class(convolver), intent(in) :: conv
        character(len=400) :: comments(3)

        character(len=:), allocatable :: label
        integer :: n

        call conv%model_size(n, label)
        write (comments(1), '(a,i0,a,es10.3,a)') 'greenconv scene '//scene%name//', method '//conv%name//' (' &
            //label//' = '//int_text(n)//'), ', scene%n_steps, ' steps of ', scene%dt, ' s'
        if (scene%output_every > 1) comments(1) = trim(comments(1))//', a row every '//int_text(scene%output_every) &
                                                  //' steps (steps 0, '//int_text(scene%output_every)//', ' &
                                                  //int_text(2*scene%output_every)//', ...)'
        comments(2) = 'units: s m m N m'
        comments(3) = 't u_road u f_contact delta'
    end function response_header

    !> The rows of a block of steps first, first + 1, ... that are written: the steps that
    !> are multiples of `every`.
    function response_rows(response, first, every) result(table)
        type(contact_response), intent(in) :: response
        integer(int64), intent(in) :: first
        integer, intent(in) :: every
        real(dp), allocatable :: table(:, :)

        integer :: j

        j = first_kept(first, every)
        table = reshape([response%time(j::every), response%road(j::every), response%displacement(j::every), &
                         response%force(j::every), response%compression(j::every)], &
                        [size(response%time(j::every)), 5])
    end function response_rows

end module greenconv_scene_runner
