!> A structure's normal modes from the user's finite-element model, read from a universal file
!> (datasets 15 or 2411 for the nodes, one dataset 55 per mode, greenconv_io_uff_dataset55),
!> as the multi-point engines take them (greenconv_model_point_modes):
!>
!>     g_ij(t) = sum_k phi_ik*phi_jk/m_k * exp(-xi_k*omega_k*t)*sin(omega_k^d*t)/omega_k^d,
!>
!> phi_ik the shape of mode k at node i in the direction the scene names, m_k its modal mass
!> (1 where the file gives 0: mass-normalised shapes), omega_k = 2*pi*f_k, xi_k the file's
!> viscous damping ratio or the scene's where the file gives 0.
!>
!> Modes above the band of a run (its Nyquist frequency 1/(2*dt), or the band the scene names)
!> are not stepped: at the run's frequencies, well below theirs, they respond without lag, as
!> a static compliance R_ij = sum_k phi_ik*phi_jk/(m_k*omega_k**2) over those modes (the
!> residual flexibility), returned with its share of the whole static flexibility at the
!> nodes. `split_band` is what a scene (greenconv_scene_models_multi) and the C and F77 doors
!> (greenconv_api_multi_handle) both call: the modes in band, R when any mode lies above, and
!> the one line that reports them; both then give R to greenconv_conv_builder's
!> `make_multipoint_convolver`, which adds it to the instant compliance W0 of the convolver
!> of the modes in band, so the same file makes the same structure through either door.
module greenconv_model_modes_file
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type, fatal_error
    use greenconv_io_uff_types, only: uff_node
    use greenconv_io_uff_dataset55, only: uff_mode_shape, read_modes_file
    use greenconv_model_modal_set, only: modes_from_paper
    use greenconv_model_point_modes, only: point_modes
    implicit none
    private

    public :: file_modes, read_file_modes, band_modes, split_band, band_bytes

    real(dp), parameter :: pi = acos(-1.0_dp)

    !> The modes of a universal file at its nodes.
    type :: file_modes
        !> Node labels, in the order of the file's first dataset 55.
        integer, allocatable :: label(:)
        !> Node coordinates x, y, z [m], as the file gives them.
        real(dp), allocatable :: x(:), y(:), z(:)
        !> Natural frequencies f_k [Hz].
        real(dp), allocatable :: frequency(:)
        !> Modal masses m_k [kg] (1 where the file gives 0).
        real(dp), allocatable :: modal_mass(:)
        !> Viscous damping ratios xi_k (the default where the file gives 0).
        real(dp), allocatable :: damping_ratio(:)
        !> Shapes phi_ik at the nodes in the chosen direction, shape(i, k), as the file gives
        !> them (dimensionless with m_k in kg; 1/sqrt(kg) for mass-normalised shapes).
        real(dp), allocatable :: shape(:, :)
        !> Number of modes whose damping ratio came from the file.
        integer :: n_damped_by_file = 0
    end type file_modes

