!> Timing helpers of the benchmark: CPU seconds of a contact run or of bare convolver steps,
!> repeated until the total is long enough for cpu_time to resolve it.
module bench_timing_mod
    use greenconv_core_kinds, only: dp
    use greenconv_conv_convolver, only: convolver
    use greenconv_contact_single, only: contact_law, contact_response, run_contact
    implicit none
    private

    public :: contact_seconds, step_seconds

    !> Shortest total CPU time [s] a measurement is repeated to, unless told otherwise.
    real(dp), parameter :: min_total = 0.25_dp

contains

    !> Mean CPU seconds of one contact run (`run_contact`), and its response.
    function contact_seconds(conv, law, road, preload, response, min_seconds) result(seconds)
        !> The convolution method.
        class(convolver), intent(inout) :: conv
        !> The contact law.
        class(contact_law), intent(in) :: law
        !> Road heights u_r(t_n) [m].
        real(dp), intent(in) :: road(:)
        !> Static preload F0 [N].
        real(dp), intent(in) :: preload
        !> Histories of the (last) run.
        type(contact_response), intent(out) :: response
        !> Shortest total CPU time [s] the run is repeated to (default 0.25 s).
        real(dp), intent(in), optional :: min_seconds
        real(dp) :: seconds

        real(dp) :: start, finish, total
        integer :: runs

        total = min_total
        if (present(min_seconds)) total = min_seconds
        runs = 0
        call cpu_time(start)
        do
            call run_contact(conv, law, road, preload, response)
            runs = runs + 1
            call cpu_time(finish)
            if (finish - start >= total) exit
        end do
        seconds = (finish - start)/runs
    end function contact_seconds

    !> Mean CPU seconds of one bare convolver step (history, then push), over runs of
    !> n_steps steps under the load q = 1 N - (1e-3 N/m)*u_h, which depends on the history so
    !> that no step can be skipped.
    function step_seconds(conv, n_steps) result(seconds)
        !> The convolution method.
        class(convolver), intent(inout) :: conv
        !> Steps per run.
        integer, intent(in) :: n_steps
        real(dp) :: seconds

        real(dp), parameter :: feedback = 1.0e-3_dp
        real(dp) :: start, finish, u
        integer :: runs, n

        runs = 0
        call cpu_time(start)
        do
            call conv%reset()
            do n = 1, n_steps
                u = conv%history()
                call conv%push(1.0_dp - feedback*u)
            end do
            runs = runs + 1
            call cpu_time(finish)
            if (finish - start >= min_total) exit
        end do
        seconds = (finish - start)/(real(runs, dp)*n_steps)
    end function step_seconds

end module bench_timing_mod
