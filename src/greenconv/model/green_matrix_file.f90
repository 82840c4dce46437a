!> A Green's matrix G_ij(omega) between the N_c points of a contact patch, read from a
!> universal file (greenconv_io_uff) and checked.
!>
!> - **Points**: the nodes that appear both as a response and as a reference node of a
!>   receptance (dataset 58, function type 4), sorted by label; point i is the i-th of them.
!>   The same reader takes impulse responses g_ij(t) instead (function type 1, time response,
!>   `function_type = 1`): the abscissa is then time [s] and the ordinate g_ij [m/(N*s)].
!> - **Units**: records 8 to 10 of every dataset are read by greenconv_model_frf's
!>   `green_values`, the same reading as a single FRF's: receptances are taken, mobilities and
!>   accelerances converted to receptances, impulse responses must be displacement over force;
!>   anything else (a pressure, a velocity time history) is refused naming the dataset and record.
!> - **Geometry**: each point's coordinates from dataset 15 or 2411; x is the direction of
!>   travel, y across the patch (z is ignored).
!> - **Checks**, each a message naming the file and what to do: no receptance; a response or
!>   reference direction that differs from the first receptance's (mixed directions); a missing
!>   or repeated (response, reference) pair of points (the message names the datasets of the
!>   pair left out for their function type, and the datasets skipped); a node given only as a
!>   response or only as a reference node (its G would be dropped: the matrix would not be
!>   square); a frequency grid that differs from the first receptance's (number of lines, or a
!>   line by more than 1e-6 of the step); a point without coordinates; and, for each dataset,
!>   greenconv_model_frf's `check_contact_function`: directions along Z (3 or -3; a file in
!>   -Z/-Z is taken as it is, one in +Z/-Z or -Z/+Z gets its sign changed, so that G_ij is
!>   always displacement +Z per force +Z), complex values for receptances, and no value
!>   above `max_green_magnitude` in magnitude.
!> - **Reciprocity** (a warning, not an error): for each pair i < j the difference
!>   d_l = G_ij - G_ji. For a reciprocal structure it is noise alone, as rough from line to
!>   line as white noise; a systematic difference is smooth. The ratio of the rms of d to the
!>   rms of its normalised 4th difference (sum c^2 = 1, which leaves white noise's rms
!>   unchanged and removes a smooth part) is about 1 for noise and large for a real
!>   difference; the worst pair is named when its ratio exceeds `reciprocity_limit`.
module greenconv_model_green_matrix_file
    use greenconv_core_kinds, only: dp
    use greenconv_core_text, only: int_text, real_text
    use greenconv_core_error, only: error_type, fatal_error
    use greenconv_io_uff, only: uff_file, read_uff, uff_function_type_name
    use greenconv_model_modal_set, only: sorted_order
    use greenconv_model_frf, only: check_contact_function, green_values, frf_type
    implicit none
    private

    public :: green_matrix, read_green_matrix, check_green_matrix, reciprocity_limit

    !> A reciprocity ratio above this is reported: pure noise gives about 1 (3 is about five
    !> standard deviations of the ratio for 300 lines).
    real(dp), parameter :: reciprocity_limit = 3.0_dp
    !> Tolerance on the frequency grids, as a fraction of the step.
    real(dp), parameter :: grid_tolerance = 1.0e-6_dp

    !> A Green's matrix on a frequency grid with the points' layout.
    type :: green_matrix
        !> Node label of each point (ascending).
        integer, allocatable :: node(:)
        !> Position along the direction of travel x_i [m] of each point.
        real(dp), allocatable :: x(:)
        !> Position across y_i [m] of each point.
        real(dp), allocatable :: y(:)
        !> Frequency lines [Hz]; for impulse responses (function type 1) the sample times [s].
        real(dp), allocatable :: frequency(:)
        !> Receptances g(i, j, l) = G_ij(2*pi*frequency(l)) [m/N], displacement at i per force at j;
        !> for impulse responses g_ij(frequency(l)) [m/(N*s)] (imaginary part zero).
        complex(dp), allocatable :: g(:, :, :)
        !> Function type of the datasets read: 4 (receptances) or 1 (impulse responses).
        integer :: function_type = 4
        !> What records 9/10 said and how the values were converted, e.g. `mobility converted by
        !> G = Y/(i*omega)`; the distinct kinds joined by `; ` when the datasets differ.
        character(len=:), allocatable :: conversion
        !> Whether no pair failed the reciprocity check.
        logical :: reciprocal = .true.
        !> Largest reciprocity ratio (rms of G_ij - G_ji over the rms of its 4th difference) and its pair.
        real(dp) :: reciprocity = 0.0_dp
        !> Points (i, j) of the largest reciprocity ratio.
        integer :: worst_pair(2) = 0
        !> A warning for the user ('' when none).
        character(len=:), allocatable :: warning
    contains
        !> Number of points N_c.
        procedure :: n_points => matrix_n_points
    end type green_matrix