contains

    !> Read the modes of a universal file: nodes and shapes in `direction`, the default damping
    !> ratio where the file gives none.
    subroutine read_file_modes(path, direction, damping_ratio, modes, error)
        !> The universal file (datasets 15/2411 and 55).
        character(len=*), intent(in) :: path
        !> Direction of the shapes: +-1, +-2, +-3 for +-X, +-Y, +-Z.
        integer, intent(in) :: direction
        !> Damping ratio applied where the file gives 0, 0 <= xi < 1.
        real(dp), intent(in) :: damping_ratio
        !> The modes read.
        type(file_modes), intent(out) :: modes
        !> Set (status 2) for an unreadable or malformed file.
        type(error_type), allocatable, intent(out) :: error

        type(uff_node), allocatable :: nodes(:)
        type(uff_mode_shape), allocatable :: shapes(:)
        integer :: k

        call read_modes_file(path, direction, nodes, shapes, error)
        if (allocated(error)) return
        modes%label = nodes%label
        modes%x = nodes%position(1)
        modes%y = nodes%position(2)
        modes%z = nodes%position(3)
        modes%frequency = shapes%frequency
        modes%modal_mass = merge(shapes%modal_mass, 1.0_dp, shapes%modal_mass > 0.0_dp)
        modes%damping_ratio = merge(shapes%damping_ratio, damping_ratio, shapes%damping_ratio > 0.0_dp)
        modes%n_damped_by_file = count(shapes%damping_ratio > 0.0_dp)
        allocate (modes%shape(size(nodes), size(shapes)))
        do k = 1, size(shapes)
            modes%shape(:, k) = shapes(k)%value
        end do
    end subroutine read_file_modes

    !> The modes up to f_band [Hz] at the nodes `selected`, and the static compliance (residual
    !> flexibility) of the modes above it between those nodes.
    subroutine band_modes(modes, f_band, selected, description, residual, static_share, error)
        !> The file's modes.
        type(file_modes), intent(in) :: modes
        !> Highest frequency stepped [Hz].
        real(dp), intent(in) :: f_band
        !> Nodes kept (indices into the file's nodes).
        integer, intent(in) :: selected(:)
        !> Modes up to f_band and their shapes at the selected nodes.
        type(point_modes), intent(out) :: description
        !> Static compliance R_ij [m/N] of the modes above f_band between the selected nodes
        !> (N_c x N_c; zero when every mode lies in the band).
        real(dp), allocatable, intent(out) :: residual(:, :)
        !> Share of the residual in the whole static flexibility at the nodes: the trace of R
        !> over the trace of all modes' static compliance.
        real(dp), intent(out) :: static_share
        !> Set (status 2) when no mode lies in the band.
        type(error_type), allocatable, intent(out) :: error

        logical :: kept(size(modes%frequency))
        real(dp) :: stiffness(size(modes%frequency)), total, column(size(selected))
        integer :: k, j

        kept = modes%frequency <= f_band
        if (.not. any(kept)) then
            call fatal_error(error, 'modes file: expected a mode at or below the band''s '//trim(hz(f_band)) &
                             //', found the lowest at '//trim(hz(minval(modes%frequency))))
            return
        end if
        stiffness = modes%modal_mass*(2.0_dp*pi*modes%frequency)**2
        description%modes = modes_from_paper(1.0_dp/pack(modes%modal_mass, kept), &
                                             2.0_dp*pi*pack(modes%frequency, kept), pack(modes%damping_ratio, kept))
        allocate (description%shape(size(selected), count(kept)), residual(size(selected), size(selected)))
        residual = 0.0_dp
        total = 0.0_dp
        do k = 1, size(kept)
            column = modes%shape(selected, k)
            total = total + sum(column**2)/stiffness(k)
            if (kept(k)) cycle
            ! R += phi_k*phi_k^T/K_k, a column at a time (no N_c x N_c temporary)
            do j = 1, size(selected)
                residual(:, j) = residual(:, j) + column*(column(j)/stiffness(k))
            end do
        end do
        description%shape = modes%shape(selected, pack([(k, k=1, size(kept))], kept))
        static_share = 0.0_dp
        if (total > 0.0_dp) static_share = sum([(residual(k, k), k=1, size(selected))])/total
    end subroutine band_modes

    !> The modes up to f_band [Hz] at the nodes `selected`, R of those above it (unallocated
    !> when none is above) and the line that reports them, e.g. `9 contact points, 9 modes from
    !> 125.4 Hz up to the band, 1000.0 Hz (23 above it as a static compliance, 3.22 % of the static
    !> flexibility at the points, largest R_ii 1.23E-09 m/N; damping ratio from the file for
    !> 16, 0.030 for 16 modes)`.
    subroutine split_band(modes, f_band, selected, damping_ratio, description, residual, summary, error, &
                          static_share)
        !> The file's modes, as `band_modes` takes them.
        type(file_modes), intent(in) :: modes
        !> The band's top [Hz], as `band_modes` takes it.
        real(dp), intent(in) :: f_band
        !> The contact points: indices into the file's nodes.
        integer, intent(in) :: selected(:)
        !> Damping ratio applied where the file gives none (for the line).
        real(dp), intent(in) :: damping_ratio
        !> The modes stepped (`band_modes`'s description).
        type(point_modes), intent(out) :: description
        !> Static compliance R_ij [m/N] of the modes above f_band (N_c x N_c), unallocated when
        !> every mode lies in the band.
        real(dp), allocatable, intent(out) :: residual(:, :)
        !> The report of the split, without a final comma.
        character(len=:), allocatable, intent(out) :: summary
        !> Set (status 2) when no mode lies in the band.
        type(error_type), allocatable, intent(out) :: error
        !> Share [-] of the static flexibility at the points the modes above f_band carry.
        real(dp), intent(out), optional :: static_share

        real(dp), allocatable :: static(:, :)
        real(dp) :: share, largest
        character(len=320) :: numbers
        character(len=6) :: percent
        integer :: n_above, i

        call band_modes(modes, f_band, selected, description, static, share, error)
        if (allocated(error)) return
        if (present(static_share)) static_share = share
        n_above = size(modes%frequency) - description%modes%n_modes()
        largest = maxval([(static(i, i), i=1, size(selected))])
        if (n_above > 0) call move_alloc(static, residual)
        write (percent, '(f6.2)') 100.0_dp*share
        write (numbers, '(i0,a,i0,a,f0.1,a,f0.1,a,i0,a,a,a,es8.2,a,i0,a,f5.3,a,i0,a)') size(selected), &
            ' contact points, ', description%modes%n_modes(), ' modes from ', minval(modes%frequency), &
            ' Hz up to the band, ', f_band, ' Hz (', n_above, ' above it as a static compliance, ', &
            trim(adjustl(percent)), &
            ' % of the static flexibility at the points, largest R_ii ', largest, ' m/N; ' &
            //'damping ratio from the file for ', modes%n_damped_by_file, ', ', damping_ratio, ' for ', &
            size(modes%frequency) - modes%n_damped_by_file, ' modes)'
        summary = trim(numbers)
    end subroutine split_band

    !> Memory [bytes] `split_band` takes for N_c points and N_m modes: the static compliance R
    !> (N_c x N_c) and the shapes at the points (N_c x N_m), before any convolver is made on
    !> them (which holds at least another N_c x N_c matrix: W0). For a check before the call.
    pure real(dp) function band_bytes(n_points, n_modes)
        !> Number of points N_c.
        integer, intent(in) :: n_points
        !> Number of modes N_m.
        integer, intent(in) :: n_modes

        band_bytes = 8.0_dp*real(n_points, dp)*(real(n_points, dp) + real(n_modes, dp))
    end function band_bytes

    !> A frequency as `1234.5 Hz` in a fixed buffer.
    pure function hz(f) result(text)
        real(dp), intent(in) :: f
        character(len=32) :: text

        write (text, '(f0.1,a)') f, ' Hz'
    end function hz

end module greenconv_model_modes_file
