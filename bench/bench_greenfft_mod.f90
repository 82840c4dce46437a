!> The multi-point `fft` engine (greenconv_conv_green_fft) against the multi-point `direct`:
!>
!> - `greenfft_cost_table`: CPU seconds per bare step (history, then push) of both on random
!>   tables g_ij(t_m), against N_c and N_g; `direct` is timed after N_g warm-up pushes (every
!>   step sums all N_g samples), `fft` over several of its largest blocks (its bursts included);
!> - `tyre_scene_speedup`: the tyre scene (data/tyre_road.nml) run by the scene runner with the
!>   methods `direct` and `fft` in one run, into out/bench/, the contact loop's CPU seconds of
!>   each, their ratio, and the largest difference of the two output files read back.
module bench_greenfft_mod
    use, intrinsic :: iso_fortran_env, only: int64
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type, fatal_error
    use greenconv_core_random, only: random_stream
    use greenconv_conv_multipoint, only: multipoint_convolver
    use greenconv_conv_green_sampled, only: sampled_green_matrix, new_sampled_green_matrix
    use greenconv_conv_green_fft, only: fft_green_matrix, new_fft_green_matrix
    use greenconv_scene_read_input, only: scene_type, read_scene, output_path
    use greenconv_scene_run_runner, only: run_scene
    implicit none
    private

    public :: greenfft_cost_table, tyre_scene_speedup

    !> Tables of more than this many samples N_c^2*N_g are left out (memory of the spectra).
    real(dp), parameter :: max_samples = 8.0e6_dp
    !> Shortest total CPU time [s] of one measurement.
    real(dp), parameter :: min_total = 0.2_dp

