!> Fuzz test of the greenconv driver: damage the shipped scene, receptance and road files
!> thousands of ways and check that the driver always ends the way it promises.
!>
!>     greenconv-fuzz DRIVER WORKDIR CASES SEED [WORKER WORKERS]
!>     greenconv-fuzz --report COUNTS...
!>
!> WORKDIR holds a copy of data/ (the Makefile's helper makes it). Cases 1..CASES are shared
!> among WORKERS processes (default 1), worker w taking cases w, w + WORKERS, ...; each
!> writes its counts to WORKDIR/counts.txt, and `--report` adds such files up and prints the
!> table. Case k damages its file with a stream seeded by SEED and k, so a failing case is
!> the same whatever the number of workers. Each case damages one
!> shipped file (fuzz/mutation_mod.f90 lists the damages), runs `DRIVER --quiet --check`
!> on it and, when the check passes and the run is short (N_t <= 20000), runs it too.
!> A case passes when every run ends with status 0 (done), 2 (bad input), 3 (numerical
!> fault) or 4 (done outside the accuracy asked: counted with 0), standard error holds only lines starting "greenconv: " with exactly one that is
!> not a warning when the status is 2 or 3 and none when it is 0, no `.part` file is left,
!> no written row holds NaN or Inf, and standard output holds no message of LAPACK's XERBLA
!> ("On entry to ..."; the reference one prints it and stops with status 0, so the status alone
!> would not show it). A signal, a runtime error, a backtrace or a hang (60 s) fails it; the damaged file is kept in WORKDIR/failures/. The counts of cases and
!> of each outcome are printed; the exit status is 1 when a case failed.
program greenconv_fuzz
    use, intrinsic :: iso_fortran_env, only: output_unit, error_unit, int64
    use greenconv_core_random, only: random_stream
    use greenconv_core_text, only: int_text
    use mutation_mod, only: mutate, mutation_names, n_mutations
    implicit none

    !> A file to damage and how to run the driver on it.
    type :: target
        !> Short name for the report.
        character(len=16) :: name
        !> The file damaged, in WORKDIR/data.
        character(len=32) :: source
        !> The scene run, in WORKDIR/data; the damaged file when it is the scene itself.
        character(len=32) :: scene
        !> Path in the scene replaced by the damaged copy ('' when the scene is damaged).
        character(len=32) :: replaced
        !> Run the scene after a passing check (else check only).
        logical :: run
    end type target

    integer, parameter :: n_targets = 6
    !> Largest N_t run in full (a damaged number may ask for a run of hours, which is valid).
    integer, parameter :: max_run_steps = 20000
    !> Statuses counted: 0, 2, 3.
    integer, parameter :: statuses(3) = [0, 2, 3]
    !> Status 4: done, every file written, a method outside the scene's accuracy (counted as 0).
    integer, parameter :: done_outside_accuracy = 4
    type(target), parameter :: targets(n_targets) = [ &
        target('sdof scene', 'sdof_sine.nml', 'sdof_sine.nml', '', .true.), &
        target('identify scene', 'identify_clean.nml', 'identify_clean.nml', '', .true.), &
        target('FRF file', 'sample_receptance.frf', 'identify_clean.nml', 'data/sample_receptance.frf', .true.), &
        target('mdof scene', 'mdof_random.nml', 'mdof_random.nml', '', .false.), &
        target('tyre scene', 'tyre_road.nml', 'tyre_road.nml', '', .false.), &
        target('road file', 'road_sample.dat', 'tyre_road.nml', 'data/road_sample.dat', .false.)]

    character(len=:), allocatable :: driver, work
    integer :: n_cases, seed, worker, workers, case, k, kind, failures
    integer :: checked(n_targets, 3), ran(n_targets, 3), skipped(n_targets), by_kind(n_mutations)
    type(random_stream) :: stream

    checked = 0
    ran = 0
    skipped = 0
    by_kind = 0
    failures = 0
    if (argument(1) == '--report') then
        call add_counts()
        call report()
        if (failures > 0) stop 1
        stop
    end if
    call read_arguments(driver, work, n_cases, seed, worker, workers)
    call shell('mkdir -p '//work//'/failures')
    do case = worker, n_cases, workers
        stream = random_stream(int(seed, int64)*1000003_int64 + case)
        k = 1 + mod(case - 1, n_targets)
        call one_case(case, targets(k), kind)
        by_kind(kind) = by_kind(kind) + 1
    end do
    call save_counts(work//'/counts.txt')
    if (failures > 0) stop 1

contains

    !> DRIVER WORKDIR CASES SEED [WORKER WORKERS].
    subroutine read_arguments(driver, work, n_cases, seed, worker, workers)
        character(len=:), allocatable, intent(out) :: driver, work
        integer, intent(out) :: n_cases, seed, worker, workers

        integer :: stat(4)

        worker = 1
        workers = 1
        stat = 0
        if (command_argument_count() /= 4 .and. command_argument_count() /= 6) stat(1) = 1
        driver = argument(1)
        work = argument(2)
        n_cases = integer_argument(3, stat(1))
        seed = integer_argument(4, stat(2))
        if (command_argument_count() == 6) then
            worker = integer_argument(5, stat(3))
            workers = integer_argument(6, stat(4))
        end if
        if (any(stat /= 0) .or. worker < 1 .or. worker > workers) then
            write (error_unit, '(a)') 'usage: greenconv-fuzz DRIVER WORKDIR CASES SEED [WORKER WORKERS] ' &
                //'| greenconv-fuzz --report COUNTS...'
            stop 2
        end if
    end subroutine read_arguments

    !> Command-line argument i read as an integer (stat /= 0 when it is none).
    integer function integer_argument(i, stat)
        integer, intent(in) :: i
        integer, intent(inout) :: stat

        character(len=:), allocatable :: text
        integer :: read_stat

        text = argument(i)
        integer_argument = 0
        read (text, *, iostat=read_stat) integer_argument
        if (read_stat /= 0) stat = read_stat
    end function integer_argument

    !> This worker's counts, one file: cases, failures, then the count arrays.
    subroutine save_counts(path)
        character(len=*), intent(in) :: path

        integer :: unit

        open (newunit=unit, file=path, action='write', status='replace')
        write (unit, *) n_cases, seed, failures
        write (unit, *) checked, ran, skipped, by_kind
        close (unit)
    end subroutine save_counts

    !> Add up the counts files named on the command line after --report.
    subroutine add_counts()
        integer :: unit, i, stat, cases_w, seed_w, failures_w
        integer :: checked_w(n_targets, 3), ran_w(n_targets, 3), skipped_w(n_targets), by_kind_w(n_mutations)

        do i = 2, command_argument_count()
            open (newunit=unit, file=argument(i), action='read', status='old', iostat=stat)
            if (stat == 0) read (unit, *, iostat=stat) cases_w, seed_w, failures_w
            if (stat == 0) read (unit, *, iostat=stat) checked_w, ran_w, skipped_w, by_kind_w
            if (stat /= 0) then
                write (output_unit, '(a)') 'FAIL: no counts in '//argument(i)//' (the worker did not finish)'
                failures = failures + 1
                cycle
            end if
            close (unit)
            n_cases = cases_w
            seed = seed_w
            failures = failures + failures_w
            checked = checked + checked_w
            ran = ran + ran_w
            skipped = skipped + skipped_w
            by_kind = by_kind + by_kind_w
        end do
    end subroutine add_counts

    !> Command-line argument i.
    function argument(i) result(text)
        integer, intent(in) :: i
        character(len=:), allocatable :: text

        integer :: length

        call get_command_argument(i, length=length)
        allocate (character(len=length) :: text)
        call get_command_argument(i, text)
    end function argument

    !> Damage the target's file, check (and maybe run) the scene, count the outcomes.
    subroutine one_case(case, this, kind)
        integer, intent(in) :: case
        type(target), intent(in) :: this
        integer, intent(out) :: kind

        character(len=:), allocatable :: original, damaged, scene, case_file
        integer :: status, n_steps
        logical :: ok

        original = file_text(work//'/data/'//trim(this%source))
        call mutate(original, stream, damaged, kind)
        if (len_trim(this%replaced) == 0) then
            case_file = 'case.nml'
            call write_text(work//'/case.nml', damaged)
        else
            case_file = 'mutant'//this%source(index(this%source, '.', back=.true.):)
            call write_text(work//'/'//case_file, damaged)
            ! The scene is only the vehicle of the damaged file: a smaller order scan (the file
            ! holds 4 modes) keeps a damaged receptance, whose fit misses E <= tol_e and scans
            ! every order, to about a second.
            scene = replace(file_text(work//'/data/'//trim(this%scene)), trim(this%replaced), case_file)
            call write_text(work//'/case.nml', replace(scene, 'max_order = 20', 'max_order = 8'))
        end if
        call run_driver('--check', status, ok, n_steps)
        call record(case, this, kind, 'check', status, ok, case_file, checked)
        if (.not. (ok .and. status == 0 .and. this%run)) return
        if (n_steps > max_run_steps) then
            skipped(index_of(this)) = skipped(index_of(this)) + 1
            return
        end if
        call run_driver('', status, ok, n_steps)
        call record(case, this, kind, 'run', status, ok, case_file, ran)
    end subroutine one_case

    !> Run the driver on WORKDIR/case.nml (with `option`) and judge how it ended.
    subroutine run_driver(option, status, ok, n_steps)
        character(len=*), intent(in) :: option
        integer, intent(out) :: status, n_steps
        logical, intent(out) :: ok

        character(len=:), allocatable :: stdout, text
        logical :: clean
        integer :: at, stat
        integer(int64) :: start, finish, rate

        call system_clock(start, rate)
        call shell('cd '//work//' && rm -rf out && timeout 60 '//driver//' --quiet '//option// &
                   ' case.nml > stdout.txt 2> stderr.txt; echo $? > status.txt; ' &
                   //'(ls out/*.part 2>/dev/null; grep -v "^#" out/*.dat 2>/dev/null | grep -iE "nan|inf") ' &
                   //'> leftovers.txt; true')
        call system_clock(finish)
        if (finish - start > 5*rate) write (output_unit, '(a,f6.1,a)') 'slow: '//option//' took ', &
            real(finish - start)/rate, ' s on '//work//'/case.nml: '//first_line(work//'/stdout.txt')
        text = file_text(work//'/status.txt')
        read (text, *, iostat=stat) status
        if (stat /= 0) status = -1
        clean = stderr_is_clean(status)
        text = file_text(work//'/leftovers.txt')
        stdout = file_text(work//'/stdout.txt')
        ok = (any(status == statuses) .or. status == done_outside_accuracy) .and. clean .and. len_trim(text) == 0 &
             .and. index(stdout, 'On entry to') == 0
        n_steps = 0
        at = index(stdout, 'N_t = ')
        if (at > 0) then
            read (stdout(at + 6:), *, iostat=stat) n_steps
            if (stat /= 0) n_steps = huge(n_steps)
        end if
    end subroutine run_driver

    !> Standard error holds only "greenconv: " lines: none but warnings on success, exactly
    !> one that is not a warning on failure.
    logical function stderr_is_clean(status)
        integer, intent(in) :: status

        character(len=:), allocatable :: text
        integer :: first, last, messages

        text = file_text(work//'/stderr.txt')
        messages = 0
        stderr_is_clean = .true.
        first = 1
        do while (first <= len(text))
            last = index(text(first:), new_line('a')) + first - 1
            if (last < first) last = len(text) + 1
            if (index(text(first:last - 1), 'greenconv: ') /= 1) stderr_is_clean = .false.
            if (index(text(first:last - 1), 'greenconv: warning') /= 1) messages = messages + 1
            first = last + 1
        end do
        if (status == 0) stderr_is_clean = stderr_is_clean .and. messages == 0
        if (status /= 0) stderr_is_clean = stderr_is_clean .and. messages == 1
    end function stderr_is_clean

    !> Count an outcome; keep the damaged file of a failing case and say what happened.
    subroutine record(case, this, kind, stage, status, ok, case_file, counts)
        integer, intent(in) :: case, kind, status
        type(target), intent(in) :: this
        character(len=*), intent(in) :: stage, case_file
        logical, intent(in) :: ok
        integer, intent(inout) :: counts(:, :)

        character(len=:), allocatable :: kept
        integer :: j

        if (ok) then
            j = findloc(statuses, merge(0, status, status == done_outside_accuracy), dim=1)
            counts(index_of(this), j) = counts(index_of(this), j) + 1
            return
        end if
        failures = failures + 1
        kept = work//'/failures/case_'//int_text(case)
        call shell('cd '//work//' && mkdir -p '//kept//' && cp case.nml stderr.txt stdout.txt leftovers.txt ' &
                   //case_file//' '//kept//'/ 2>/dev/null; true')
        write (output_unit, '(a)') 'FAIL case '//int_text(case)//' ('//trim(this%name)//', '// &
            trim(mutation_names(kind))//', '//stage//'): status '//int_text(status)//'; kept in '//kept
    end subroutine record

    !> Position of a target in `targets`.
    integer function index_of(this)
        type(target), intent(in) :: this

        integer :: k

        index_of = 1
        do k = 1, n_targets
            if (targets(k)%name == this%name) index_of = k
        end do
    end function index_of

    !> The counts: per target, per stage and status; per kind of damage.
    subroutine report()
        integer :: k

        write (output_unit, '(a)') 'greenconv fuzz: '//int_text(sum(by_kind))//' cases, seed '//int_text(seed)// &
            '; statuses 0 done, 2 bad input, 3 numerical fault'
        write (output_unit, '(a16,3a8,3a8,a9)') 'file damaged', 'chk 0', 'chk 2', 'chk 3', 'run 0', 'run 2', &
            'run 3', 'not run'
        do k = 1, n_targets
            write (output_unit, '(a16,6i8,i9)') targets(k)%name, checked(k, :), ran(k, :), skipped(k)
        end do
        write (output_unit, '(a16,6i8,i9)') 'total', sum(checked, dim=1), sum(ran, dim=1), sum(skipped)
        write (output_unit, '(a)') 'damages: '//kinds_text()
        write (output_unit, '(a)') 'not run: the check passed but N_t > '//int_text(max_run_steps)// &
            ' (a valid, long run) or the file is checked only (mdof, tyre, road)'
        write (output_unit, '(a)') 'failures (signal, runtime error, hang, stray output, NaN row): '// &
            int_text(failures)
    end subroutine report

    !> "name n, name n, ..." for the kinds of damage done.
    function kinds_text() result(text)
        character(len=:), allocatable :: text

        integer :: j

        text = ''
        do j = 1, n_mutations
            if (j > 1) text = text//', '
            text = text//trim(mutation_names(j))//' '//int_text(by_kind(j))
        end do
    end function kinds_text

    !> The first line of a file.
    function first_line(path) result(line)
        character(len=*), intent(in) :: path
        character(len=:), allocatable :: line

        integer :: last

        line = file_text(path)
        last = index(line, new_line('a'))
        if (last > 0) line = line(1:last - 1)
    end function first_line

    !> The whole file as one string ('' when it cannot be read).
    function file_text(path) result(text)
        character(len=*), intent(in) :: path
        character(len=:), allocatable :: text

        integer :: unit, stat, length

        text = ''
        open (newunit=unit, file=path, access='stream', form='unformatted', action='read', status='old', &
              iostat=stat)
        if (stat /= 0) return
        inquire (unit=unit, size=length)
        if (length > 0) then
            deallocate (text)
            allocate (character(len=length) :: text)
            read (unit, iostat=stat) text
            if (stat /= 0) text = ''
        end if
        close (unit)
    end function file_text

    !> Write a string as a whole file.
    subroutine write_text(path, text)
        character(len=*), intent(in) :: path, text

        integer :: unit

        open (newunit=unit, file=path, access='stream', form='unformatted', action='write', status='replace')
        write (unit) text
        close (unit)
    end subroutine write_text

    !> `text` with every `old` replaced by `new`.
    function replace(text, old, new) result(changed)
        character(len=*), intent(in) :: text, old, new
        character(len=:), allocatable :: changed

        integer :: at, from

        changed = ''
        from = 1
        do
            at = index(text(from:), old)
            if (at == 0) exit
            changed = changed//text(from:from + at - 2)//new
            from = from + at - 1 + len(old)
        end do
        changed = changed//text(from:)
    end function replace

    !> Run a shell command; the harness stops if the shell itself cannot run.
    subroutine shell(command)
        character(len=*), intent(in) :: command

        integer :: exit_status, command_status

        call execute_command_line(command, exitstat=exit_status, cmdstat=command_status)
        if (command_status /= 0) then
            write (error_unit, '(a)') 'greenconv-fuzz: cannot run a shell command: '//command
            stop 2
        end if
    end subroutine shell

end program greenconv_fuzz
