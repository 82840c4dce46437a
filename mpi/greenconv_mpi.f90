!> greenconv-mpi: the driver built with MPI (`make mpi`, through mpif90), for sweep scenes.
!>
!>     mpirun -np N greenconv-mpi [--check] [--quiet] SWEEP.nml
!>
!> Every rank reads the sweep. The variants are then taken one at a time by whichever rank
!> is free: a counter on rank 0 that each rank advances with an atomic MPI_Fetch_and_op
!> (one-sided), so rank 0 works too and a cheap variant never waits for an expensive one.
!> The rank that takes a variant checks it, finds its record when a previous run finished
!> it (then it costs only its key) or runs it and records it at once (greenconv_scene_sweep's
!> `take_variant`, `report_taken`): no serial phase grows with the number of variants. The
!> outcomes are sent to rank 0 at the end, each rank's in one go (a send per variant could
!> wait for rank 0 to finish its own variant: MPI progresses only inside MPI calls); rank 0
!> then prints the count of variants and writes the table in variant order, so the table
!> does not depend on the number of ranks.
!> A scene that is not a sweep runs on rank 0 as the serial driver runs it.
!> Exit status as the serial driver's: 0 done (failed variants are in the table), 2 bad input.
program greenconv_mpi
    use, intrinsic :: iso_fortran_env, only: output_unit, error_unit
    use, intrinsic :: iso_c_binding, only: c_ptr, c_f_pointer
    use mpi_f08, only: MPI_Init, MPI_Finalize, MPI_Comm_rank, MPI_Comm_size, MPI_COMM_WORLD, MPI_Allreduce, &
                       MPI_IN_PLACE, MPI_INTEGER, MPI_CHARACTER, MPI_MAX, MPI_SUM, MPI_Barrier, MPI_Win, &
                       MPI_ADDRESS_KIND, MPI_INFO_NULL, MPI_LOCK_SHARED, MPI_Win_allocate, MPI_Win_lock, &
                       MPI_Fetch_and_op, MPI_Win_unlock, MPI_Win_free, MPI_Send, MPI_Recv, MPI_Probe, MPI_Get_count, &
                       MPI_Status, MPI_ANY_SOURCE
    use greenconv, only: scene_type, read_scene, run_scene, check_scene, error_type
    use greenconv_scene_sweep, only: sweep_plan, scene_files, variant_outcome, is_sweep_file, read_sweep, &
                                     take_variant, report_taken, outcome_text, outcome_from_text, report_check, &
                                     finish_report
    use greenconv_core_text, only: int_text
    implicit none

    character(len=*), parameter :: usage = 'usage: mpirun -np N greenconv-mpi [--check] [--quiet] SWEEP.nml'
    character(len=:), allocatable :: path, argument
    logical :: check_only, quiet
    integer :: i, length, rank, ranks, status, severity

    call MPI_Init()
    call MPI_Comm_rank(MPI_COMM_WORLD, rank)
    call MPI_Comm_size(MPI_COMM_WORLD, ranks)
    check_only = .false.
    quiet = .false.
    path = ''
    status = 0
    do i = 1, command_argument_count()
        call get_command_argument(i, length=length)
        allocate (character(len=length) :: argument)
        call get_command_argument(i, argument)
        select case (argument)
        case ('--check')
            check_only = .true.
        case ('--quiet')
            quiet = .true.
        case default
            if (index(argument, '-') == 1 .or. len(path) > 0) status = 2
            path = argument
        end select
        deallocate (argument)
    end do
    if (len(path) == 0 .or. status /= 0) then
        if (rank == 0) write (error_unit, '(a)') 'greenconv: unexpected or missing argument; '//usage
        status = 2
    else if (is_sweep_file(path)) then
        call run_on_ranks(path, check_only, status)
    else if (rank == 0) then
        call run_alone(path, check_only, quiet, status)
    end if
    ! The worst status over the ranks: a failure (3 numerical, then 2 input) before 4 (ran outside
    ! the accuracy asked) before 0, so the statuses are ranked by severity, not by value.
    severity = severity_of(status)
    call MPI_Allreduce(MPI_IN_PLACE, severity, 1, MPI_INTEGER, MPI_MAX, MPI_COMM_WORLD)
    status = status_of_severity(severity)
    call MPI_Finalize()
    if (status /= 0) stop status, quiet=.true.

