!> Parameter sweeps (greenconv_scene_sweep): the variants of value lists (cartesian product,
!> last list fastest) and of a table file, how a value is written into the base scene's text
!> (replaced on its line, added to its group, or in a new group), the content key, the
!> table's row, the record's text, and the messages for a bad &sweep group. The runs on 1 and
!> 2 MPI ranks, resume and failures are checked by tools/test_sweep.sh (make sweep-test).
module test_sweep_mod
    use testsuite_mod, only: test_error, unittest_type, new_unittest, check
    use scene_text_mod, only: write_text
    use greenconv_core_error, only: error_type
    use greenconv_io_files, only: make_directory
    use greenconv_scene_sweep, only: sweep_text, sweep_plan, variant_outcome, read_sweep, variant_lines, &
                                     variant_key, summary_row, outcome_text, outcome_from_text, is_sweep_file
    implicit none
    private

    public :: collect_sweep

    !> Scratch directory for the files the tests write.
    character(len=*), parameter :: scratch = 'build/test_scratch/sweep'

contains

    !> Tests of greenconv_scene_sweep.
    subroutine collect_sweep(testsuite)
        type(unittest_type), allocatable, intent(out) :: testsuite(:)

        testsuite = [new_unittest('lists: cartesian product, last list fastest', test_product), &
                     new_unittest('variant text: replaced, added to its group, new group', test_variant_text), &
                     new_unittest('content key: equal texts, one changed character', test_key), &
                     new_unittest('table file: rows are the variants', test_table_file), &
                     new_unittest('summary row and record text', test_row), &
                     new_unittest('bad &sweep group: messages with the line', test_bad_sweep)]
    end subroutine collect_sweep

    !> A small SDOF sweep scene with the given &sweep group.
    function sweep_scene(group) result(text)
        character(len=*), intent(in) :: group
        character(len=:), allocatable :: text

        character(len=*), parameter :: nl = new_line('a')

        text = "&scene task = 'sweep', name = 'unit', output_dir = '"//scratch//"/out', dt = 1.0e-4, n_steps = 200 /" &
               //nl//"&structure model = 'sdof', mass = 1.0, stiffness = 1.0e6, damping_ratio = 0.02 /"//nl &
               //"&road"//nl//"    profile = 'sine'   ! the road"//nl//"    amplitude = 1.0e-3 ! [m]"//nl//"/"//nl &
               //"&contact stiffness = 1.0e6, exponent = 1.5 /"//nl//"&convolution methods = 'direct' /"//nl//group//nl
    end function sweep_scene

    !> Read a sweep written from `text`.
    subroutine read_text(name, text, plan, failure)
        character(len=*), intent(in) :: name, text
        type(sweep_plan), intent(out) :: plan
        type(error_type), allocatable, intent(out) :: failure

        call make_directory(scratch, failure)
        if (allocated(failure)) return
        call write_text(scratch//'/'//name, text)
        call read_sweep(scratch//'/'//name, plan, failure, 'unit')
    end subroutine read_text

    subroutine test_product(error)
        type(test_error), allocatable, intent(out) :: error

        type(sweep_plan) :: plan
        type(error_type), allocatable :: failure

        call read_text('product.nml', sweep_scene("&sweep"//new_line('a')//"  road.amplitude = 1.0e-3, 2.0e-3, 3.0e-3" &
                       //new_line('a')//"  contact.stiffness = 1.0e6 2.0e6 /"), plan, failure)
        call check(error, .not. allocated(failure), 'the sweep reads')
        if (allocated(error)) return
        call check(error, is_sweep_file(scratch//'/product.nml'), 'it is a sweep file')
        if (allocated(error)) return
        call check(error, size(plan%values, 1) == 6 .and. size(plan%values, 2) == 2, '3 x 2 = 6 variants')
        if (allocated(error)) return
        call check(error, plan%variables(1)%text == 'road.amplitude' .and. plan%variables(2)%text == &
                   'contact.stiffness', 'variables in order')
        if (allocated(error)) return
        call check(error, plan%values(2, 1)%text == '1.0e-3' .and. plan%values(2, 2)%text == '2.0e6' .and. &
                   plan%values(3, 1)%text == '2.0e-3' .and. plan%values(6, 2)%text == '2.0e6', &
                   'the last list varies fastest')
    end subroutine test_product

    subroutine test_variant_text(error)
        type(test_error), allocatable, intent(out) :: error

        type(sweep_plan) :: plan
        type(error_type), allocatable :: failure
        type(sweep_text), allocatable :: lines(:)

        call read_text('text.nml', sweep_scene("&sweep road.amplitude = 5.0e-4, road.omega = 50.0, " &
                       //"identification.order = 3 /"), plan, failure)
        call check(error, .not. allocated(failure), 'the sweep reads')
        if (allocated(error)) return
        lines = variant_lines(plan, 1)
        call check(error, size(lines) == size(plan%base) + 1, 'one line added (the new group)')
        if (allocated(error)) return
        call check(error, lines(5)%text == "    amplitude = 5.0e-4 ! [m]", 'the value replaced, its comment kept: ' &
                   //lines(5)%text)
        if (allocated(error)) return
        call check(error, lines(3)%text == "&road omega = 50.0 ", 'added right after its group''s name: ' &
                   //lines(3)%text)
        if (allocated(error)) return
        call check(error, lines(size(lines))%text == '&identification order = 3 /', 'a new group at the end')
        if (allocated(error)) return
        call check(error, len_trim(lines(9)%text) == 0 .and. index(lines(1)%text, "task = 'contact'") > 0, &
                   'the &sweep line blanked, the task set to contact')
    end subroutine test_variant_text

    subroutine test_key(error)
        type(test_error), allocatable, intent(out) :: error

        type(sweep_text), allocatable :: a(:), b(:)
        character(len=16) :: key

        a = [sweep_text('&scene n_steps = 10 /'), sweep_text('&road speed = 20.0 /')]
        b = a
        key = variant_key(a)
        call check(error, key == variant_key(b) .and. verify(key, '0123456789ABCDEF') == 0, 'equal texts, equal keys')
        if (allocated(error)) return
        b(2)%text = '&road speed = 20.1 /'
        call check(error, key /= variant_key(b), 'one character changed, another key')
        if (allocated(error)) return
        b = [sweep_text('&scene n_steps = 10 /&road'), sweep_text(' speed = 20.0 /')]
        call check(error, key /= variant_key(b), 'line breaks count')
    end subroutine test_key

    subroutine test_table_file(error)
        type(test_error), allocatable, intent(out) :: error

        type(sweep_plan) :: plan
        type(error_type), allocatable :: failure
        character(len=*), parameter :: nl = new_line('a')

        call make_directory(scratch, failure)
        call write_text(scratch//'/design.txt', '# road.amplitude contact.stiffness'//nl//'1.0e-3 1.0e6'//nl//nl &
                        //'# a comment'//nl//'2.0e-3, 4.0e6'//nl)
        call read_text('table.nml', sweep_scene("&sweep table_file = '"//scratch//"/design.txt' /"), plan, failure)
        call check(error, .not. allocated(failure), 'the sweep reads')
        if (allocated(error)) return
        call check(error, size(plan%values, 1) == 2 .and. plan%values(2, 2)%text == '4.0e6', 'two rows, two variants')
        if (allocated(error)) return
        call write_text(scratch//'/design.txt', 'road.amplitude contact.stiffness'//nl//'1.0e-3'//nl)
        call read_text('table.nml', sweep_scene("&sweep table_file = '"//scratch//"/design.txt' /"), plan, failure)
        call check(error, allocated(failure), 'a short row is refused')
        if (allocated(error)) return
        call check(error, index(failure%message, 'design.txt:2: expected 2 values') > 0, failure%message)
    end subroutine test_table_file

    subroutine test_row(error)
        type(test_error), allocatable, intent(out) :: error

        type(sweep_plan) :: plan
        type(error_type), allocatable :: failure
        type(variant_outcome) :: outcome, back
        logical :: ok

        call read_text('row.nml', sweep_scene("&sweep road.amplitude = 1.0e-3, 2.5e-3 /"), plan, failure)
        call check(error, .not. allocated(failure), 'the sweep reads')
        if (allocated(error)) return
        outcome%result = ' 1.0 2.0 3.0 0.5 0 0'
        outcome%cpu = ' 0.0100'
        outcome%status = 3
        outcome%message = 'diverged'
        call check(error, summary_row(plan, 2, outcome) == '2        2.5e-3         1.0 2.0 3.0 0.5 0 0', &
                   'the row: '//summary_row(plan, 2, outcome))
        if (allocated(error)) return
        call outcome_from_text(outcome_text(outcome), back, ok)
        call check(error, ok .and. back%result == outcome%result .and. back%cpu == outcome%cpu .and. &
                   back%status == 3 .and. back%message == 'diverged', 'the record text reads back')
    end subroutine test_row

    subroutine test_bad_sweep(error)
        type(test_error), allocatable, intent(out) :: error

        type(sweep_plan) :: plan
        type(error_type), allocatable :: failure

        call read_text('bad.nml', sweep_scene("&sweep"//new_line('a')//"road.sped = 1.0 /"), plan, failure)
        call check(error, allocated(failure), 'an unknown variable is refused')
        if (allocated(error)) return
        call check(error, failure%stat == 2 .and. index(failure%message, 'bad.nml:10: &sweep road.sped: expected a ' &
                   //'scene variable') > 0, failure%message)
        if (allocated(error)) return
        call read_text('bad.nml', sweep_scene("&sweep scene.name = 'a', 'b' /"), plan, failure)
        call check(error, allocated(failure), 'scene.name may not vary')
        if (allocated(error)) return
        call read_text('bad.nml', sweep_scene("&sweep road.amplitude = 1.0e-3"), plan, failure)
        call check(error, allocated(failure), 'an unclosed group is refused')
        if (allocated(error)) return
        call read_text('bad.nml', sweep_scene("&sweep road.amplitude = 1.0e-3 /") // "&road profile = 'x' /", &
                       plan, failure)
        call check(error, allocated(failure), 'a bad base scene is refused')
        if (allocated(error)) return
        call check(error, index(failure%message, '(the base scene)') > 0, failure%message)
    end subroutine test_bad_sweep

end module test_sweep_mod
