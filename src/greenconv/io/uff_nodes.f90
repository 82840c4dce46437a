!> Datasets 15 and 2411 of universal files (nodes) for the reader greenconv_io_uff: dataset
!> 15 holds one record per node, 4I10,1P3E13.5; dataset 2411 two, 4I10 and 1P3D25.16.
module greenconv_io_uff_nodes
    use greenconv_core_error, only: error_type, fatal_error
    use greenconv_core_text, only: int_text
    use greenconv_io_uff_types, only: uff_node
    use greenconv_io_uff_records, only: text_line, dataset_extent, record_prefix, integer_field, real_field
    implicit none
    private

    public :: read_nodes

contains

    !> Append the nodes of a dataset 15 (one record per node, 4I10,1P3E13.5) or 2411 (4I10,
    !> then 1P3D25.16) to nodes(1:n_nodes).
    subroutine read_nodes(path, lines, set, nodes, n_nodes, error)
        !> File the lines come from (for messages).
        character(len=*), intent(in) :: path
        !> The file's lines.
        type(text_line), intent(in) :: lines(:)
        !> Where the dataset (15 or 2411) lies in them.
        type(dataset_extent), intent(in) :: set
        !> Nodes read so far, 1..n_nodes in use; grown as needed.
        type(uff_node), allocatable, intent(inout) :: nodes(:)
        !> Number of nodes in use, increased by the dataset's nodes.
        integer, intent(inout) :: n_nodes
        !> Set (status 2) when a record is malformed or the dataset ends inside a node.
        type(error_type), allocatable, intent(out) :: error

        type(uff_node) :: node
        character(len=:), allocatable :: line, prefix
        integer :: k, field, record

        record = 1
        do k = set%first + 2, set%last - 1
            if (len_trim(lines(k)%text) == 0) cycle
            line = lines(k)%text
            prefix = record_prefix(path, k, set%number, record)
            if (record == 1) then
                node = uff_node(dataset=set%number, line=k)
                call integer_field(prefix, line, 1, 10, 'the node label', .true., node%label, error)
                if (.not. allocated(error)) call integer_field(prefix, line, 11, 20, &
                    'the definition coordinate system', .false., node%definition_system, error)
                if (.not. allocated(error)) call integer_field(prefix, line, 21, 30, &
                    'the displacement coordinate system', .false., node%displacement_system, error)
                if (allocated(error)) return
                call integer_field(prefix, line, 31, 40, 'the color', .false., node%color, error)
                if (allocated(error)) return
            end if
            if (set%number == 15) then
                call read_coordinates(prefix, line, 40, 13, '4I10,1P3E13.5', node, error)
            else if (record == 2) then
                call read_coordinates(prefix, line, 0, 25, '1P3D25.16', node, error)
            else if (len_trim(line) > 40) then
                call fatal_error(error, prefix//'expected nothing after column 40 (4I10), found "' &
                                 //trim(adjustl(line(41:)))//'"')
            end if
            if (allocated(error)) return
            if (set%number == 2411 .and. record == 1) then
                record = 2
                cycle
            end if
            record = 1
            if (n_nodes == size(nodes)) nodes = [nodes, (uff_node(), field=1, max(16, n_nodes))]
            n_nodes = n_nodes + 1
            nodes(n_nodes) = node
        end do
        if (record == 2) then
            call fatal_error(error, record_prefix(path, set%last, set%number, 2)//'expected the coordinates of node ' &
                             //int_text(node%label)//' (1P3D25.16), found the -1 line that ends the dataset')
        end if
    end subroutine read_nodes

    !> Three coordinates in fields of `width` columns after column `skip`; nothing after them.
    subroutine read_coordinates(prefix, line, skip, width, layout, node, error)
        character(len=*), intent(in) :: prefix, line, layout
        integer, intent(in) :: skip, width
        type(uff_node), intent(inout) :: node
        type(error_type), allocatable, intent(out) :: error

        character(len=1), parameter :: axes(3) = ['x', 'y', 'z']
        integer :: i, a

        do i = 1, 3
            a = skip + (i - 1)*width + 1
            call real_field(prefix, line, a, a + width - 1, 'the '//axes(i)//' coordinate of node ' &
                            //int_text(node%label), layout, .true., node%position(i), error)
            if (allocated(error)) return
        end do
        if (len_trim(line) > skip + 3*width) then
            call fatal_error(error, prefix//'expected nothing after column '//int_text(skip + 3*width)//' (' &
                             //layout//'), found "'//trim(adjustl(line(skip + 3*width + 1:)))//'"')
        end if
    end subroutine read_coordinates

end module greenconv_io_uff_nodes