contains

    !> The rank of an exit status by severity: 0 success, 1 outside the accuracy (4), 2 bad
    !> input (2), 3 numerical fault (3); any other status counts as a fault.
    pure integer function severity_of(status)
        integer, intent(in) :: status

        select case (status)
        case (0)
            severity_of = 0
        case (4)
            severity_of = 1
        case (2)
            severity_of = 2
        case default
            severity_of = 3
        end select
    end function severity_of

    !> The exit status of a severity from `severity_of`.
    pure integer function status_of_severity(severity)
        integer, intent(in) :: severity

        integer, parameter :: statuses(0:3) = [0, 4, 2, 3]

        status_of_severity = statuses(max(0, min(3, severity)))
    end function status_of_severity

    !> A scene that is not a sweep, on this rank alone.
    subroutine run_alone(path, check_only, quiet, status)
        character(len=*), intent(in) :: path
        logical, intent(in) :: check_only, quiet
        integer, intent(out) :: status

        type(scene_type) :: scene
        type(error_type), allocatable :: error

        status = 0
        call read_scene(path, scene, error)
        if (.not. allocated(error)) then
            if (quiet) scene%progress = .false.
            if (check_only) then
                call check_scene(scene, output_unit, error)
            else
                call run_scene(scene, output_unit, error)
            end if
        end if
        call give_up(error, status)
    end subroutine run_alone

    !> A sweep shared among the ranks.
    subroutine run_on_ranks(path, check_only, status)
        character(len=*), intent(in) :: path
        logical, intent(in) :: check_only
        integer, intent(out) :: status

        type(sweep_plan) :: plan
        type(variant_outcome), allocatable :: outcomes(:)
        type(variant_outcome) :: outcome
        type(scene_files) :: files
        type(error_type), allocatable :: error
        integer :: n, next, k, what, counts(2)
        integer, allocatable :: taken(:), lengths(:)
        character(len=:), allocatable :: texts
        type(MPI_Win) :: window
        type(c_ptr) :: base
        integer, pointer :: counter(:)
        integer(MPI_ADDRESS_KIND) :: bytes

        status = 0
        ! every rank reads the same file and meets the same error: rank 0 says it
        call read_sweep(path, plan, error)
        if (allocated(error)) then
            if (rank /= 0) deallocate (error)
            call give_up(error, status)
            status = 2
            return
        end if
        n = size(plan%values, 1)
        if (rank == 0) allocate (outcomes(n))

        bytes = 0
        if (rank == 0) bytes = storage_size(0)/8
        call MPI_Win_allocate(bytes, storage_size(0)/8, MPI_INFO_NULL, MPI_COMM_WORLD, base, window)
        if (rank == 0) then
            call c_f_pointer(base, counter, [1])
            counter(1) = 0
        end if
        call MPI_Barrier(MPI_COMM_WORLD)
        counts = 0
        allocate (taken(0), lengths(0))
        texts = ''
        do
            call MPI_Win_lock(MPI_LOCK_SHARED, 0, 0, window)
            call MPI_Fetch_and_op(1, next, MPI_INTEGER, 0, 0_MPI_ADDRESS_KIND, MPI_SUM, window)
            call MPI_Win_unlock(0, window)
            if (next >= n) exit
            k = next + 1
            call take_variant(plan, k, check_only, outcome, what, files)
            call report_taken(plan, k, outcome, what, output_unit, counts(1), counts(2), error)
            if (allocated(error)) then
                write (error_unit, '(a)') 'greenconv: '//error%message
                deallocate (error)
            end if
            if (check_only) cycle
            if (rank == 0) then
                outcomes(k) = outcome
            else
                ! kept until the end: a send now could wait for rank 0, busy with a variant
                taken = [taken, k]
                texts = texts//outcome_text(outcome)
                lengths = [lengths, len(outcome_text(outcome))]
            end if
        end do
        call MPI_Win_free(window)
        if (.not. check_only) then
            if (rank == 0) then
                call gather_outcomes(outcomes)
            else
                call send_outcomes(taken, lengths, texts)
            end if
        end if
        call MPI_Allreduce(MPI_IN_PLACE, counts, 2, MPI_INTEGER, MPI_SUM, MPI_COMM_WORLD)
        if (rank /= 0) return
        call report_check(plan, output_unit, counts(1), counts(2), check_only, error)
        if (.not. (check_only .or. allocated(error))) call finish_report(plan, outcomes, output_unit, error)
        call give_up(error, status)
    end subroutine run_on_ranks

    !> Send this rank's outcomes to rank 0 in three messages: their count (tag 1), then the
    !> variants' numbers and the lengths of their texts (tag 2), then the texts one after
    !> another (tag 3).
    subroutine send_outcomes(taken, lengths, texts)
        integer, intent(in) :: taken(:), lengths(:)
        character(len=*), intent(in) :: texts

        call MPI_Send(size(taken), 1, MPI_INTEGER, 0, 1, MPI_COMM_WORLD)
        if (size(taken) == 0) return
        call MPI_Send([taken, lengths], 2*size(taken), MPI_INTEGER, 0, 2, MPI_COMM_WORLD)
        call MPI_Send(texts, len(texts), MPI_CHARACTER, 0, 3, MPI_COMM_WORLD)
    end subroutine send_outcomes

    !> On rank 0: every other rank's outcomes (`send_outcomes`).
    subroutine gather_outcomes(outcomes)
        type(variant_outcome), intent(inout) :: outcomes(:)

        type(MPI_Status) :: state
        character(len=:), allocatable :: texts
        integer, allocatable :: numbers(:)
        integer :: i, m, n, from, at
        logical :: ok

        do i = 1, ranks - 1
            call MPI_Recv(m, 1, MPI_INTEGER, MPI_ANY_SOURCE, 1, MPI_COMM_WORLD, state)
            if (m == 0) cycle
            from = state%MPI_SOURCE
            allocate (numbers(2*m))
            call MPI_Recv(numbers, 2*m, MPI_INTEGER, from, 2, MPI_COMM_WORLD, state)
            call MPI_Probe(from, 3, MPI_COMM_WORLD, state)
            call MPI_Get_count(state, MPI_CHARACTER, n)
            allocate (character(len=n) :: texts)
            call MPI_Recv(texts, n, MPI_CHARACTER, from, 3, MPI_COMM_WORLD, state)
            at = 0
            do n = 1, m
                call outcome_from_text(texts(at + 1:at + numbers(m + n)), outcomes(numbers(n)), ok)
                at = at + numbers(m + n)
            end do
            deallocate (numbers, texts)
        end do
    end subroutine gather_outcomes

    !> Print an error (if any) and set the exit status from it.
    subroutine give_up(error, status)
        type(error_type), allocatable, intent(in) :: error
        integer, intent(inout) :: status

        if (.not. allocated(error)) return
        write (error_unit, '(a)') 'greenconv: '//error%message
        status = error%stat
    end subroutine give_up

end program greenconv_mpi
