!> The contact points of a multi-point scene and what their convolvers are built from: the
!> modes of a structure and their shapes at the points (a built-in model), or a Green's matrix
!> read from a file and identified. A multi-point structure model of the registry
!> (greenconv_scene_models_registry) fills one; greenconv_scene_run_points builds each method on it.
module greenconv_scene_models_point_set
    use greenconv_core_kinds, only: dp
    use greenconv_model_point_modes, only: point_modes
    use greenconv_ident_green_structure, only: green_structure
    implicit none
    private

    public :: scene_points

    !> The points of a multi-point scene and what their convolvers are built from.
    type :: scene_points
        !> Positions x_i, y_i [m] of the points on the body (the columns x, y of the output).
        real(dp), allocatable :: x(:), y(:)
        !> Positions X_i(0), Y_i [m] of the points on the road (greenconv_scene_models_patch).
        real(dp), allocatable :: road_x(:), road_y(:)
        !> Whether the points come from a Green's matrix file (else from `modes`).
        logical :: from_file = .false.
        !> Whether the points spread across the patch too (y varies), so that the output has a
        !> column y.
        logical :: across = .false.
        !> The structure's modes and their shapes at the points.
        type(point_modes) :: modes
        !> Static compliance [m/N] (N_c x N_c) of the structure's modes above the band, added
        !> to W0 of the methods with an instant part (unallocated: none).
        real(dp), allocatable :: static(:, :)
        !> Top of the band of the modes stepped [Hz]; 0 when the model has no band (a Green's
        !> matrix file: its band is the file's).
        real(dp) :: band = 0.0_dp
        !> Whether every mode of the structure lies in the band (a modes file's modes all below
        !> it); an analytic model's modes never end.
        logical :: complete = .false.
        !> The Green's matrix read from the file, identified.
        type(green_structure) :: green
    contains
        !> Number of points N_c.
        procedure :: n_points => points_n_points
    end type scene_points

contains

    !> Number of points N_c.
    elemental integer function points_n_points(self)
        !> The points.
        class(scene_points), intent(in) :: self

        points_n_points = 0
        if (allocated(self%x)) points_n_points = size(self%x)
    end function points_n_points

end module greenconv_scene_models_point_set
