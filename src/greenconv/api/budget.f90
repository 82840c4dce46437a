!> The error budget of a contact run at the C and Fortran 77 doors, single- and multi-point
!> alike, as a scene's runner finds it (doc/methods.md, "The error budget"): the run's box
!> keeps its method's own estimate (the model's terms: E of an identified model, a kernel's
!> truncation and wrap-around), and each contact run adds its time-step and band terms from
!> companions stepped alongside it:
!>
!> - the same run at 2*dt and 4*dt on every second and fourth road height; the time-step term
!>   from the three runs' contact forces by step doubling (greenconv_contact_budget), Richardson
!>   with the order of the method (1 for `backward`, else 2);
!> - for a box on a modes file's modes up to a band, the same run at dt with the modes up to
!>   twice the band: the band's term is the relative difference of the two runs, doubled
!>   unless the wider run holds every mode.
!>
!> A whole run (`start_budget` given its road and forces) feeds its arrays to the companions
!> once; a run stepped one call at a time (`start_budget`, `feed_budget`) feeds each step, so
!> that its terms are known at every step. Before a run has 8 steps the terms are what is known
!> without one (`prior_terms`: the static share of a modes file's modes above the band for a
!> method that leaves it out). Companions cost 1/2 + 1/4 of the run for a modal method (1/4 +
!> 1/16 for `direct`), and the band's a run with the wider band. A companion at 2*dt that cannot
!> be built or fails makes the time-step term 1 (unknown); a run of fewer than 8 steps has none.
!>
!> `outside_accuracy` is the one check of every door against the accuracy the host asked:
!> status 4 (`stat_accuracy`) when the model's estimate plus the run's terms exceed it.
module greenconv_api_budget
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use, intrinsic :: iso_fortran_env, only: int64
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type, fatal_error, stat_accuracy
    use greenconv_core_text, only: sci_text, int_text
    use greenconv_model_point_modes, only: point_modes
    use greenconv_model_modes_file, only: split_band
    use greenconv_ident_structure, only: structure_model
    use greenconv_conv_convolver, only: convolver
    use greenconv_conv_multipoint, only: multipoint_convolver
    use greenconv_conv_point_matrix, only: point_matrix, wrap_point
    use greenconv_conv_builder, only: make_multipoint_convolver, table_convolver, new_convolver
    use greenconv_conv_green_file, only: green_file_convolver
    use greenconv_contact_laws, only: contact_law, replicate_law
    use greenconv_contact_multi, only: multi_contact_response, start_multi_contact, multi_contact_block
    use greenconv_contact_budget, only: doubling_sums, step_doubling_error
    use greenconv_conv_methods, only: method_order
    use greenconv_contact_single, only: contact_options, contact_response, run_contact, copy_histories, &
                                        start_contact
    use greenconv_api_library, only: check_contact_law
    use greenconv_api_handle, only: convolver_box, door_budget, companion_run, release_companions, check_steps
    implicit none
    private

    public :: start_budget, feed_budget, stop_budget
    public :: run_point_budget, start_point_budget
    public :: set_box_accuracy, outside_accuracy

    !> Runs shorter than this have no time-step term (too few steps at 4*dt).
    integer, parameter :: min_budget_steps = 8

