!> `direct` against a plain compiled loop of the same sum, on Tab. 2's largest case (the SDOF
!> scene at dt = 0.01 ms over N_t = 200000 steps, N_g from the scene's truncation rule).
!>
!> The loop is what a user would write: every force of the run kept in one array, and at step n
!>
!>     u = 0
!>     do k = 1, min(n, N_g)
!>         u = u + w(k)*q(n - k)
!>     end do
!>
!> compiled in this program, with the same flags as the library. Both are timed bare (history,
!> then push, as `step_seconds`) and in the whole contact run (`contact_seconds`), in rounds
!> that alternate them; each time is the best of the rounds, so that other work on a shared
!> machine lengthens a round and not the ratio.
module bench_direct_mod
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type, fatal_error
    use greenconv_conv_convolver, only: convolver, capped_step, free_convolver
    use greenconv_conv_direct, only: direct_convolver
    use greenconv_contact_single, only: contact_response
    use greenconv_scene_read_input, only: scene_type
    use greenconv_ident_structure, only: structure_model
    use greenconv_scene_run_runner, only: make_convolver
    use bench_timing_mod, only: contact_seconds, step_seconds
    use bench_tables_mod, only: load_scene, verdict
    implicit none
    private

    public :: direct_loop_table, plain_loop, new_plain_loop

    !> The plain loop of eq. (20): all forces of the run in one array, one running sum per step.
    type, extends(convolver) :: plain_loop
        !> Kernel weights w_k = dt*g(t_k) [m/N], k = 1..N_g.
        real(dp), allocatable :: weight(:)
        !> Forces q(t_m) [N] pushed so far, m = 0..step - 1 (grown as the run goes on).
        real(dp), allocatable :: forces(:)
    contains
        procedure :: history => plain_history
        procedure :: push => plain_push
        procedure :: clear => plain_clear
    end type plain_loop

contains

    !> A plain loop with the weights and the instant weight of a `direct` convolver, room for
    !> `n_steps` forces.
    function new_plain_loop(direct, n_steps) result(loop)
        !> The direct convolver whose sum the loop repeats.
        type(direct_convolver), intent(in) :: direct
        !> Steps the run will take (more grow the force array).
        integer, intent(in) :: n_steps
        type(plain_loop) :: loop

        call loop%set_model('loop', direct%dt, size(direct%weight), 'N_g')
        loop%weight0 = direct%weight0
        loop%weight = direct%weight
        allocate (loop%forces(0:max(n_steps, 1) - 1))
        call loop%reset()
    end function new_plain_loop

    !> u_h(n) = sum_{k=1..min(n,N_g)} w_k*q(t_{n-k}) [m], one term after the other.
    function plain_history(self) result(u)
        !> The loop.
        class(plain_loop), intent(in) :: self
        real(dp) :: u

        integer :: k, n

        n = int(self%step)
        u = 0.0_dp
        do k = 1, capped_step(self%step, size(self%weight))
            u = u + self%weight(k)*self%forces(n - k)
        end do
    end function plain_history

    !> Keep the force q(t_n) [N] and advance.
    subroutine plain_push(self, force)
        !> The loop.
        class(plain_loop), intent(inout) :: self
        !> Force of the current step [N].
        real(dp), intent(in) :: force

        real(dp), allocatable :: longer(:)
        integer :: n

        n = int(self%step)
        if (n > ubound(self%forces, 1)) then
            allocate (longer(0:2*size(self%forces) - 1))
            longer(0:n - 1) = self%forces(0:n - 1)
            call move_alloc(longer, self%forces)
        end if
        self%forces(n) = force
        self%step = self%step + 1
    end subroutine plain_push

    !> Forget the forces.
    subroutine plain_clear(self)
        !> The loop.
        class(plain_loop), intent(inout) :: self

        self%forces = 0.0_dp
    end subroutine plain_clear

    !> Print the comparison on `unit`: CPU seconds and MAC rates of `direct` and of the plain
    !> loop, bare and in the contact run, their ratios against the target 3, and how far apart
    !> their displacements are.
    subroutine direct_loop_table(unit, sdof_file, error)
        !> Unit the lines are printed on.
        integer, intent(in) :: unit
        !> The SDOF scene of section 3.1 (data/sdof_sine.nml).
        character(len=*), intent(in) :: sdof_file
        !> Set when the scene cannot be read or the direct convolver built.
        type(error_type), allocatable, intent(out) :: error

        integer, parameter :: n_steps = 200000, rounds = 3
        real(dp), parameter :: dt = 1.0e-5_dp, target = 3.0_dp
        class(convolver), allocatable :: direct
        type(plain_loop) :: loop
        type(contact_response) :: r_direct, r_loop
        character(len=:), allocatable :: accuracy
        real(dp), allocatable :: road(:)
        real(dp) :: s_direct, s_loop, t_direct, t_loop, macs
        type(scene_type) :: scene
        type(structure_model) :: structure
        integer :: round, n_g

        call load_scene(sdof_file, scene, structure, error)
        if (allocated(error)) return
        call make_convolver('direct', structure, dt, scene%truncation_tol, n_steps, direct, accuracy, error)
        if (allocated(error)) return
        select type (direct)
        type is (direct_convolver)
            loop = new_plain_loop(direct, n_steps)
        class default
            call fatal_error(error, 'bench_direct: the direct method did not build a direct convolver')
            return
        end select
        n_g = size(loop%weight)
        allocate (road(n_steps))
        road(:) = scene%road%sample(dt, n_steps)
        s_direct = huge(1.0_dp)
        s_loop = huge(1.0_dp)
        t_direct = huge(1.0_dp)
        t_loop = huge(1.0_dp)
        do round = 1, rounds
            s_direct = min(s_direct, step_seconds(direct, n_steps))
            s_loop = min(s_loop, step_seconds(loop, n_steps))
            t_direct = min(t_direct, contact_seconds(direct, scene%law, road, scene%preload, r_direct))
            t_loop = min(t_loop, contact_seconds(loop, scene%law, road, scene%preload, r_loop))
        end do
        ! Products summed over the run: min(n, N_g) at step n.
        macs = 0.5_dp*n_g*(n_g - 1.0_dp) + real(n_steps - n_g, dp)*n_g
        write (unit, '(a,i0,a,i0,a)') '# direct against a plain compiled loop of the same sum (Tab. 2''s largest case: ' &
            //'dt 0.01 ms, N_t ', n_steps, ', N_g ', n_g, '), best of 3 interleaved rounds:'
        write (unit, '(a,2(f8.3,a,f6.2,a))') '#   convolution alone: direct ', s_direct*n_steps, ' s (', &
            macs/(s_direct*n_steps)*1.0e-9_dp, ' GMAC/s), loop ', s_loop*n_steps, ' s (', &
            macs/(s_loop*n_steps)*1.0e-9_dp, ' GMAC/s)'
        write (unit, '(a,2(f8.3,a))') '#   whole contact run:  direct ', t_direct, ' s, loop ', t_loop, ' s'
        call verdict(unit, 'loop/direct, convolution alone', s_loop/s_direct, target)
        call verdict(unit, 'loop/direct, whole contact run', t_loop/t_direct, target)
        write (unit, '(a,es9.2)') '#   max|u_direct - u_loop|/max|u_loop| over the contact run = ', &
            maxval(abs(r_direct%displacement - r_loop%displacement))/maxval(abs(r_loop%displacement))
        write (unit, '(a)') ''
        call free_convolver(direct)
    end subroutine direct_loop_table

end module bench_direct_mod