contains

    !> Print CPU seconds per step of multi-point `direct` and `fft` for N_c x N_g cases.
    subroutine greenfft_cost_table(unit, error, n_points, lengths)
        !> Unit the table is printed on.
        integer, intent(in) :: unit
        !> Set when a convolver cannot be built.
        type(error_type), allocatable, intent(out) :: error
        !> Numbers of points N_c; (1, 5, 20, 50) when absent.
        integer, intent(in), optional :: n_points(:)
        !> Kernel lengths N_g; (300, 2741, 10000) when absent.
        integer, intent(in), optional :: lengths(:)

        integer, allocatable :: counts(:), sizes(:)
        integer :: a, b

        counts = [1, 5, 20, 50]
        if (present(n_points)) counts = n_points
        sizes = [300, 2741, 10000]
        if (present(lengths)) sizes = lengths
        write (unit, '(a)') '# Multi-point fft against direct (random g_ij tables; bare steps: history, then push)', &
            '# N_c    N_g   direct_s_per_step   fft_s_per_step   direct/fft'
        do a = 1, size(counts)
            do b = 1, size(sizes)
                if (real(counts(a), dp)**2*sizes(b) > max_samples) cycle
                call cost_row(unit, counts(a), sizes(b), error)
                if (allocated(error)) return
            end do
        end do
        write (unit, '(a)') ''
    end subroutine greenfft_cost_table

    !> Time both engines on one random table and print one row.
    subroutine cost_row(unit, n_c, n_g, error)
        integer, intent(in) :: unit, n_c, n_g
        type(error_type), allocatable, intent(out) :: error

        type(sampled_green_matrix) :: direct
        type(fft_green_matrix) :: partitioned
        type(random_stream) :: stream
        real(dp), allocatable :: kernel(:, :, :)
        real(dp) :: t_direct, t_fft
        integer :: i, j, m

        allocate (kernel(0:n_g, n_c, n_c))
        stream = random_stream(n_c*100000 + n_g)
        do j = 1, n_c
            do i = 1, n_c
                do m = 0, n_g
                    kernel(m, i, j) = stream%between(-1.0_dp, 1.0_dp)*exp(-3.0_dp*m/n_g)
                end do
            end do
        end do
        call new_sampled_green_matrix(kernel, 1.0e-4_dp, direct, error)
        if (allocated(error)) return
        t_direct = step_seconds(direct, n_g, max(20, min(2000, int(2.0e7_dp/(real(n_c, dp)**2*n_g)))))
        deallocate (direct%weight, direct%past)
        call new_fft_green_matrix(kernel, 1.0e-4_dp, partitioned, error)
        if (allocated(error)) return
        deallocate (kernel)
        t_fft = step_seconds(partitioned, 0, max(2*n_g, 4096))
        call partitioned%release()
        write (unit, '(i5,i7,3x,es14.4,5x,es14.4,3x,f10.1)') n_c, n_g, t_direct, t_fft, &
            t_direct/max(t_fft, tiny(1.0_dp))
    end subroutine cost_row

    !> CPU seconds per step of runs of n_steps steps after `warm_up` pushes, the forces
    !> q_i = 1 N - (1e-3 N/m)*u_h,i depending on the history; repeated to `min_total`.
    function step_seconds(conv, warm_up, n_steps) result(seconds)
        class(multipoint_convolver), intent(inout) :: conv
        integer, intent(in) :: warm_up, n_steps
        real(dp) :: seconds

        real(dp) :: u(conv%n_points()), start, finish
        integer :: n, runs

        runs = 0
        call cpu_time(start)
        do
            call conv%reset()
            u(:) = 0.0_dp
            do n = 1, warm_up
                call conv%push(u)
            end do
            call cpu_time(start)
            do n = 1, n_steps
                call conv%history(u)
                call conv%push(1.0_dp - 1.0e-3_dp*u)
            end do
            call cpu_time(finish)
            runs = runs + 1
            if (runs*(finish - start) >= min_total .or. runs >= 50) exit
        end do
        seconds = (finish - start)/n_steps
    end function step_seconds

    !> Run the tyre scene with `direct` and `fft` into out/bench and print the summary, the
    !> speed-up of the contact loop and the largest difference of the two files read back.
    subroutine tyre_scene_speedup(unit, scene_file, output_dir, error)
        !> Unit the lines are printed on.
        integer, intent(in) :: unit
        !> The tyre scene (data/tyre_road.nml).
        character(len=*), intent(in) :: scene_file
        !> Directory of the two column files.
        character(len=*), intent(in) :: output_dir
        !> Set when the scene cannot be read or run.
        type(error_type), allocatable, intent(out) :: error

        type(scene_type) :: scene
        character(len=400) :: line
        real(dp) :: seconds(2), difference
        integer :: scratch, stat, k

        call read_scene(scene_file, scene, error)
        if (allocated(error)) return
        scene%methods = [character(len=len(scene%methods)) :: 'direct', 'fft']
        scene%output_dir = output_dir
        scene%progress = .false.
        open (newunit=scratch, status='scratch', action='readwrite', form='formatted')
        call run_scene(scene, scratch, error)
        if (allocated(error)) return
        rewind (scratch)
        write (unit, '(a)') '# Tyre scene '//scene_file//' with direct and fft in one run (scene runner, '// &
            'cpu_s = contact loop)'
        k = 0
        do
            read (scratch, '(a)', iostat=stat) line
            if (stat /= 0) exit
            write (unit, '(a)') trim(line)
            if (line(1:7) == 'direct ' .or. line(1:4) == 'fft ') then
                k = min(k + 1, 2)
                read (line(36:45), *, iostat=stat) seconds(k)
            end if
        end do
        close (scratch)
        if (k /= 2) then
            call fatal_error(error, 'tyre_scene_speedup: the runner''s summary has no cpu_s of direct and fft')
            return
        end if
        call largest_difference(output_path(scene, 'direct'), output_path(scene, 'fft'), difference, error)
        if (allocated(error)) return
        write (unit, '(a,f0.1,a,es9.2,a)') '# fft speed-up over direct: ', seconds(1)/max(seconds(2), 1.0e-4_dp), &
            'x; largest |fft - direct| per column over max|direct| of the column: ', difference, &
            ' (files read back)'
        write (unit, '(a)') ''
    end subroutine tyre_scene_speedup

    !> Largest |a - b|/max|b| over the columns of two column files of equal layout.
    subroutine largest_difference(path_b, path_a, difference, error)
        character(len=*), intent(in) :: path_b, path_a
        real(dp), intent(out) :: difference
        type(error_type), allocatable, intent(out) :: error

        real(dp), allocatable :: a(:, :), b(:, :)
        real(dp) :: scale
        integer :: c

        call read_table(path_a, a, error)
        if (.not. allocated(error)) call read_table(path_b, b, error)
        if (allocated(error)) return
        if (any(shape(a) /= shape(b))) then
            call fatal_error(error, 'tyre_scene_speedup: '//path_a//' and '//path_b//' differ in shape')
            return
        end if
        difference = 0.0_dp
        do c = 1, size(b, 1)
            scale = maxval(abs(b(c, :)))
            if (scale > 0.0_dp) difference = max(difference, maxval(abs(a(c, :) - b(c, :)))/scale)
        end do
    end subroutine largest_difference

    !> The rows of a column file (lines starting with # skipped), table(column, row).
    subroutine read_table(path, table, error)
        character(len=*), intent(in) :: path
        real(dp), allocatable, intent(out) :: table(:, :)
        type(error_type), allocatable, intent(out) :: error

        character(len=4096) :: line
        integer :: unit, stat, rows, columns, r

        open (newunit=unit, file=path, status='old', action='read', iostat=stat)
        if (stat /= 0) then
            call fatal_error(error, 'tyre_scene_speedup: cannot open '//path)
            return
        end if
        rows = 0
        columns = 0
        do
            read (unit, '(a)', iostat=stat) line
            if (stat /= 0) exit
            if (line(1:1) == '#' .or. len_trim(line) == 0) cycle
            rows = rows + 1
            if (columns == 0) columns = count_words(line)
        end do
        allocate (table(columns, rows))
        rewind (unit)
        r = 0
        do while (r < rows)
            read (unit, '(a)', iostat=stat) line
            if (stat /= 0) exit
            if (line(1:1) == '#' .or. len_trim(line) == 0) cycle
            r = r + 1
            read (line, *, iostat=stat) table(:, r)
            if (stat /= 0) exit
        end do
        close (unit)
        if (r /= rows .or. stat /= 0) call fatal_error(error, 'tyre_scene_speedup: cannot read the rows of '//path)
    end subroutine read_table

    !> Number of blank-separated words of a line.
    pure integer function count_words(line)
        character(len=*), intent(in) :: line

        integer :: i
        logical :: inside

        count_words = 0
        inside = .false.
        do i = 1, len_trim(line)
            if (line(i:i) /= ' ' .and. .not. inside) count_words = count_words + 1
            inside = line(i:i) /= ' '
        end do
    end function count_words

end module bench_greenfft_mod