contains

    !> A whole single-point contact run on a box (its convolver reset first) and its budget:
    !> the steps done, then zero after a fault, which `error` names (step and time); `error`
    !> (`stat_accuracy`) when the run is whole but outside the accuracy asked.
    subroutine run_point_budget(caller, box, law, preload, road, options, displacement, force, compression, error)
        !> Name of the front-door routine, first word of a message.
        character(len=*), intent(in) :: caller
        !> The box of a single-point structure.
        type(convolver_box), intent(inout) :: box
        !> The contact law.
        class(contact_law), intent(in) :: law
        !> Static preload F0 [N], >= 0.
        real(dp), intent(in) :: preload
        !> Road heights u_r(t_n) [m], one per step.
        real(dp), intent(in) :: road(:)
        !> Scheme, divergence bound and Newton settings.
        type(contact_options), intent(in) :: options
        !> Body displacements u(t_n) [m], contact forces F(t_n) [N] and compressions delta(t_n)
        !> [m]; zero after a fault.
        real(dp), intent(out) :: displacement(:), force(:), compression(:)
        !> Set on bad input (`stat_input`), a fault of the run (`stat_numerical`), or outside the
        !> accuracy asked (`stat_accuracy`).
        type(error_type), allocatable, intent(out) :: error

        class(contact_law), allocatable :: laws(:)
        type(contact_response) :: response

        box%stepping = .false.
        call check_contact_law(law, preload, error)
        if (.not. allocated(error)) then
            call box%conv%reset()
            call check_steps(box, 'a run of '//int_text(size(road))//' steps', int(size(road), int64), error)
        end if
        if (.not. allocated(error)) then
            select type (matrix => box%conv)
            type is (point_matrix)
                call run_contact(matrix%point, law, road, preload, response, options, error)
                matrix%step = matrix%point%step
            end select
        end if
        call copy_histories(response, displacement, force, compression)
        if (allocated(error)) then
            error%message = caller//': '//error%message
            return
        end if
        box%point_options = options
        call replicate_law(law, 1, laws)
        call start_budget(box, laws, [preload], size(road), reshape(road, [size(road), 1]), &
                          reshape(force, [size(force), 1]))
        call outside_accuracy(caller, box, error)
    end subroutine run_point_budget

    !> Start a single-point contact run stepped one call at a time (the N_c = 1 case of
    !> greenconv_api_multi_handle's `advance_multi_box`) and its budget: the options checked
    !> against the convolver, the convolver reset; `error` (`stat_accuracy`) when the run
    !> started but the model is already outside the accuracy asked.
    subroutine start_point_budget(caller, box, law, preload, options, error)
        !> Name of the front-door routine, first word of a message.
        character(len=*), intent(in) :: caller
        !> The box of a single-point structure.
        type(convolver_box), intent(inout) :: box
        !> The contact law (checked by the caller).
        class(contact_law), intent(in) :: law
        !> Static preload F0 [N], >= 0.
        real(dp), intent(in) :: preload
        !> Scheme, divergence bound and Newton settings.
        type(contact_options), intent(in) :: options
        !> Set (`stat_input`) when the options are unusable with this convolver, (`stat_accuracy`)
        !> when outside the accuracy asked.
        type(error_type), allocatable, intent(out) :: error

        class(contact_law), allocatable :: laws(:)

        box%stepping = .false.
        select type (matrix => box%conv)
        type is (point_matrix)
            call start_contact(matrix%point, law, preload, box%contact, error, options)
            matrix%step = matrix%point%step
            box%stepping = .not. allocated(error)
        end select
        if (allocated(error)) return
        box%point_options = options
        call replicate_law(law, 1, laws)
        call start_budget(box, laws, [preload], box%n_steps)
        call outside_accuracy(caller, box, error)
    end subroutine start_point_budget

    !> Build and start the companions of a contact run on a box (module comment); `run_terms`
    !> back to 0. The single-point scheme is `box%point_options` when `box%structure` is held.
    !> Given the `road` and `force` of a whole run already done, the companions are also fed
    !> them and stopped: `run_terms` is then that run's.
    subroutine start_budget(box, laws, preload, n_steps, road, force)
        !> The box, its run starting (or done, with `road` and `force`).
        type(convolver_box), intent(inout) :: box
        !> The contact laws of the run.
        class(contact_law), intent(in) :: laws(:)
        !> Static preloads F0_i [N] of the run.
        real(dp), intent(in) :: preload(:)
        !> Number of steps N_t the run will take at most.
        integer, intent(in) :: n_steps
        !> Road heights road(n, i) [m] of a whole run done, n = 0 to n_steps - 1.
        real(dp), intent(in), optional :: road(0:, :)
        !> The forces force(n, i) [N] of that run.
        real(dp), intent(in), optional :: force(0:, :)

        type(error_type), allocatable :: fault
        type(point_modes) :: description
        real(dp), allocatable :: residual(:, :)
        character(len=:), allocatable :: text
        integer :: f, i

        call stop_budget(box)
        box%run_terms = box%prior_terms
        box%budget = door_budget()
        box%budget%single = allocated(box%structure)
        box%budget%preload = preload
        if (allocated(box%method) .and. n_steps >= min_budget_steps) then
            box%budget%order = method_order(box%method)
            do f = 1, 2
                call companion_convolver(box, 2**f, (n_steps + 2**f - 1)/2**f, box%budget%run(f)%conv, fault)
                if (.not. allocated(fault)) call start_companion(box, box%budget%run(f), laws, preload, fault)
                if (f == 1) box%budget%step_missing = allocated(fault)
                if (allocated(fault)) deallocate (fault)
            end do
            if (allocated(box%source_file)) then
                call split_band(box%source_file, 2.0_dp*box%band, [(i, i=1, size(box%source_file%x))], 0.0_dp, &
                                description, residual, text, fault)
                if (.not. allocated(fault)) call make_multipoint_convolver(box%method, description, box%dt, &
                    box%truncation_tol, n_steps, box%budget%run(3)%conv, text, fault, residual=residual)
                if (.not. allocated(fault)) call start_companion(box, box%budget%run(3), laws, preload, fault)
                box%budget%band_doubled = allocated(residual)
            end if
        end if
        if (present(road) .and. present(force) .and. n_steps >= min_budget_steps) then
            call feed_budget(box, road, force)
            call stop_budget(box)
        end if
    end subroutine start_budget

    !> Feed the companions the next steps of the run (road heights and the run's forces, rows
    !> n = steps fed so far onwards), add their differences and update `box%run_terms`.
    subroutine feed_budget(box, road, force)
        !> The box, its budget started.
        type(convolver_box), intent(inout) :: box
        !> Road heights road(j, i) [m] and the run's forces force(j, i) [N] of these steps.
        real(dp), intent(in) :: road(0:, :), force(0:, :)

        real(dp), allocatable :: coarse(:, :), coarse_2(:, :), coarse_4(:, :), wide(:, :)
        integer :: first(2), f, j, k, n_rows

        n_rows = size(force, 1)
        if (n_rows == 0) return
        associate (budget => box%budget)
            do f = 1, 2
                ! the first row whose step is a multiple of 2^f
                first(f) = int(modulo(-budget%step, int(2**f, int64)))
                call advance_companion(budget%run(f), road(first(f)::2**f, :), coarse)
                if (f == 1) call move_alloc(coarse, coarse_2)
                if (f == 2) call move_alloc(coarse, coarse_4)
            end do
            if (.not. budget%run(1)%running) budget%step_missing = .true.
            if (.not. budget%step_missing) then
                do j = 0, size(coarse_2, 1) - 1
                    budget%sums%fine = budget%sums%fine + sum((force(first(1) + 2*j, :) - budget%preload)**2)
                    budget%sums%fine_2 = budget%sums%fine_2 + sum((force(first(1) + 2*j, :) - coarse_2(j, :))**2)
                end do
                do k = 0, size(coarse_4, 1) - 1
                    ! the row of the run at 2*dt on the same step
                    j = (first(2) - first(1))/2 + 2*k
                    budget%sums%grid_12 = budget%sums%grid_12 + sum((force(first(2) + 4*k, :) - coarse_2(j, :))**2)
                    budget%sums%grid_24 = budget%sums%grid_24 + sum((coarse_2(j, :) - coarse_4(k, :))**2)
                end do
            end if
            if (budget%run(3)%running) then
                call advance_companion(budget%run(3), road, wide)
                if (budget%run(3)%running) then
                    budget%band_difference = budget%band_difference + sum((force - wide)**2)
                    budget%band_reference = budget%band_reference &
                                            + sum((wide - spread(budget%preload, 1, n_rows))**2)
                end if
            end if
            budget%step = budget%step + n_rows
        end associate
        box%run_terms = box%prior_terms
        if (box%budget%step >= min_budget_steps) box%run_terms = budget_terms(box%budget)
    end subroutine feed_budget

    !> Release the companions (their FFTW plans too); the sums and `run_terms` stay.
    subroutine stop_budget(box)
        !> The box.
        type(convolver_box), intent(inout) :: box

        call release_companions(box%budget)
    end subroutine stop_budget

    !> The time-step term plus the band's [-] from a budget's sums (module comment).
    function budget_terms(budget) result(terms)
        type(door_budget), intent(in) :: budget
        real(dp) :: terms

        type(doubling_sums) :: sums
        real(dp) :: step_part, ratio

        terms = 0.0_dp
        if (budget%step < min_budget_steps) return
        sums = budget%sums
        ! a run at 4*dt that failed gives no ratio
        if (.not. budget%run(2)%running) sums%grid_12 = 0.0_dp
        if (budget%step_missing) then
            step_part = 1.0_dp
        else
            call step_doubling_error(sums, budget%order, step_part, ratio)
        end if
        terms = step_part
        if (budget%band_reference > 0.0_dp) terms = terms + merge(2.0_dp, 1.0_dp, budget%band_doubled) &
                                                            *sqrt(budget%band_difference/budget%band_reference)
    end function budget_terms

    !> Start a companion's contact run: the box's single-point scheme on the 1 x 1 case of a
    !> single-point box, the box's Newton settings on a multi-point one.
    subroutine start_companion(box, companion, laws, preload, error)
        type(convolver_box), intent(in) :: box
        type(companion_run), intent(inout) :: companion
        class(contact_law), intent(in) :: laws(:)
        real(dp), intent(in) :: preload(:)
        type(error_type), allocatable, intent(out) :: error

        if (box%budget%single) then
            call start_multi_contact(companion%conv, laws, preload, companion%state, error, &
                                     settings=box%point_options)
        else
            call start_multi_contact(companion%conv, laws, preload, companion%state, error, box%settings)
        end if
        companion%running = .not. allocated(error)
    end subroutine start_companion

    !> Step a companion over `road`'s rows; `force` gets its forces (rows done); a fault stops
    !> it for the rest of the run.
    subroutine advance_companion(companion, road, force)
        type(companion_run), intent(inout) :: companion
        real(dp), intent(in) :: road(0:, :)
        real(dp), allocatable, intent(out) :: force(:, :)

        type(multi_contact_response) :: response
        type(error_type), allocatable :: fault

        allocate (force(0:-1, size(road, 2)))
        if (.not. companion%running .or. size(road, 1) == 0) return
        call multi_contact_block(companion%conv, companion%state, road, response, fault)
        if (allocated(fault)) then
            companion%running = .false.
        else
            call move_alloc(response%force, force)
        end if
    end subroutine advance_companion

    !> The box's method on its source at dt*factor for n_steps: a single-point structure (its g
    !> samples every factor-th), shared modes, samples every factor-th, or its Green's file.
    subroutine companion_convolver(box, factor, n_steps, conv, error)
        type(convolver_box), intent(in) :: box
        integer, intent(in) :: factor, n_steps
        class(multipoint_convolver), allocatable, intent(out) :: conv
        type(error_type), allocatable, intent(out) :: error

        type(structure_model) :: coarse
        class(convolver), allocatable :: point
        character(len=:), allocatable :: text

        if (allocated(box%structure)) then
            coarse = box%structure
            if (allocated(box%structure%sampled_g)) then
                if (size(box%structure%sampled_g) < 2*factor) then
                    call fatal_error(error, 'the samples are too few for a run at '//int_text(factor)//'*dt')
                    return
                end if
                coarse%sampled_g = box%structure%sampled_g(1::factor)
                coarse%sampled_step = box%structure%sampled_step*factor
            end if
            call new_convolver(box%method, coarse, box%dt*factor, n_steps, point, error, box%truncation_tol)
            if (allocated(error)) return
            allocate (point_matrix :: conv)
            select type (matrix => conv)
            type is (point_matrix)
                call wrap_point(point, matrix)
            end select
        else if (allocated(box%source_modes)) then
            call make_multipoint_convolver(box%method, box%source_modes, box%dt*factor, box%truncation_tol, n_steps, &
                                           conv, text, error, residual=box%source_residual)
        else if (allocated(box%source_g)) then
            if (size(box%source_g, 1) < 2*factor) then
                call fatal_error(error, 'the samples are too few for a run at '//int_text(factor)//'*dt')
                return
            end if
            call table_convolver(box%method, box%source_g(0::factor, :, :), box%dt*factor, box%truncation_tol, &
                                 n_steps, conv, text, error)
        else if (allocated(box%green)) then
            call green_file_convolver(box%green, box%method, box%dt*factor, box%truncation_tol, n_steps, conv, text, &
                                      error)
        else
            call fatal_error(error, 'no source kept for a run at another time step')
        end if
    end subroutine companion_convolver

    !> Set the relative accuracy the host asks of a box's runs (0: none); `error` says, with
    !> status 4, when the box's method is already outside it (`outside_accuracy`).
    subroutine set_box_accuracy(caller, box, accuracy, error)
        !> Name of the front-door routine, first word of a message.
        character(len=*), intent(in) :: caller
        !> The box.
        type(convolver_box), intent(inout) :: box
        !> Relative accuracy asked (the largest error estimate accepted), > 0, or 0 for none.
        real(dp), intent(in) :: accuracy
        !> Set (`stat_input`) for an accuracy out of range, (`stat_accuracy`) when outside it.
        type(error_type), allocatable, intent(out) :: error

        if (.not. (accuracy >= 0.0_dp .and. ieee_is_finite(accuracy))) then
            call fatal_error(error, caller//': accuracy = '//sci_text(accuracy)//': give a finite relative ' &
                             //'accuracy > 0, or 0 to ask none')
            return
        end if
        box%accuracy = accuracy
        call outside_accuracy(caller, box, error)
    end subroutine set_box_accuracy

    !> Status 4 (`stat_accuracy`) when the host asked an accuracy and the box's method's own
    !> error estimate plus its run's terms exceed it: the message names them and what to do.
    subroutine outside_accuracy(caller, box, error)
        !> Name of the front-door routine, first word of a message.
        character(len=*), intent(in) :: caller
        !> The box.
        type(convolver_box), intent(in) :: box
        !> Set (`stat_accuracy`) when outside the accuracy asked.
        type(error_type), allocatable, intent(out) :: error

        if (.not. (box%accuracy > 0.0_dp .and. box%estimate + box%run_terms > box%accuracy)) return
        call fatal_error(error, caller//': outside the accuracy asked: the method''s own error estimate ' &
                         //sci_text(box%estimate + box%run_terms)//' > accuracy '//sci_text(box%accuracy) &
                         //' (model '//sci_text(box%estimate)//', time step and band ' &
                         //sci_text(box%run_terms)//'; the results are whole); use a smaller dt, exact on ' &
                         //'identified modes, a model with a smaller E, or ask a larger accuracy', stat_accuracy)
    end subroutine outside_accuracy

end module greenconv_api_budget
