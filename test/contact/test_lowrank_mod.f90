!> The implicit multi-point step with a low-rank instant compliance: W0 of a modal
!> structure factored as U*V^T and Newton's systems solved by Woodbury
!> (greenconv_contact_lowrank_solve), against the dense LU they replace.
!>
!> Tolerances, each against something computed another way:
!> - Woodbury against dgesv on the same system I + U*V^T*diag(t) (random, conditioned below
!>   1e3, a third of the slopes zero as off the active set): 1e-12 of max|s|, a few hundred
!>   roundings of an O(r) elimination; the same with the kept factors solved again, and with 5
!>   active points, where the system on the active set is the cheaper (its path checked), for
!>   two sets of slopes (the kept factors must not serve the second);
!> - the factors: rank found at most the number of modes (mode shapes sampled over a short
!>   patch are nearly dependent: 11 of 34 tyre modes leave a remainder below round-off) and
!>   |W0 - U*V^T| at most 1e-13 of max|W0| (the elimination stops at 1e-14 of it);
!> - a whole run (tyre, 120 points, exact engine, Hertz points losing and regaining contact)
!>   with the factors against the same run kept dense: 1e-10 of the peak force on every force,
!>   the Newton tolerance being 1e-12 of the compression scale;
!> - M^-1 updated by Sherman-Morrison when two slopes change (a point leaving the contact,
!>   another entering) against dgesv on the new system: 1e-12 of max|s|, the update path checked;
!> - a run of linear springs (p = 1: the slopes stay those of the active set, which changes
!>   from step to step, so M^-1 is updated rather than formed again) with the factors against the
!>   same run kept dense (dgesv on I + W0*diag(t) at every iteration, every product by the dense
!>   W0): 1e-10 of the peak force on every force and displacement, the Newton tolerance being
!>   1e-12 of the compression scale;
!> - W0 of rank >= N_c/2 (fewer points than modes) is left dense, so results stay bit for bit;
!> - threads (a build with -fopenmp): the modal step of 1,000 points on 1 thread, on 2 and from
!>   inside a host's parallel region against the modal forces and history displacements summed
!>   here by plain loops in the serial order: equal bit for bit (tolerance 0). Without OpenMP
!>   the three runs are the serial one;
!> - threads in the implicit step (W0*x by blocks of V's columns and of U's rows, the Woodbury
!>   products, the Newton matrix, the fused modal push): a plate patch of 500 points, W0 of
!>   rank r with N_c*r above the threads' threshold, Hertz points losing and regaining contact,
!>   run on 1 thread, on 2, and twice at once on two host threads (where the library and
!>   LAPACK stay serial): forces and displacements equal bit for bit (tolerance 0). The modes
!>   to 3 kHz give r above 100, where OpenBLAS's OpenMP build threads an r x r LU by itself
!>   (with other round-off) unless called from inside a parallel region;
!> - factors in the modes' span (the plate patch's separable shapes compressed to an orthonormal
!>   basis Psi of fewer columns than modes, U = Psi*A, V = Psi*B, no dense elimination): the
!>   basis factors orthonormal within 1e-13, U*V^T within 1e-13 of max|W0| of W0 (the
!>   compression and the elimination each stop at 1e-14), U and V within 1e-13 of
!>   max(|Psi|*|A|) and max(|Psi|*|B|) of Psi*A and Psi*B formed here entry by entry (a sum of S
!>   products each; the late columns, divided by small pivots, are cancellations, so a bound
!>   relative to max|V| would be too tight); a 200-step run against the same run with the dense
!>   elimination's factors and
!>   with dgesv: 1e-10 of the peak force, the Newton tolerance being 1e-12 of the compression
!>   scale, and the same points in contact at every step;
!> - the plate patch with linear springs rolling over the rough road (points lifting off and
!>   landing, several at once in a step, so that M^-1 takes several rank-one updates in a step,
!>   and the push takes the modal loads kept by the step's last product W0*x) against the same run
!>   with dgesv on the dense W0 at every iteration: the same points in contact at every step,
!>   forces within 1e-10 of the peak force (the Newton tolerance being 1e-12 of the
!>   compression scale). The bound is shown to catch an iteration stopped early: with linear
!>   springs one Newton step on the right active set is the root, so the control is the patch's
!>   Hertz run (p = 1.5, a few iterations a step), whose forces with a Newton tolerance of 1e-3
!>   must miss 1e-10 of the peak against the same run at the default 1e-12;
!> - the same linear springs over 1,200 steps, more rank-one updates than points, so that the
!>   kept M^-1 is checked (M*(M^-1*1) against 1 to 1e-12) instead of formed anew: the check
!>   kept it at least once, and the M^-1 left at the end against M formed anew by plain loops,
!>   ||M*M^-1 - I||_max within 1e-10; forces against the same run with the dense
!>   elimination's factors (other factors, other updates) within 1e-10 of the peak force.
module test_lowrank_mod
    !$ use omp_lib, only: omp_get_max_threads, omp_set_num_threads
    use, intrinsic :: iso_fortran_env, only: dp => real64
    use testsuite_mod, only: test_error, unittest_type, new_unittest, check, note
    use greenconv_core_error, only: error_type
    use greenconv_core_random, only: random_stream
    use greenconv_ext_lapack, only: solve_linear
    use greenconv_model_point_modes, only: point_modes
    use greenconv_model_tyre, only: tyre_belt, tyre_modes, contact_positions
    use greenconv_model_plate, only: tyre_plate, plate_modes, patch_points
    use greenconv_model_road, only: random_road, new_random_road
    use greenconv_conv_green_modal, only: modal_green_matrix, new_modal_green_matrix
    use greenconv_contact_laws, only: contact_law
    use greenconv_contact_multi, only: multi_contact_state, multi_contact_response, start_multi_contact, &
                                       multi_contact_block, newton_options
    use greenconv_contact_lowrank_solve, only: lowrank_compliance, factor_compliance, apply_compliance, &
                                               newton_solve, factor_modal_compliance
    use greenconv_contact_law_power, only: power_law
    implicit none
    private

    public :: collect_lowrank

    !> Time step [s] of the runs (the tyre line's).
    real(dp), parameter :: dt = 5.0e-5_dp

contains

    !> Tests of the low-rank Newton solve.
    subroutine collect_lowrank(testsuite)
        type(unittest_type), allocatable, intent(out) :: testsuite(:)

        testsuite = [new_unittest('Woodbury and active-set solves equal dgesv on I + U V^T diag(t)', test_woodbury), &
                     new_unittest('modal W0 factored: rank at most N_m, U V^T equals W0', test_factors), &
                     new_unittest('tyre run, 120 points: low-rank forces equal the dense run', test_run), &
                     new_unittest('linear springs, 200 points: updated M^-1 forces equal the dense run', &
                                  test_run_updated), &
                     new_unittest('fewer points than modes: W0 stays dense', test_dense_fallback), &
                     new_unittest('modal step on 1, 2 threads and in a host region: bit for bit', test_threads), &
                     new_unittest('implicit plate patch on 1, 2 and two host threads: bit for bit', &
                                  test_implicit_threads), &
                     new_unittest('plate patch: factors in the modes'' span equal the dense factors and dgesv', &
                                  test_modal_span), &
                     new_unittest('modes'' span refused: some w_k < 0, rank not below N_c/2, explicit', &
                                  test_modal_span_refused), &
                     new_unittest('plate patch, linear springs: updated M^-1, kept push equal dgesv at every step', &
                                  test_rank_k_updates), &
                     new_unittest('plate patch, 1,200 steps: M^-1 checked and kept past N_c updates', &
                                  test_inverse_kept)]
    end subroutine collect_lowrank

    !> The default tyre up to f_max [Hz] at n points over a 0.12 m patch centred at 0.5 m on the belt.
    function tyre_points(n, f_max) result(description)
        integer, intent(in) :: n
        real(dp), intent(in) :: f_max
        type(point_modes) :: description

        type(error_type), allocatable :: failure

        call tyre_modes(tyre_belt(), contact_positions(0.5_dp, 0.12_dp, n), f_max, description, failure)
        if (allocated(failure)) error stop 'test_lowrank_mod: '//failure%message
    end function tyre_points

    !> The exact engine's Green's matrix of a description, or stop.
    function exact_matrix(description) result(conv)
        type(point_modes), intent(in) :: description
        type(modal_green_matrix) :: conv

        type(error_type), allocatable :: failure

        call new_modal_green_matrix(description, dt, 'exact', conv, failure)
        if (allocated(failure)) error stop 'test_lowrank_mod: '//failure%message
    end function exact_matrix

    subroutine test_woodbury(error)
        type(test_error), allocatable, intent(out) :: error

        integer, parameter :: n = 60, r = 7
        type(lowrank_compliance) :: factors
        type(random_stream) :: stream
        real(dp) :: weight0(n, n), slopes(n), b(n)
        integer :: i, k

        stream = random_stream(25)
        allocate (factors%left(n, r), factors%right(n, r))
        do k = 1, r
            do i = 1, n
                factors%left(i, k) = 1.0e-6_dp*(stream%uniform() - 0.5_dp)
                factors%right(i, k) = stream%uniform() - 0.5_dp
            end do
        end do
        do i = 1, n
            slopes(i) = 1.0e5_dp*stream%uniform()
            if (mod(i, 3) == 0) slopes(i) = 0.0_dp
            b(i) = 1.0e-4_dp*(stream%uniform() - 0.5_dp)
        end do
        factors%right_t = transpose(factors%right)
        factors%checked = .true.
        factors%low_rank = .true.
        factors%rank = r
        weight0 = matmul(factors%left, transpose(factors%right))
        ! 40 of 60 points active: M of Woodbury (40*49 + 343/3 operations against 40^3/3).
        call compare_with_dense('40 active, Woodbury', factors, weight0, slopes, b, .false., error)
        if (allocated(error)) return
        ! Solved again with the same slopes: the factors kept serve.
        call compare_with_dense('40 active, factors kept', factors, weight0, slopes, 2*b, .false., error)
        if (allocated(error)) return
        ! Point 1 leaves the contact, point 3 enters: M^-1 updated twice, not formed again.
        slopes(1) = 0.0_dp
        slopes(3) = 2.0e4_dp
        call compare_with_dense('40 active, two slopes changed', factors, weight0, slopes, b, .false., error)
        if (allocated(error)) return
        call check(error, factors%newton%updates == 2, 'two slopes changed: two rank-one updates of M^-1')
        if (allocated(error)) return
        ! 5 active points: the system on the active set (125/3 against 5*49 + 343/3).
        where (slopes(6:) /= 0.0_dp) slopes(6:) = 0.0_dp
        call compare_with_dense('5 active, on the active set', factors, weight0, slopes, b, .true., error)
        if (allocated(error)) return
        ! The same active set, other slopes: factored again, not the kept factors.
        slopes(1:5) = 3*slopes(1:5)
        call compare_with_dense('5 active, new slopes', factors, weight0, slopes, b, .true., error)
        if (allocated(error)) return
        call check(error, maxval(abs(apply_compliance(factors, weight0, b) - matmul(weight0, b))), 0.0_dp, &
                   'U*(V^T*x) against W0*x', thr=1.0e-13_dp*maxval(abs(matmul(weight0, b))))
    end subroutine test_woodbury

    !> The low-rank Newton step against dgesv on the dense I + W0*diag(t), and the path taken.
    subroutine compare_with_dense(case, factors, weight0, slopes, b, on_active_set, error)
        character(len=*), intent(in) :: case
        type(lowrank_compliance), intent(inout) :: factors
        real(dp), intent(in) :: weight0(:, :), slopes(:), b(:)
        logical, intent(in) :: on_active_set
        type(test_error), allocatable, intent(out) :: error

        type(lowrank_compliance) :: dense
        type(error_type), allocatable :: failure
        real(dp) :: by_lowrank(size(b)), by_lu(size(b))

        call newton_solve(factors, weight0, slopes, b, by_lowrank, failure)
        call check(error, .not. allocated(failure), case//': low-rank solve failed')
        if (allocated(error)) return
        call check(error, factors%newton%on_active_set .eqv. on_active_set, case//': not the path expected')
        if (allocated(error)) return
        dense%checked = .true.
        call newton_solve(dense, weight0, slopes, b, by_lu, failure)
        call check(error, .not. allocated(failure), case//': dense solve failed')
        if (allocated(error)) return
        call note(case//': max|s_lowrank - s_lu|/max|s|', maxval(abs(by_lowrank - by_lu))/maxval(abs(by_lu)))
        call check(error, maxval(abs(by_lowrank - by_lu)), 0.0_dp, case//': against dgesv', &
                   thr=1.0e-12_dp*maxval(abs(by_lu)))
    end subroutine compare_with_dense

    subroutine test_factors(error)
        type(test_error), allocatable, intent(out) :: error

        type(modal_green_matrix) :: conv
        type(lowrank_compliance) :: factors
        integer :: n_modes

        conv = exact_matrix(tyre_points(100, 1000.0_dp))
        n_modes = size(conv%shape, 2)
        call factor_compliance(conv%weight0, factors)
        call note('N_m', real(n_modes, dp))
        call note('rank found', real(factors%rank, dp))
        call check(error, factors%low_rank .and. factors%rank >= 1 .and. factors%rank <= n_modes, &
                   'W0 of the tyre: rank at most N_m')
        if (allocated(error)) return
        call note('max|W0 - U V^T|/max|W0|', maxval(abs(conv%weight0 - matmul(factors%left, &
                  transpose(factors%right))))/maxval(abs(conv%weight0)))
        call check(error, maxval(abs(conv%weight0 - matmul(factors%left, transpose(factors%right)))), 0.0_dp, &
                   'U V^T against W0', thr=1.0e-13_dp*maxval(abs(conv%weight0)))
    end subroutine test_factors

    !> The exact engine, Hertz laws (2 mm static compression) and a rough road under the points
    !> of `description` for n_t steps: points lose and regain contact.
    !> `exponent`: p of the laws (1.5 when absent), the static compression kept.
    subroutine set_up_run(description, n_t, conv, laws, preloads, road, exponent)
        type(point_modes), intent(in) :: description
        integer, intent(in) :: n_t
        type(modal_green_matrix), intent(out) :: conv
        type(power_law), allocatable, intent(out) :: laws(:)
        real(dp), allocatable, intent(out) :: preloads(:), road(:, :)
        real(dp), intent(in), optional :: exponent

        type(random_road) :: profile
        real(dp) :: positions(description%n_points()), p
        integer :: n_c, i, m

        n_c = description%n_points()
        positions = contact_positions(0.5_dp, 0.12_dp, n_c)
        profile = new_random_road(35, 10, 1.0e-3_dp, 0.05_dp, 20.0_dp)
        allocate (road(0:n_t - 1, n_c), preloads(n_c), laws(n_c))
        do i = 1, n_c
            road(:, i) = profile%height([(m*dt + positions(i)/20.0_dp, m=0, n_t - 1)])
        end do
        preloads(:) = 3000.0_dp/n_c
        p = 1.5_dp
        if (present(exponent)) p = exponent
        laws(:) = power_law(preloads(1)/(2.0e-3_dp)**p, p)
        conv = exact_matrix(description)
    end subroutine set_up_run

    !> The same run twice, the factors used and the dense W0 forced.
    subroutine run_twice(description, n_t, low_rank, dense, used)
        type(point_modes), intent(in) :: description
        integer, intent(in) :: n_t
        type(multi_contact_response), intent(out) :: low_rank, dense
        type(lowrank_compliance), intent(out) :: used

        type(lowrank_compliance) :: unused

        call implicit_run(description, n_t, low_rank, used)
        call implicit_run(description, n_t, dense, unused, forced_dense=.true.)
    end subroutine run_twice

    !> One implicit run of `description` over n_t steps (`set_up_run`), with the factors it
    !> used; `forced_dense`: W0 kept dense whatever its rank.
    !> `dense_factors`: W0's factors by eliminating the dense W0 even where the convolver
    !> offers its separable modes.
    !> `tolerance`: the Newton tolerance (the default's when absent).
    subroutine implicit_run(description, n_t, response, used, forced_dense, exponent, dense_factors, tolerance)
        type(point_modes), intent(in) :: description
        integer, intent(in) :: n_t
        type(multi_contact_response), intent(out) :: response
        type(lowrank_compliance), intent(out) :: used
        logical, intent(in), optional :: forced_dense
        real(dp), intent(in), optional :: exponent
        logical, intent(in), optional :: dense_factors
        real(dp), intent(in), optional :: tolerance

        type(modal_green_matrix) :: conv
        type(multi_contact_state) :: state
        type(error_type), allocatable :: failure
        type(power_law), allocatable :: laws(:)
        real(dp), allocatable :: road(:, :), preloads(:)

        type(newton_options) :: options

        if (present(tolerance)) options%tolerance = tolerance
        call set_up_run(description, n_t, conv, laws, preloads, road, exponent)
        call start_multi_contact(conv, laws, preloads, state, failure, options)
        if (present(forced_dense)) state%compliance%checked = forced_dense
        if (present(dense_factors)) then
            if (dense_factors) call factor_compliance(conv%weight0, state%compliance)
        end if
        if (.not. allocated(failure)) call multi_contact_block(conv, state, road, response, failure)
        if (allocated(failure)) error stop 'test_lowrank_mod: '//failure%message
        used = state%compliance
    end subroutine implicit_run

    subroutine test_run(error)
        type(test_error), allocatable, intent(out) :: error

        type(multi_contact_response) :: low_rank, dense
        type(lowrank_compliance) :: used
        type(point_modes) :: description

        description = tyre_points(120, 2000.0_dp)
        call run_twice(description, 400, low_rank, dense, used)
        call note('N_m', real(size(description%shape, 2), dp))
        call note('rank used', real(used%rank, dp))
        call check(error, used%low_rank .and. used%rank >= 1 .and. used%rank <= size(description%shape, 2), &
                   'the run used the factors, of rank at most N_m')
        if (allocated(error)) return
        call check(error, any(dense%force <= 0.0_dp) .and. any(dense%force > 0.0_dp), &
                   'some points lose contact, others keep it')
        if (allocated(error)) return
        call check_against_dense('low rank', low_rank, dense, error)
    end subroutine test_run

    !> Forces and displacements of a run against the same run kept dense, within 1e-10 of
    !> their peaks (the Newton tolerance being 1e-12 of the compression scale).
    subroutine check_against_dense(case, run, dense, error)
        character(len=*), intent(in) :: case
        type(multi_contact_response), intent(in) :: run, dense
        type(test_error), allocatable, intent(out) :: error

        real(dp) :: peak

        peak = maxval(abs(dense%force))
        call note('max|F_'//case//' - F_dense|/max F', maxval(abs(run%force - dense%force))/peak)
        call check(error, maxval(abs(run%force - dense%force)), 0.0_dp, 'forces: '//case//' against dense', &
                   thr=1.0e-10_dp*peak)
        if (allocated(error)) return
        call check(error, maxval(abs(run%displacement - dense%displacement)), 0.0_dp, &
                   'displacements: '//case//' against dense', thr=1.0e-10_dp*maxval(abs(dense%displacement)))
    end subroutine check_against_dense

    !> Linear springs: the active set changes from step to step while the slopes on it stay,
    !> so the run goes through the updates of M^-1; against the same run kept dense.
    subroutine test_run_updated(error)
        type(test_error), allocatable, intent(out) :: error

        type(multi_contact_response) :: low_rank, dense
        type(lowrank_compliance) :: used, unused
        type(point_modes) :: description
        integer :: changes, n

        description = tyre_points(200, 2000.0_dp)
        call implicit_run(description, 400, low_rank, used, exponent=1.0_dp)
        call implicit_run(description, 400, dense, unused, forced_dense=.true., exponent=1.0_dp)
        changes = 0
        do n = 1, ubound(dense%force, 1)
            if (any((dense%force(n, :) > 0.0_dp) .neqv. (dense%force(n - 1, :) > 0.0_dp))) changes = changes + 1
        end do
        call note('rank used', real(used%rank, dp))
        call note('steps whose active set changed', real(changes, dp))
        call check(error, used%low_rank .and. .not. used%newton%on_active_set .and. changes >= 10, &
                   'the run used Woodbury''s M over active sets that change')
        if (allocated(error)) return
        call check_against_dense('updated M^-1', low_rank, dense, error)
    end subroutine test_run_updated

    subroutine test_dense_fallback(error)
        type(test_error), allocatable, intent(out) :: error

        type(multi_contact_response) :: low_rank, dense
        type(lowrank_compliance) :: used
        type(point_modes) :: description

        description = tyre_points(20, 2000.0_dp)
        call run_twice(description, 200, low_rank, dense, used)
        call check(error, used%checked .and. .not. used%low_rank, 'N_m >= N_c/2: dense')
        if (allocated(error)) return
        call check(error, all(low_rank%force == dense%force) .and. all(low_rank%displacement == dense%displacement), &
                   'dense: bit for bit the same run')
    end subroutine test_dense_fallback

    !> Step the modal matrix of `description` over n_t random loads; every history [m] kept.
    subroutine step_modal(description, n_t, in_region, histories)
        type(point_modes), intent(in) :: description
        integer, intent(in) :: n_t
        logical, intent(in) :: in_region
        real(dp), intent(out) :: histories(:, :)

        type(modal_green_matrix) :: conv
        type(random_stream) :: stream
        real(dp) :: load(description%n_points())
        integer :: n, i

        conv = exact_matrix(description)
        stream = random_stream(7)
        do n = 1, n_t
            do i = 1, size(load)
                load(i) = stream%uniform() - 0.5_dp
            end do
            if (in_region) then
                !$omp parallel num_threads(2) default(shared)
                !$omp single
                call conv%push(load)
                call conv%history(histories(:, n))
                !$omp end single
                !$omp end parallel
            else
                call conv%push(load)
                call conv%history(histories(:, n))
            end if
        end do
    end subroutine step_modal

    subroutine test_threads(error)
        type(test_error), allocatable, intent(out) :: error

        integer, parameter :: n_t = 20
        type(point_modes) :: description
        type(modal_green_matrix) :: conv
        type(random_stream) :: stream
        real(dp), allocatable :: one(:, :), two(:, :), hosted(:, :), by_loops(:, :)
        real(dp) :: load(1000), modal(2000), re_before, modal_re(2000), modal_im(2000)
        integer :: n, i, k, threads

        description = tyre_points(1000, 3000.0_dp)
        associate (n_c => description%n_points(), n_m => size(description%shape, 2))
            call note('N_c*N_m', real(n_c*n_m, dp))
            call check(error, n_c*n_m >= 20000 .and. n_m <= size(modal), 'the step is large enough for threads')
            if (allocated(error)) return
            allocate (one(n_c, n_t), two(n_c, n_t), hosted(n_c, n_t), by_loops(n_c, n_t))
            threads = 1
            !$ threads = omp_get_max_threads()
            !$ call omp_set_num_threads(1)
            call step_modal(description, n_t, .false., one)
            !$ call omp_set_num_threads(2)
            call step_modal(description, n_t, .false., two)
            call step_modal(description, n_t, .true., hosted)
            !$ call omp_set_num_threads(threads)
            ! The same recursion by plain loops, in the serial order of every sum.
            conv = exact_matrix(description)
            stream = random_stream(7)
            modal_re(:) = 0.0_dp
            modal_im(:) = 0.0_dp
            do n = 1, n_t
                do i = 1, n_c
                    load(i) = stream%uniform() - 0.5_dp
                end do
                if (n == 1) load(1:n_c) = 0.5_dp*load(1:n_c)
                do k = 1, n_m
                    modal(k) = dot_product(description%shape(:, k), load(1:n_c))
                    associate (e => conv%engine)
                        re_before = modal_re(k)
                        modal_re(k) = e%decay_re(k)*re_before - e%decay_im(k)*modal_im(k) + e%input_re(k)*modal(k)
                        modal_im(k) = e%decay_re(k)*modal_im(k) + e%decay_im(k)*re_before + e%input_im(k)*modal(k)
                    end associate
                end do
                do i = 1, n_c
                    by_loops(i, n) = 0.0_dp
                    do k = 1, n_m
                        by_loops(i, n) = by_loops(i, n) + description%shape(i, k)*modal_re(k)
                    end do
                end do
            end do
        end associate
        call note('max|u_1 - u_loops| [m]', maxval(abs(one - by_loops)))
        call note('max|u_2 - u_1| [m]', maxval(abs(two - one)))
        call note('max|u_hosted - u_1| [m]', maxval(abs(hosted - one)))
        call check(error, all(one == by_loops), '1 thread against the plain loops: bit for bit')
        if (allocated(error)) return
        call check(error, all(two == one), '2 threads against 1: bit for bit')
        if (allocated(error)) return
        call check(error, all(hosted == one), 'inside a host''s parallel region against 1 thread: bit for bit')
    end subroutine test_threads

    subroutine test_implicit_threads(error)
        type(test_error), allocatable, intent(out) :: error

        integer, parameter :: n_t = 40
        type(point_modes) :: description
        type(error_type), allocatable :: failure
        type(multi_contact_response) :: one, two, hosted(2)
        type(lowrank_compliance) :: used, used_hosted(2)
        real(dp) :: x(500), y(500)
        integer :: threads, host

        call patch_points([0.6_dp, 0.08_dp], [0.15_dp, 0.16_dp], 25, 20, x, y)
        call plate_modes(tyre_plate(damping_ratio=0.05_dp), x, y, 3000.0_dp, description, failure)
        if (allocated(failure)) error stop 'test_lowrank_mod: '//failure%message
        threads = 1
        !$ threads = omp_get_max_threads()
        !$ call omp_set_num_threads(1)
        call implicit_run(description, n_t, one, used)
        !$ call omp_set_num_threads(2)
        call implicit_run(description, n_t, two, used)
        ! Two host threads, each with its own run (the library's steps and LAPACK serial there).
        !$omp parallel do num_threads(2) default(shared) schedule(static, 1)
        do host = 1, 2
            call implicit_run(description, n_t, hosted(host), used_hosted(host))
        end do
        !$omp end parallel do
        !$ call omp_set_num_threads(threads)
        call note('N_m', real(size(description%shape, 2), dp))
        call note('rank used', real(used%rank, dp))
        call note('N_c*r', real(description%n_points()*used%rank, dp))
        call check(error, used%low_rank .and. description%n_points()*used%rank >= 20000 .and. used%rank > 100, &
                   'the run used the factors, with N_c*r large enough for threads and r > 100')
        if (allocated(error)) return
        call check(error, any(one%force <= 0.0_dp) .and. any(one%force > 0.0_dp), &
                   'some points lose contact, others keep it')
        if (allocated(error)) return
        call note('max|F_2 - F_1| [N]', maxval(abs(two%force - one%force)))
        call check(error, all(two%force == one%force) .and. all(two%displacement == one%displacement), &
                   '2 threads against 1: bit for bit')
        if (allocated(error)) return
        do host = 1, 2
            call note('max|F_host - F_1| [N]', maxval(abs(hosted(host)%force - one%force)))
            call check(error, all(hosted(host)%force == one%force) .and. &
                       all(hosted(host)%displacement == one%displacement), &
                       'a run on a host thread against 1 thread: bit for bit')
            if (allocated(error)) return
        end do
    end subroutine test_implicit_threads

    !> The plate patch of `test_implicit_threads` (25 x 20 points, 441 modes to 3 kHz, Hertz
    !> points losing and regaining contact): the factors made in the modes' span (U = Phi*A,
    !> V = Phi*B, no dense elimination) against W0 and Phi*A, and the run against the same run
    !> with the factors of the dense elimination and with dgesv on the dense W0. Bounds: U*V^T
    !> within 1e-13 of max|W0| (the elimination stops at 1e-14), U within 1e-13 of max|U| of
    !> Phi*A (a sum of N_m products); forces within 1e-10 of the peak force, the Newton
    !> tolerance being 1e-12 of the compression scale, and the same points in contact at
    !> every step.
    subroutine test_modal_span(error)
        type(test_error), allocatable, intent(out) :: error

        integer, parameter :: n_t = 200
        type(point_modes) :: description
        type(error_type), allocatable :: failure
        type(multi_contact_response) :: modal, factors, dense
        type(lowrank_compliance) :: used, used_dense, unused
        type(modal_green_matrix) :: conv
        real(dp) :: x(500), y(500), peak, scale
        real(dp), allocatable :: psi(:, :)

        call patch_points([0.6_dp, 0.08_dp], [0.15_dp, 0.16_dp], 25, 20, x, y)
        call plate_modes(tyre_plate(damping_ratio=0.05_dp), x, y, 3000.0_dp, description, failure)
        if (allocated(failure)) error stop 'test_lowrank_mod: '//failure%message
        call implicit_run(description, n_t, modal, used)
        call implicit_run(description, n_t, factors, used_dense, dense_factors=.true.)
        call implicit_run(description, n_t, dense, unused, forced_dense=.true.)
        call note('N_m', real(size(description%shape, 2), dp))
        call note('rank in the modes'' span', real(used%rank, dp))
        call note('rank of the dense elimination', real(used_dense%rank, dp))
        call note('min points in contact', real(minval(count(modal%force > 0.0_dp, dim=2)), dp))
        call note('max points in contact', real(maxval(count(modal%force > 0.0_dp, dim=2)), dp))
        call note('Newton iterations', real(sum(modal%iterations), dp))
        call check(error, used%low_rank .and. allocated(used%shapes) .and. .not. allocated(used_dense%shapes) &
                   .and. used%rank >= 1 .and. used%rank <= size(description%shape, 2) &
                   .and. .not. used%newton%on_active_set, &
                   'the run used factors in the modes'' span, of rank at most N_m, and Woodbury''s M')
        if (allocated(error)) return
        conv = exact_matrix(description)
        associate (w0 => conv%weight0, u => used%left, v => used%right)
            call note('max|W0 - U V^T|/max|W0|', maxval(abs(w0 - matmul(u, transpose(v))))/maxval(abs(w0)))
            call check(error, maxval(abs(w0 - matmul(u, transpose(v)))), 0.0_dp, 'U V^T against W0', &
                       thr=1.0e-13_dp*maxval(abs(w0)))
            if (allocated(error)) return
            psi = basis_matrix(used)
            call note('basis columns S', real(size(psi, 2), dp))
            call check(error, allocated(used%along_q) .and. size(psi, 2) < size(description%shape, 2), &
                       'the compressed basis has fewer columns than the modes')
            if (allocated(error)) return
            call note('max|Q_x^T Q_x - I|', orthonormality(used%along_q))
            call note('max|Q_y^T Q_y - I|', orthonormality(used%across_q))
            call check(error, max(orthonormality(used%along_q), orthonormality(used%across_q)), 0.0_dp, &
                       'the basis factors are orthonormal', thr=1.0e-13_dp)
            if (allocated(error)) return
            scale = maxval(matmul(abs(psi), abs(used%modal_left)))
            call note('max|U - Psi A|/max(|Psi| |A|)', maxval(abs(u - matmul(psi, used%modal_left)))/scale)
            call check(error, maxval(abs(u - matmul(psi, used%modal_left))), 0.0_dp, &
                       'U against Psi*A', thr=1.0e-13_dp*scale)
            if (allocated(error)) return
            scale = maxval(matmul(abs(psi), abs(transpose(used%modal_right_t))))
            call note('max|V - Psi B|/max(|Psi| |B|)', &
                      maxval(abs(v - matmul(psi, transpose(used%modal_right_t))))/scale)
            call check(error, maxval(abs(v - matmul(psi, transpose(used%modal_right_t)))), 0.0_dp, &
                       'V against Psi*B', thr=1.0e-13_dp*scale)
            if (allocated(error)) return
        end associate
        call check(error, any(dense%force <= 0.0_dp) .and. any(dense%force > 0.0_dp), &
                   'some points lose contact, others keep it')
        if (allocated(error)) return
        call check(error, all((modal%force > 0.0_dp) .eqv. (dense%force > 0.0_dp)) .and. &
                   all((modal%force > 0.0_dp) .eqv. (factors%force > 0.0_dp)), &
                   'the same points in contact at every step')
        if (allocated(error)) return
        peak = maxval(abs(dense%force))
        call note('max|F_span - F_dense factors|/max F', maxval(abs(modal%force - factors%force))/peak)
        call check(error, maxval(abs(modal%force - factors%force)), 0.0_dp, &
                   'forces: modes'' span against the dense factors', thr=1.0e-10_dp*peak)
        if (allocated(error)) return
        call check_against_dense('modes'' span', modal, dense, error)
    end subroutine test_modal_span

    !> Where the factors cannot be made in the modes' span, `factor_modal_compliance` says so and
    !> sets nothing (the step then eliminates the dense W0): one w_k < 0 (W0 indefinite), a
    !> patch of 20 x 10 points under 441 modes (W0's numerical rank is not below N_c/2, as the
    !> dense elimination finds too), and the explicit scheme offers no modes (W0 = 0).
    subroutine test_modal_span_refused(error)
        type(test_error), allocatable, intent(out) :: error

        type(point_modes) :: description
        type(error_type), allocatable :: failure
        type(modal_green_matrix) :: conv
        type(lowrank_compliance) :: factors, dense
        real(dp) :: x(500), y(500)
        real(dp), allocatable :: weight(:)
        logical :: done

        call patch_points([0.6_dp, 0.08_dp], [0.15_dp, 0.16_dp], 25, 20, x, y)
        call plate_modes(tyre_plate(damping_ratio=0.05_dp), x, y, 3000.0_dp, description, failure)
        if (allocated(failure)) error stop 'test_lowrank_mod: '//failure%message
        conv = exact_matrix(description)
        call check(error, allocated(conv%separable), 'the 25 x 20 patch''s convolver holds separable shapes')
        if (allocated(error)) return
        weight = conv%engine%mode_weight
        call factor_modal_compliance(conv%separable, weight, factors, done)
        call check(error, done .and. factors%rank > 0, 'w >= 0: factored in the span')
        if (allocated(error)) return
        weight(size(weight)/2) = -weight(size(weight)/2)
        call factor_modal_compliance(conv%separable, weight, factors, done)
        call check(error, .not. done .and. .not. factors%checked .and. .not. allocated(factors%shapes), &
                   'one w_k < 0: refused, nothing set')
        if (allocated(error)) return
        call patch_points([0.6_dp, 0.08_dp], [0.15_dp, 0.16_dp], 20, 10, x(1:200), y(1:200))
        call plate_modes(tyre_plate(damping_ratio=0.05_dp), x(1:200), y(1:200), 3000.0_dp, description, failure)
        if (allocated(failure)) error stop 'test_lowrank_mod: '//failure%message
        conv = exact_matrix(description)
        call check(error, allocated(conv%separable), 'the 20 x 10 patch''s convolver holds separable shapes')
        if (allocated(error)) return
        call factor_modal_compliance(conv%separable, conv%engine%mode_weight, factors, done)
        call factor_compliance(conv%weight0, dense)
        call note('20 x 10: rank of the dense elimination (0: dense)', real(dense%rank, dp))
        call check(error, .not. done .and. .not. dense%low_rank, 'rank not below N_c/2: refused, as densely')
        if (allocated(error)) return
        call new_modal_green_matrix(description, dt, 'modal', conv, failure)
        if (allocated(failure)) error stop 'test_lowrank_mod: '//failure%message
        call conv%instant_modes(factors%shapes, weight, done)
        call check(error, .not. done, 'the explicit scheme (W0 = 0) offers no modes')
    end subroutine test_modal_span_refused

    !> Linear springs on the plate patch of `test_modal_span` (25 x 20 points, 441 modes): the
    !> active set changes by several points in some steps, so M^-1 follows it by several
    !> rank-one updates a step, and the push reuses the modal loads of the step's last product W0*x. Against
    !> the same run with dgesv on the dense W0: the same points in contact at every step and
    !> forces within 1e-10 of the peak force. A Hertz run (p = 1.5) whose Newton iteration stops
    !> early (tolerance 1e-3) must miss that bound against the same run at the default tolerance.
    subroutine test_rank_k_updates(error)
        type(test_error), allocatable, intent(out) :: error

        integer, parameter :: n_t = 200
        type(point_modes) :: description
        type(error_type), allocatable :: failure
        type(multi_contact_response) :: modal, dense, hertz, early
        type(lowrank_compliance) :: used, unused
        real(dp) :: x(500), y(500), peak
        integer :: n, several

        call patch_points([0.6_dp, 0.08_dp], [0.15_dp, 0.16_dp], 25, 20, x, y)
        call plate_modes(tyre_plate(damping_ratio=0.05_dp), x, y, 3000.0_dp, description, failure)
        if (allocated(failure)) error stop 'test_lowrank_mod: '//failure%message
        call implicit_run(description, n_t, modal, used, exponent=1.0_dp)
        call implicit_run(description, n_t, dense, unused, forced_dense=.true., exponent=1.0_dp)
        call implicit_run(description, n_t, hertz, unused)
        call implicit_run(description, n_t, early, unused, tolerance=1.0e-3_dp)
        several = 0
        do n = 1, n_t - 1
            if (count((dense%force(n, :) > 0.0_dp) .neqv. (dense%force(n - 1, :) > 0.0_dp)) >= 2) &
                several = several + 1
        end do
        peak = maxval(abs(dense%force))
        call note('rank used', real(used%rank, dp))
        call note('steps where two or more points lift off or land', real(several, dp))
        call note('min points in contact', real(minval(count(dense%force > 0.0_dp, dim=2)), dp))
        call note('max|F - F_dgesv|/max F', maxval(abs(modal%force - dense%force))/peak)
        call note('Hertz, tolerance 1e-3 against 1e-12: max|F_early - F|/max F', &
                  maxval(abs(early%force - hertz%force))/maxval(abs(hertz%force)))
        call check(error, used%low_rank .and. allocated(used%shapes) .and. .not. used%newton%on_active_set &
                   .and. several >= 5, 'the run used Woodbury''s M in the modes'' span over several points changing')
        if (allocated(error)) return
        call check(error, any(dense%force <= 0.0_dp) .and. any(dense%force > 0.0_dp), &
                   'some points lose contact, others keep it')
        if (allocated(error)) return
        call check(error, all((modal%force > 0.0_dp) .eqv. (dense%force > 0.0_dp)), &
                   'the same points in contact at every step')
        if (allocated(error)) return
        call check(error, maxval(abs(modal%force - dense%force)), 0.0_dp, 'forces against dgesv', &
                   thr=1.0e-10_dp*peak)
        if (allocated(error)) return
        call check(error, maxval(abs(early%force - hertz%force)) > 1.0e-10_dp*maxval(abs(hertz%force)), &
                   'an iteration stopped early misses the bound')
        if (allocated(error)) return
        call check_kept_inverse(used, error)
    end subroutine test_rank_k_updates

    !> More rank-one updates than points: the kept M^-1 checked and kept (`inverse_accurate`), and
    !> still the inverse of M at the end; the forces against the dense elimination's factors.
    subroutine test_inverse_kept(error)
        type(test_error), allocatable, intent(out) :: error

        integer, parameter :: n_t = 1200
        type(point_modes) :: description
        type(error_type), allocatable :: failure
        type(multi_contact_response) :: modal, factors
        type(lowrank_compliance) :: used, used_dense
        real(dp) :: x(500), y(500), peak

        call patch_points([0.6_dp, 0.08_dp], [0.15_dp, 0.16_dp], 25, 20, x, y)
        call plate_modes(tyre_plate(damping_ratio=0.05_dp), x, y, 3000.0_dp, description, failure)
        if (allocated(failure)) error stop 'test_lowrank_mod: '//failure%message
        call implicit_run(description, n_t, modal, used, exponent=1.0_dp)
        call implicit_run(description, n_t, factors, used_dense, exponent=1.0_dp, dense_factors=.true.)
        call note('checks that kept M^-1', real(used%newton%kept, dp))
        call check(error, used%newton%kept >= 1, 'the kept M^-1 was checked and kept past N_c updates')
        if (allocated(error)) return
        peak = maxval(abs(factors%force))
        call note('max|F - F_dense factors|/max F', maxval(abs(modal%force - factors%force))/peak)
        call check(error, all((modal%force > 0.0_dp) .eqv. (factors%force > 0.0_dp)), &
                   'the same points in contact at every step')
        if (allocated(error)) return
        call check(error, maxval(abs(modal%force - factors%force)), 0.0_dp, 'forces against the dense factors', &
                   thr=1.0e-10_dp*peak)
        if (allocated(error)) return
        call check_kept_inverse(used, error)
    end subroutine test_inverse_kept

    !> The symmetric factors of the modes' span (V = U) and the M^-1 a run left after its
    !> rank-one updates: symmetric to the bit, and the inverse of M = I + U^T*diag(t)*U formed
    !> anew from the kept slopes by plain loops, ||M*M^-1 - I||_max within 1e-10 (the updates'
    !> round-off; a wrong update leaves O(1)).
    subroutine check_kept_inverse(used, error)
        type(lowrank_compliance), intent(in) :: used
        type(test_error), allocatable, intent(out) :: error

        real(dp), allocatable :: m(:, :), product(:, :)
        integer :: k

        call check(error, used%symmetric .and. all(used%right == used%left), 'the factors are symmetric, V = U')
        if (allocated(error)) return
        call check(error, used%newton%ready .and. allocated(used%newton%inverse) .and. used%newton%updates > 0, &
                   'the run left an updated M^-1')
        if (allocated(error)) return
        call check(error, all(used%newton%inverse == transpose(used%newton%inverse)), 'M^-1 symmetric to the bit')
        if (allocated(error)) return
        m = matmul(transpose(used%left), spread(used%newton%slopes, 2, used%rank)*used%left)
        do k = 1, used%rank
            m(k, k) = m(k, k) + 1.0_dp
        end do
        product = matmul(m, used%newton%inverse)
        do k = 1, used%rank
            product(k, k) = product(k, k) - 1.0_dp
        end do
        call note('rank-one updates kept', real(used%newton%updates, dp))
        call note('max|M M^-1 - I| after the updates', maxval(abs(product)))
        call check(error, maxval(abs(product)), 0.0_dp, 'M^-1 after the updates against M formed anew', thr=1.0e-10_dp)
    end subroutine check_kept_inverse

    !> The basis Psi (N_c x S) of factors made in the modes' span, psi_ik = Q_x(col(i), a(k))*
    !> Q_y(row(i), b(k)), formed here entry by entry from the kept separable description.
    function basis_matrix(used) result(psi)
        type(lowrank_compliance), intent(in) :: used
        real(dp), allocatable :: psi(:, :)

        integer :: i, k

        associate (shapes => used%shapes)
            allocate (psi(size(shapes%column), size(shapes%mode_along)))
            do k = 1, size(shapes%mode_along)
                do i = 1, size(shapes%column)
                    psi(i, k) = shapes%along(shapes%column(i), shapes%mode_along(k)) &
                                *shapes%across(shapes%row(i), shapes%mode_across(k))
                end do
            end do
        end associate
    end function basis_matrix

    !> max|Q^T*Q - I| of the columns of q.
    real(dp) function orthonormality(q)
        real(dp), intent(in) :: q(:, :)

        real(dp), allocatable :: gram(:, :)
        integer :: k

        gram = matmul(transpose(q), q)
        do k = 1, size(q, 2)
            gram(k, k) = gram(k, k) - 1.0_dp
        end do
        orthonormality = maxval(abs(gram))
    end function orthonormality

end module test_lowrank_mod
