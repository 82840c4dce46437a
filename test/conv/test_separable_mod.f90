!> The plate's separable mode shapes on a grid of points (greenconv_model_point_modes's
!> `separable_shapes`, set by greenconv_model_plate's `plate_modes`): the factors against the
!> dense shapes, the two products Phi*a and Phi^T*q against MATMUL on the dense shapes, W0 and a
!> modal convolver's steps against the dense path, its product W0*x on the factors against
!> MATMUL on the dense W0, and the shipped tyre_patch scene's contact run on the factors against
!> the same run on the dense shapes (whose implicit step takes W0's low-rank factors).
module test_separable_mod
    use, intrinsic :: iso_fortran_env, only: dp => real64, int64
    use testsuite_mod, only: test_error, unittest_type, new_unittest, check, note
    use scene_text_mod, only: message_of
    use greenconv_core_error, only: error_type
    use greenconv_core_random, only: random_stream
    use greenconv_model_point_modes, only: point_modes, separable_displacements, separable_modal_forces
    use greenconv_model_plate, only: tyre_plate, plate_modes, patch_points
    use greenconv_conv_green_modal, only: modal_green_matrix, new_modal_green_matrix
    use greenconv_conv_multipoint, only: multipoint_convolver
    use greenconv_contact_multi, only: multi_contact_response, run_multi_contact
    use greenconv_contact_laws, only: contact_law, replicate_law
    use greenconv_scene_read_input, only: scene_type, read_scene
    use greenconv_scene_models_registry, only: structure_kind, find_model
    use greenconv_scene_models_point_set, only: scene_points
    use greenconv_scene_run_points, only: points_convolver
    use greenconv_scene_models_patch, only: sample_patch_road
    implicit none
    private

    public :: collect_separable

    !> Relative agreement asked of a product on the factors against the dense one.
    real(dp), parameter :: product_tol = 1.0e-13_dp

contains

    !> Tests of the separable shapes.
    subroutine collect_separable(testsuite)
        type(unittest_type), allocatable, intent(out) :: testsuite(:)

        testsuite = [new_unittest('factors: a 7 x 5 grid in any order, the dense shapes bit for bit; no grid, none', &
                                  test_factors), &
                     new_unittest('products: Phi*a and Phi^T*q on the factors against MATMUL, random values', &
                                  test_products), &
                     new_unittest('modal convolver: W0 and 60 steps on the factors against the dense shapes', &
                                  test_convolver), &
                     new_unittest('instant product: W0*x on the factors against MATMUL(W0, x), random loads', &
                                  test_instant), &
                     new_unittest('tyre_patch, 1,000 points, 200 steps: totals on the factors against dense', &
                                  test_tyre_patch)]
    end subroutine collect_separable

    !> 7 x 5 points over the default plate's patch, modes up to 3 kHz, with the points listed
    !> grid-wise and then shuffled.
    subroutine grid_modes(shuffled, x, y, description, error)
        logical, intent(in) :: shuffled
        real(dp), intent(out) :: x(35), y(35)
        type(point_modes), intent(out) :: description
        type(test_error), allocatable, intent(out) :: error

        type(error_type), allocatable :: fail
        type(random_stream) :: stream
        real(dp) :: swap(2)
        integer :: i, j

        call patch_points([0.9425_dp, 0.1_dp], [0.15_dp, 0.16_dp], 7, 5, x, y)
        if (shuffled) then
            stream = random_stream(17)
            do i = size(x), 2, -1
                j = 1 + int(stream%uniform()*i)
                swap = [x(i), y(i)]
                x(i) = x(j)
                y(i) = y(j)
                x(j) = swap(1)
                y(j) = swap(2)
            end do
        end if
        call plate_modes(tyre_plate(), x, y, 3000.0_dp, description, fail)
        call check(error, .not. allocated(fail), 'plate_modes: '//message_of(fail))
    end subroutine grid_modes

    !> The factors reproduce every phi_ik exactly (the same products as `plate_mode_shape`),
    !> with the points in grid order and shuffled; points that leave a cell empty get none.
    subroutine test_factors(error)
        type(test_error), allocatable, intent(out) :: error

        type(point_modes) :: description
        type(error_type), allocatable :: fail
        real(dp) :: x(35), y(35), worst
        integer :: i, k, order

        do order = 1, 2
            call grid_modes(order == 2, x, y, description, error)
            if (allocated(error)) return
            call check(error, allocated(description%separable), 'a grid of points has factors')
            if (allocated(error)) return
            worst = 0.0_dp
            associate (f => description%separable)
                do k = 1, size(description%shape, 2)
                    do i = 1, size(description%shape, 1)
                        worst = max(worst, abs(description%shape(i, k) - f%along(f%column(i), f%mode_along(k)) &
                                                                       *f%across(f%row(i), f%mode_across(k))))
                    end do
                end do
                if (order == 1) then
                    call note('N_m', real(size(description%shape, 2), dp))
                    call note('x functions', real(size(f%along, 2), dp))
                    call note('y functions', real(size(f%across, 2), dp))
                end if
                call check(error, size(f%along, 1) == 7 .and. size(f%across, 1) == 5, '7 columns and 5 rows')
                if (allocated(error)) return
            end associate
            call check(error, worst == 0.0_dp, 'the factors'' products differ from the dense shapes')
            if (allocated(error)) return
        end do
        ! 34 of the 35 points: one cell empty, no grid
        call plate_modes(tyre_plate(), x(1:34), y(1:34), 3000.0_dp, description, fail)
        call check(error, .not. allocated(fail), 'plate_modes on 34 points: '//message_of(fail))
        if (allocated(error)) return
        call check(error, .not. allocated(description%separable), 'a grid with an empty cell has no factors')
    end subroutine test_factors

    !> u = Phi*a and Q = Phi^T*q on the factors against MATMUL on the dense shapes, random a
    !> and q in [-1, 1], relative to sum |phi|*|a| (resp. |q|) at the worst point (mode);
    !> shared and not shared give the same bits.
    subroutine test_products(error)
        type(test_error), allocatable, intent(out) :: error

        type(point_modes) :: description
        type(random_stream) :: stream
        real(dp) :: x(35), y(35)
        real(dp), allocatable :: a(:), q(:), u(:), u_shared(:), modal(:), modal_shared(:)
        real(dp) :: worst_u, worst_q
        integer :: i, order, trial

        stream = random_stream(2011)
        worst_u = 0.0_dp
        worst_q = 0.0_dp
        do order = 1, 2
            call grid_modes(order == 2, x, y, description, error)
            if (allocated(error)) return
            associate (phi => description%shape, n_c => size(description%shape, 1), n_m => size(description%shape, 2))
                allocate (a(n_m), q(n_c), u(n_c), u_shared(n_c), modal(n_m), modal_shared(n_m))
                do trial = 1, 5
                    a = [(stream%between(-1.0_dp, 1.0_dp), i=1, n_m)]
                    q = [(stream%between(-1.0_dp, 1.0_dp), i=1, n_c)]
                    call separable_displacements(description%separable, a, u, .false.)
                    call separable_displacements(description%separable, a, u_shared, .true.)
                    call separable_modal_forces(description%separable, q, modal, .false.)
                    call separable_modal_forces(description%separable, q, modal_shared, .true.)
                    call check(error, all(u_shared == u) .and. all(modal_shared == modal), &
                               'shared and serial products differ')
                    if (allocated(error)) return
                    worst_u = max(worst_u, maxval(abs(u - matmul(phi, a))/matmul(abs(phi), abs(a))))
                    worst_q = max(worst_q, maxval(abs(modal - matmul(q, phi))/matmul(abs(q), abs(phi))))
                end do
                deallocate (a, q, u, u_shared, modal, modal_shared)
            end associate
        end do
        call note('max rel. |Phi*a - MATMUL|', worst_u)
        call note('max rel. |Phi^T*q - MATMUL|', worst_q)
        call check(error, worst_u <= product_tol .and. worst_q <= product_tol, &
                   'a product on the factors misses the dense one by more than 1e-13')
    end subroutine test_products

    !> The `exact` modal convolver on the factors and on the dense shapes (the same description
    !> less its factors): W0 to 1e-13 of its largest entry, and 60 steps of random forces, the
    !> histories to 1e-13 of their largest value.
    subroutine test_convolver(error)
        type(test_error), allocatable, intent(out) :: error

        type(point_modes) :: description, dense
        type(modal_green_matrix) :: on_factors, on_shapes
        type(error_type), allocatable :: fail
        type(random_stream) :: stream
        real(dp) :: x(35), y(35), u(35), u_dense(35), q(35), w0_diff, history_diff, largest
        integer :: i, n

        call grid_modes(.true., x, y, description, error)
        if (allocated(error)) return
        dense = description
        deallocate (dense%separable)
        call new_modal_green_matrix(description, 2.0e-5_dp, 'exact', on_factors, fail)
        if (.not. allocated(fail)) call new_modal_green_matrix(dense, 2.0e-5_dp, 'exact', on_shapes, fail)
        call check(error, .not. allocated(fail), 'the convolvers: '//message_of(fail))
        if (allocated(error)) return
        call check(error, allocated(on_factors%separable) .and. .not. allocated(on_factors%shape) .and. &
                   allocated(on_shapes%shape) .and. .not. allocated(on_shapes%separable), &
                   'the convolver on the factors holds them and no dense shapes')
        if (allocated(error)) return
        w0_diff = maxval(abs(on_factors%weight0 - on_shapes%weight0))/maxval(abs(on_shapes%weight0))
        stream = random_stream(5)
        history_diff = 0.0_dp
        largest = 0.0_dp
        do n = 1, 60
            call on_factors%history(u)
            call on_shapes%history(u_dense)
            history_diff = max(history_diff, maxval(abs(u - u_dense)))
            largest = max(largest, maxval(abs(u_dense)))
            q = [(stream%between(0.0_dp, 100.0_dp), i=1, 35)]
            call on_factors%push(q)
            call on_shapes%push(q)
        end do
        call note('max|W0 - W0_dense|/max|W0_dense|', w0_diff)
        call note('max|u_h - u_h dense|/max|u_h dense|', history_diff/largest)
        call check(error, w0_diff <= product_tol .and. history_diff <= product_tol*largest .and. largest > 0.0_dp, &
                   'W0 or the histories on the factors miss the dense ones by more than 1e-13')
    end subroutine test_convolver

    !> `apply_instant_kept` of the `exact` convolver on the factors, Phi*(w o Phi^T*x), against
    !> MATMUL(W0, x) on the dense convolver's W0 (made from the dense shapes), random loads in
    !> [-1, 1], relative to sum_j |W0_ij|*|x_j| at the worst point: within 1e-13. Only the
    !> convolver on the factors offers its product as the cheaper one (`fast_instant`); the dense
    !> one's `apply_instant` is MATMUL on its W0, the explicit one's (W0 = 0) product on the
    !> factors zero.
    subroutine test_instant(error)
        type(test_error), allocatable, intent(out) :: error

        type(point_modes) :: description, dense
        type(modal_green_matrix) :: on_factors, on_shapes, explicit
        type(error_type), allocatable :: fail
        type(random_stream) :: stream
        real(dp) :: x(35), y(35), y_dense(35), worst
        integer :: i, trial

        call grid_modes(.true., x, y, description, error)
        if (allocated(error)) return
        dense = description
        deallocate (dense%separable)
        call new_modal_green_matrix(description, 2.0e-5_dp, 'exact', on_factors, fail)
        if (.not. allocated(fail)) call new_modal_green_matrix(dense, 2.0e-5_dp, 'exact', on_shapes, fail)
        if (.not. allocated(fail)) call new_modal_green_matrix(description, 2.0e-5_dp, 'modal', explicit, fail)
        call check(error, .not. allocated(fail), 'the convolvers: '//message_of(fail))
        if (allocated(error)) return
        call check(error, on_factors%fast_instant() .and. .not. on_shapes%fast_instant() .and. &
                   .not. explicit%fast_instant(), 'only the implicit convolver on the factors has the cheaper W0*x')
        if (allocated(error)) return
        stream = random_stream(41)
        worst = 0.0_dp
        do trial = 1, 10
            x = [(stream%between(-1.0_dp, 1.0_dp), i=1, 35)]
            call on_factors%apply_instant_kept(x, y)
            call on_shapes%apply_instant(x, y_dense)
            call check(error, all(y_dense == matmul(on_shapes%weight0, x)), 'the dense product is MATMUL(W0, x)')
            if (allocated(error)) return
            worst = max(worst, maxval(abs(y - y_dense)/matmul(abs(on_shapes%weight0), abs(x))))
        end do
        call explicit%apply_instant_kept(x, y)
        call note('max rel. |W0*x on the factors - MATMUL(W0, x)|', worst)
        call check(error, worst <= product_tol .and. all(y == 0.0_dp), &
                   'W0*x on the factors misses MATMUL(W0, x) by more than 1e-13, or W0*x /= 0 when explicit')
    end subroutine test_instant

    !> data/tyre_patch.nml (50 x 20 points, 441 modes, linear tread) for 200 steps, `exact`
    !> (Newton with W0's low rank) and `modal` (explicit), run as the scene runs them, on the
    !> factors and again on the dense shapes: the total contact forces agree to 1e-12 of their
    !> peak, the Newton solver's tolerance on the compressions (1e-12 of their scale) carried
    !> to forces by the linear law, and the points in contact are the same at every step. The
    !> implicit step's products W0*x are made on the separable factors in the first run and by
    !> W0's low-rank factors U*V^T in the second: two ways to round-off.
    subroutine test_tyre_patch(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=*), parameter :: methods(2) = [character(len=5) :: 'exact', 'modal']
        type(scene_type) :: scene
        type(structure_kind) :: model
        type(scene_points) :: points
        type(error_type), allocatable :: fail
        character(len=:), allocatable :: summary
        real(dp), allocatable :: heights(:, :), on_factors(:), on_shapes(:)
        logical, allocatable :: touching(:, :), touching_dense(:, :)
        real(dp) :: difference
        integer :: m

        call read_scene('data/tyre_patch.nml', scene, fail)
        if (.not. allocated(fail)) then
            scene%n_steps = 200
            model = find_model(scene%model)
            call model%find_points(scene, points, summary, fail)
        end if
        call check(error, .not. allocated(fail), 'the shipped scene and its points: '//message_of(fail))
        if (allocated(error)) return
        call check(error, allocated(points%modes%separable) .and. points%n_points() == 1000, &
                   'the shipped patch''s 1,000 points come with factors')
        if (allocated(error)) return
        call sample_patch_road(scene, points%road_x, points%road_y, 0_int64, scene%n_steps, heights)
        do m = 1, size(methods)
            if (.not. allocated(points%modes%separable)) call model%find_points(scene, points, summary, fail)
            call check(error, .not. allocated(fail), 'the points again: '//message_of(fail))
            if (allocated(error)) return
            call total_force(points, scene, trim(methods(m)), heights, on_factors, touching, error)
            if (allocated(error)) return
            deallocate (points%modes%separable)
            call total_force(points, scene, trim(methods(m)), heights, on_shapes, touching_dense, error)
            if (allocated(error)) return
            difference = maxval(abs(on_factors - on_shapes))/maxval(abs(on_shapes))
            call note(trim(methods(m))//': steps', real(size(on_shapes), dp))
            call note(trim(methods(m))//': peak total force [N]', maxval(on_shapes))
            call note(trim(methods(m))//': max|F_factors - F_dense|/peak', difference)
            call note(trim(methods(m))//': point-steps in contact', real(count(touching_dense), dp))
            call check(error, difference <= 1.0e-12_dp .and. maxval(on_shapes) > 0.0_dp, &
                       trim(methods(m))//': the totals on the factors differ from the dense path''s')
            if (allocated(error)) return
            call check(error, all(touching .eqv. touching_dense), &
                       trim(methods(m))//': the points in contact on the factors differ from the dense path''s')
            if (allocated(error)) return
        end do
    end subroutine test_tyre_patch

    !> The total contact force [N] of each step of a scene's method on its points, as the
    !> runner steps it (preload shared evenly), and which points touch (F_i > 0) at each step.
    subroutine total_force(points, scene, method, heights, total, touching, error)
        type(scene_points), intent(in) :: points
        type(scene_type), intent(in) :: scene
        character(len=*), intent(in) :: method
        real(dp), intent(in) :: heights(:, :)
        real(dp), allocatable, intent(out) :: total(:)
        logical, allocatable, intent(out) :: touching(:, :)
        type(test_error), allocatable, intent(out) :: error

        class(multipoint_convolver), allocatable :: conv
        type(multi_contact_response) :: response
        type(error_type), allocatable :: fail
        character(len=:), allocatable :: accuracy
        class(contact_law), allocatable :: laws(:)
        integer :: i, n_c

        n_c = points%n_points()
        call points_convolver(points, scene, method, conv, accuracy, fail)
        call replicate_law(scene%law, n_c, laws)
        if (.not. allocated(fail)) call run_multi_contact(conv, laws, heights, &
                                                          [(scene%preload/n_c, i=1, n_c)], response, fail)
        call check(error, .not. allocated(fail), method//': the run: '//message_of(fail))
        if (allocated(error)) return
        total = response%total_force
        touching = response%force > 0.0_dp
    end subroutine total_force

end module test_separable_mod