contains

    !> Number of points N_c of a Green's matrix.
    elemental integer function matrix_n_points(self)
        !> The matrix.
        class(green_matrix), intent(in) :: self

        matrix_n_points = 0
        if (allocated(self%node)) matrix_n_points = size(self%node)
    end function matrix_n_points

    !> Read a Green's matrix from a universal file and check it (see the module description).
    subroutine read_green_matrix(path, matrix, error, function_type)
        !> The universal file.
        character(len=*), intent(in) :: path
        !> The matrix, its points and their layout.
        type(green_matrix), intent(out) :: matrix
        !> Set (status 2) when the file cannot be read or does not hold a complete Green's matrix.
        type(error_type), allocatable, intent(out) :: error
        !> Function type of the datasets 58 that make the matrix: 4 (receptances, the default)
        !> or 1 (impulse responses).
        integer, intent(in), optional :: function_type

        type(uff_file) :: file

        call read_uff(path, file, error)
        if (allocated(error)) return
        call check_green_matrix(file, matrix, error, function_type)
    end subroutine read_green_matrix

    !> The Green's matrix held by a universal file already read (see the module description).
    subroutine check_green_matrix(file, matrix, error, function_type)
        !> The file as `read_uff` returned it.
        type(uff_file), intent(in) :: file
        !> The matrix, its points and their layout.
        type(green_matrix), intent(out) :: matrix
        !> Set (status 2) when the file does not hold a complete Green's matrix.
        type(error_type), allocatable, intent(out) :: error
        !> Function type of the datasets 58 that make the matrix: 4 (receptances, the default)
        !> or 1 (impulse responses).
        integer, intent(in), optional :: function_type

        integer, allocatable :: frfs(:), found(:, :)
        integer :: f, first, i, j, k, n_c, n_f, sign
        character(len=:), allocatable :: place, functions, grid_name, source, omitted
        complex(dp), allocatable :: values(:)
        type(frf_type) :: grid

        if (present(function_type)) matrix%function_type = function_type
        functions = 'receptances G_ij (datasets 58 of function type 4)'
        grid_name = 'frequency grid'
        if (matrix%function_type /= 4) then
            functions = 'impulse responses g_ij(t) (datasets 58 of function type '//int_text(matrix%function_type)//')'
            grid_name = 'time grid'
        end if
        frfs = pack([(f, f=1, size(file%functions))], file%functions%function_type == matrix%function_type)
        if (size(frfs) == 0) then
            call fatal_error(error, file%path//': expected '//functions//', found none; write one dataset per ' &
                             //'response and reference point')
            return
        end if
        first = frfs(1)
        do k = 1, size(frfs)
            associate (fun => file%functions(frfs(k)))
                place = file%path//':'//int_text(fun%line)//': dataset 58'
                if (fun%response_direction /= file%functions(first)%response_direction .or. &
                    fun%reference_direction /= file%functions(first)%reference_direction) then
                    call fatal_error(error, place//': mixed directions: response '//int_text(fun%response_direction) &
                                     //', reference '//int_text(fun%reference_direction)//', where the first ' &
                                     //'dataset (line '//int_text(file%functions(first)%line)//') has ' &
                                     //int_text(file%functions(first)%response_direction)//', ' &
                                     //int_text(file%functions(first)%reference_direction) &
                                     //'; give every G_ij in the one direction of contact')
                    return
                end if
                if (.not. same_grid(fun%abscissa, file%functions(first)%abscissa)) then
                    call fatal_error(error, place//': its '//grid_name//' ('//int_text(size(fun%abscissa)) &
                                     //' lines) differs from the first dataset''s (' &
                                     //int_text(size(file%functions(first)%abscissa))//' lines, line ' &
                                     //int_text(file%functions(first)%line)//'); resample every G_ij on one grid')
                    return
                end if
                call check_contact_function(file%path, fun, .false., sign, error)
                if (allocated(error)) return
            end associate
        end do
        call contact_nodes(file, frfs, matrix%node)
        call one_way_node(file, frfs, matrix%node, error)
        if (allocated(error)) return
        n_c = size(matrix%node)
        if (n_c == 0) then
            call fatal_error(error, file%path//': no node is both a response and a reference node; the contact ' &
                             //'points are the nodes where G_ij is given both ways')
            return
        end if
        n_f = size(file%functions(first)%abscissa)
        matrix%frequency = file%functions(first)%abscissa
        allocate (matrix%g(n_c, n_c, n_f), found(n_c, n_c))
        found(:, :) = 0
        grid%frequency = matrix%frequency
        matrix%conversion = ''
        do k = 1, size(frfs)
            associate (fun => file%functions(frfs(k)))
                i = findloc(matrix%node, fun%response_node, dim=1)
                j = findloc(matrix%node, fun%reference_node, dim=1)
                if (i == 0 .or. j == 0) cycle
                if (found(i, j) > 0) then
                    call fatal_error(error, file%path//':'//int_text(fun%line)//': dataset 58: G for response node ' &
                                     //int_text(fun%response_node)//', reference node '//int_text(fun%reference_node) &
                                     //' is given twice (first at line '//int_text(found(i, j)) &
                                     //'); keep one')
                    return
                end if
                found(i, j) = fun%line
                call green_values(file%path, fun, matrix%frequency, grid%uniform_from_zero(), values, source, error)
                if (allocated(error)) return
                if (index(matrix%conversion, source) == 0) then
                    if (len(matrix%conversion) > 0) matrix%conversion = matrix%conversion//'; '
                    matrix%conversion = matrix%conversion//source
                end if
                ! every dataset has the first one's directions: one sign for all (-Z/-Z: +1)
                matrix%g(i, j, :) = sign*values
            end associate
        end do
        do j = 1, n_c
            do i = 1, n_c
                if (found(i, j) == 0) then
                    call left_out(file, matrix%function_type, matrix%node(i), matrix%node(j), omitted)
                    call fatal_error(error, file%path//': missing G for response node '//int_text(matrix%node(i)) &
                                     //', reference node '//int_text(matrix%node(j))//' (the contact points are ' &
                                     //'the '//int_text(n_c)//' nodes given as response and reference); add it' &
                                     //omitted)
                    return
                end if
            end do
        end do
        call point_layout(file, matrix, error)
        if (allocated(error)) return
        call check_reciprocity(matrix)
        if (.not. matrix%reciprocal) then
            matrix%warning = file%path//': G_ij and G_ji differ beyond the noise: worst pair nodes ' &
                             //int_text(matrix%node(matrix%worst_pair(1)))//' and ' &
                             //int_text(matrix%node(matrix%worst_pair(2)))//', ratio ' &
                             //real_text(matrix%reciprocity)//' (about 1 for noise alone); the fit keeps ' &
                             //'G_ij and G_ji apart'
        else
            matrix%warning = ''
        end if
    end subroutine check_green_matrix

    !> Whether two frequency grids have as many lines and agree within `grid_tolerance` of a step.
    pure logical function same_grid(a, b)
        real(dp), intent(in) :: a(:), b(:)

        real(dp) :: step

        same_grid = size(a) == size(b)
        if (.not. same_grid .or. size(a) < 2) return
        step = abs(b(2) - b(1))
        same_grid = maxval(abs(a - b)) <= grid_tolerance*step
    end function same_grid

    !> The labels of the nodes that are both response and reference of a receptance, ascending.
    pure subroutine contact_nodes(file, frfs, nodes)
        type(uff_file), intent(in) :: file
        integer, intent(in) :: frfs(:)
        integer, allocatable, intent(out) :: nodes(:)

        integer, allocatable :: responses(:), references(:)
        integer :: k, label

        responses = file%functions(frfs)%response_node
        references = file%functions(frfs)%reference_node
        allocate (nodes(0))
        do k = 1, size(responses)
            label = responses(k)
            if (any(references == label) .and. .not. any(nodes == label)) nodes = [nodes, label]
        end do
        ! the labels are integers, exact as reals
        nodes = nodes(sorted_order(real(nodes, dp)))
    end subroutine contact_nodes

    !> Refuse a node that is only a response or only a reference node of the functions: the
    !> contact points are the nodes given both ways, so its datasets would be dropped without a
    !> word and the matrix the file means would not be square.
    subroutine one_way_node(file, frfs, nodes, error)
        type(uff_file), intent(in) :: file
        integer, intent(in) :: frfs(:), nodes(:)
        type(error_type), allocatable, intent(out) :: error

        integer :: k

        do k = 1, size(frfs)
            associate (fun => file%functions(frfs(k)))
                if (all(nodes /= fun%response_node)) then
                    call fatal_error(error, one_way(file%path, fun%line, fun%response_node, 'response', 'reference'))
                else if (all(nodes /= fun%reference_node)) then
                    call fatal_error(error, one_way(file%path, fun%line, fun%reference_node, 'reference', 'response'))
                end if
                if (allocated(error)) return
            end associate
        end do
    end subroutine one_way_node

    !> The message of `one_way_node`.
    pure function one_way(path, line, node, given, missing) result(text)
        character(len=*), intent(in) :: path, given, missing
        integer, intent(in) :: line, node
        character(len=len(path//':'//int_text(line + 7)//': universal file dataset 58 record 6: node '//int_text(node) &
               //' is a '//given//' node here but never a '//missing//' node, so it is no contact point (those ' &
               //'are the nodes given both ways) and this G would be dropped, leaving the matrix not square; ' &
               //'give G_ij both ways for every contact point, or remove the dataset')) :: text

        text = path//':'//int_text(line + 7)//': universal file dataset 58 record 6: node '//int_text(node) &
               //' is a '//given//' node here but never a '//missing//' node, so it is no contact point (those ' &
               //'are the nodes given both ways) and this G would be dropped, leaving the matrix not square; ' &
               //'give G_ij both ways for every contact point, or remove the dataset'
    end function one_way

    !> For the message on a missing G_ij: the datasets 58 of the pair that were left out for
    !> their function type ('' when there is none).
    pure subroutine left_out(file, function_type, response, reference, text)
        type(uff_file), intent(in) :: file
        integer, intent(in) :: function_type, response, reference
        character(len=:), allocatable, intent(out) :: text

        integer :: f

        text = ''
        do f = 1, size(file%functions)
            associate (fun => file%functions(f))
                if (fun%response_node /= response .or. fun%reference_node /= reference .or. &
                    fun%function_type == function_type) cycle
                text = text//'; the dataset 58 at line '//int_text(fun%line)//' for this pair was left out: its ' &
                       //'function type (record 6 field 1) is '//int_text(fun%function_type)//' (' &
                       //uff_function_type_name(fun%function_type)//'), not '//int_text(function_type)
            end associate
        end do
        do f = 1, size(file%skipped)
            if (f == 1) text = text//'; datasets the reader does not read were skipped:'
            text = text//' '//int_text(file%skipped(f)%dataset)//' (line '//int_text(file%skipped(f)%line)//')'
        end do
    end subroutine left_out

    !> x_i, y_i of every point from the file's nodes.
    subroutine point_layout(file, matrix, error)
        type(uff_file), intent(in) :: file
        type(green_matrix), intent(inout) :: matrix
        type(error_type), allocatable, intent(out) :: error

        integer :: i, k

        allocate (matrix%x(size(matrix%node)), matrix%y(size(matrix%node)))
        do i = 1, size(matrix%node)
            k = 0
            if (size(file%nodes) > 0) k = findloc(file%nodes%label, matrix%node(i), dim=1)
            if (k == 0) then
                call fatal_error(error, file%path//': node '//int_text(matrix%node(i))//' (a contact point) has ' &
                                 //'no coordinates; give it in dataset 15 or 2411 (x along the travel, y across)')
                return
            end if
            matrix%x(i) = file%nodes(k)%position(1)
            matrix%y(i) = file%nodes(k)%position(2)
        end do
    end subroutine point_layout

    !> The reciprocity ratio of every pair (see the module description), the worst one kept.
    pure subroutine check_reciprocity(matrix)
        type(green_matrix), intent(inout) :: matrix

        real(dp), parameter :: c(5) = [1.0_dp, -4.0_dp, 6.0_dp, -4.0_dp, 1.0_dp]/sqrt(70.0_dp)
        complex(dp), allocatable :: d(:), rough(:)
        real(dp) :: ratio
        integer :: i, j, l, n_f

        n_f = size(matrix%frequency)
        matrix%reciprocity = 0.0_dp
        matrix%worst_pair = 0
        if (n_f < 5) return
        allocate (rough(n_f - 4))
        do j = 2, size(matrix%node)
            do i = 1, j - 1
                d = matrix%g(i, j, :) - matrix%g(j, i, :)
                do l = 1, n_f - 4
                    rough(l) = sum(c*d(l:l + 4))
                end do
                ratio = sqrt(sum(abs(d)**2)/n_f)/max(sqrt(sum(abs(rough)**2)/(n_f - 4)), tiny(1.0_dp))
                if (sum(abs(d)**2) <= 0.0_dp) ratio = 0.0_dp
                if (ratio > matrix%reciprocity) then
                    matrix%reciprocity = ratio
                    matrix%worst_pair = [i, j]
                end if
            end do
        end do
        matrix%reciprocal = matrix%reciprocity <= reciprocity_limit
    end subroutine check_reciprocity

end module greenconv_model_green_matrix_file
