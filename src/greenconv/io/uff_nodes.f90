!> Datasets 15 and 2411 of universal files (nodes) for the reader greenconv_io_uff: dataset
!> 15 holds one record per node, 4I10,1P3E13.5; dataset 2411 two, 4I10 and 1P3D25.16.
module greenconv_io_uff_nodes
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type, fatal_error
    use greenconv_core_text, only: int_text, real_text
    use greenconv_io_uff_types, only: uff_node
    use greenconv_io_uff_records, only: text_line, dataset_extent, record_prefix, integer_field, real_field, &
                                        repeated_labels, locate_label, quick_integer, quick_real
    implicit none
    private

    public :: read_nodes, check_node_labels

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
        character(len=:), allocatable :: line
        integer :: k, field, record

        record = 1
        do k = set%first + 2, set%last - 1
            if (len_trim(lines(k)%text) == 0) cycle
            line = lines(k)%text
            if (record == 1) node = uff_node(dataset=set%number, line=k)
            if (.not. well_formed(line, record, set%number == 15, node)) then
                ! read again with the fields' names: the message (the slow path keeps the last word)
                call refuse_record(record_prefix(path, k, set%number, record), line, record, node, error)
                if (allocated(error)) return
            end if
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

    contains

        !> The fields of one record read into `node` without a message (the fast path: a
        !> message prefix per record cost a minute on 10^5 nodes); false when one is malformed.
        logical function well_formed(text, at, one_record, node) result(ok)
            !> The record's line.
            character(len=*), intent(in) :: text
            !> Record number within the node (1, or 2 for the coordinates of dataset 2411).
            integer, intent(in) :: at
            !> Whether the node is one record (dataset 15: 4I10,1P3E13.5).
            logical, intent(in) :: one_record
            !> The node, its fields of this record filled.
            type(uff_node), intent(inout) :: node

            integer :: i, width, skip

            ok = .true.
            if (at == 1) then
                call quick_integer(text, 1, 10, node%label, ok)
                if (ok) call optional_integer(text, 11, 20, node%definition_system, ok)
                if (ok) call optional_integer(text, 21, 30, node%displacement_system, ok)
                if (ok) call optional_integer(text, 31, 40, node%color, ok)
                if (.not. ok) return
                if (.not. one_record) then
                    ok = len_trim(text) <= 40
                    return
                end if
            end if
            skip = merge(40, 0, one_record)
            width = merge(13, 25, one_record)
            do i = 1, 3
                if (ok) call quick_real(text, skip + (i - 1)*width + 1, skip + i*width, node%position(i), ok)
            end do
            ok = ok .and. len_trim(text) <= skip + 3*width
        end function well_formed

        !> An integer field that may be blank (0).
        subroutine optional_integer(text, first, last, value, ok)
            !> The line.
            character(len=*), intent(in) :: text
            !> First and last column of the field.
            integer, intent(in) :: first, last
            !> The integer (0 when blank).
            integer, intent(out) :: value
            !> Whether the field is blank or an integer.
            logical, intent(out) :: ok

            value = 0
            ok = .true.
            if (len_trim(adjustl(text(min(first, len(text) + 1):min(last, len(text))))) == 0) return
            call quick_integer(text, first, last, value, ok)
        end subroutine optional_integer

        !> A record the fast path did not take, read again field by field with their names: the
        !> message of the first malformed field, or the node when all are well formed.
        subroutine refuse_record(prefix, text, at, node, fail)
            !> Start of the message (`record_prefix`) and the record's line.
            character(len=*), intent(in) :: prefix, text
            !> Record number within the node.
            integer, intent(in) :: at
            !> The node, its fields of this record filled.
            type(uff_node), intent(inout) :: node
            !> Set (status 2) for the first malformed field.
            type(error_type), allocatable, intent(out) :: fail

            if (at == 1) then
                call integer_field(prefix, text, 1, 10, 'the node label', .true., node%label, fail)
                if (.not. allocated(fail)) call integer_field(prefix, text, 11, 20, &
                    'the definition coordinate system', .false., node%definition_system, fail)
                if (.not. allocated(fail)) call integer_field(prefix, text, 21, 30, &
                    'the displacement coordinate system', .false., node%displacement_system, fail)
                if (.not. allocated(fail)) call integer_field(prefix, text, 31, 40, 'the color', .false., &
                                                              node%color, fail)
                if (allocated(fail)) return
            end if
            if (set%number == 15) then
                call read_coordinates(prefix, text, 40, 13, '4I10,1P3E13.5', node, fail)
            else if (at == 2) then
                call read_coordinates(prefix, text, 0, 25, '1P3D25.16', node, fail)
            else if (len_trim(text) > 40) then
                call fatal_error(fail, prefix//'expected nothing after column 40 (4I10), found "' &
                                 //trim(adjustl(text(41:)))//'"')
            end if
        end subroutine refuse_record
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

    !> Refuse a node label given twice with other coordinates (a second definition would
    !> otherwise be ignored without a word); a label repeated with the same coordinates is
    !> harmless. O(n log n): the labels are sorted, and only the repeated ones are compared.
    subroutine check_node_labels(path, nodes, error)
        !> File the nodes come from (for messages).
        character(len=*), intent(in) :: path
        !> Every node of the file's datasets 15 and 2411, in file order.
        type(uff_node), intent(in) :: nodes(:)
        !> Set (status 2) naming both lines when a label has two sets of coordinates.
        type(error_type), allocatable, intent(out) :: error

        real(dp), allocatable :: repeated(:)
        integer, allocatable :: first(:), labels(:)
        integer :: k, at

        labels = nodes%label
        repeated = repeated_labels(labels)
        if (size(repeated) == 0) return
        allocate (first(size(repeated)))
        first(:) = 0
        do k = 1, size(nodes)
            at = locate_label(repeated, nodes(k)%label)
            if (at == 0) cycle
            if (first(at) == 0) then
                first(at) = k
            else if (any(nodes(k)%position /= nodes(first(at))%position)) then
                call fatal_error(error, path//':'//int_text(nodes(k)%line)//': universal file dataset ' &
                                 //int_text(nodes(k)%dataset)//': node '//int_text(nodes(k)%label) &
                                 //' is given again with other coordinates ('//position_text(nodes(k)) &
                                 //') than at line '//int_text(nodes(first(at))%line)//' (' &
                                 //position_text(nodes(first(at)))//'); give each node once')
                return
            end if
        end do
    end subroutine check_node_labels

    !> `position_text` blank-padded to a fixed length, which gives that function a result of spec length.
    pure function position_text_buffer(node) result(text)
        type(uff_node), intent(in) :: node
        character(len=96) :: text

        text = 'x, y, z = '//real_text(node%position(1))//', '//real_text(node%position(2))//', ' &
               //real_text(node%position(3))
    end function position_text_buffer

    !> A node's coordinates as `x, y, z = 0.1, 0.0, 0.0`.
    pure function position_text(node) result(text)
        type(uff_node), intent(in) :: node
        character(len=len_trim(position_text_buffer(node))) :: text

        text = position_text_buffer(node)
    end function position_text

end module greenconv_io_uff_nodes
