!> The records of a sweep's finished variants: each finished variant is recorded
!> at once (atomically, greenconv_io_files's `write_text`) in
!> `<output_dir>/<name>_sweep.d/<key>.rec`, keyed by a hash of the variant's text, of the
!> contents of the files it names (road file or texture, receptance or Green's matrix file)
!> and of the options that change what a variant gives (spectra and their band range,
!> histories with the variant's number, which names its files), so a rerun skips what is
!> done and reruns what was edited, also through the files. A skipped variant costs its
!> key: reading its scene from memory and hashing its text and files.
module greenconv_scene_sweep_record
    use, intrinsic :: iso_fortran_env, only: int64
    use greenconv_core_error, only: error_type, fatal_error
    use greenconv_core_text, only: int_text, real_text
    use greenconv_io_files, only: make_directory, write_text
    use greenconv_scene_read_facade, only: scene_type
    use greenconv_scene_settings, only: scene_files, file_print
    use greenconv_scene_sweep_plan, only: sweep_text, sweep_plan, variant_lines, read_text_lines, append_text
    implicit none
    private

    public :: variant_outcome, variant_key, content_key, outcome_text, outcome_from_text, save_record, load_record, &
              record_path

    !> What one variant gave: its summary per method, the CPU times, the worst status.
    type :: variant_outcome
        !> Per method: max, mean, rms of the total contact force [N], fraction of steps in
        !> contact, status, step of the fault; blank-separated, the same on every machine run.
        character(len=:), allocatable :: result
        !> CPU seconds of the contact loop of each method, blank-separated.
        character(len=:), allocatable :: cpu
        !> Worst status of its methods (greenconv_scene_sweep_report's `worse_status`): 0 done, 4 ran
        !> outside the accuracy asked, 2 bad input, 3 numerical fault.
        integer :: status = 0
        !> The first failure's message ('' when none).
        character(len=:), allocatable :: message
        !> The variant's content key (`content_key`), set when it ran; its record's name. Not
        !> part of the outcome's text: unset, the outcome is not recorded.
        character(len=:), allocatable :: key
    end type variant_outcome

    !> Lines hashed one after another (a key's parts: a variant's text, a file).
    type :: text_block
        type(sweep_text), allocatable :: lines(:)
    end type text_block

    !> The FNV-1a prime and the modulus 2^32 of the keys' hashes.
    integer(int64), parameter :: prime = 16777619_int64, modulus = 4294967296_int64

contains

    !> The content key of a variant: two 32-bit FNV-1a hashes (forwards and backwards) of its
    !> text, as 16 hexadecimal digits. Equal texts give equal keys on every machine.
    function variant_key(lines) result(key)
        !> The variant's lines.
        type(sweep_text), intent(in) :: lines(:)
        character(len=16) :: key

        key = block_key([text_block(lines)])
    end function variant_key

    !> Continue the forward hash over lines (each followed by a newline).
    pure subroutine hash_forward(lines, hash)
        type(sweep_text), intent(in) :: lines(:)
        integer(int64), intent(inout) :: hash

        integer :: i, c

        do i = 1, size(lines)
            do c = 1, len(lines(i)%text)
                hash = mod(ieor(hash, int(ichar(lines(i)%text(c:c)), int64))*prime, modulus)
            end do
            hash = mod(ieor(hash, 10_int64)*prime, modulus)
        end do
    end subroutine hash_forward

    !> Continue the backward hash over lines, last character first (each line's newline before it).
    pure subroutine hash_backward(lines, hash)
        type(sweep_text), intent(in) :: lines(:)
        integer(int64), intent(inout) :: hash

        integer :: i, c

        do i = size(lines), 1, -1
            hash = mod(ieor(hash, 10_int64)*prime, modulus)
            do c = len(lines(i)%text), 1, -1
                hash = mod(ieor(hash, int(ichar(lines(i)%text(c:c)), int64))*prime, modulus)
            end do
        end do
    end subroutine hash_backward

    !> The content key of variant k, its record's name: `variant_key` of its lines, followed
    !> by a line of the options that change its result (spectra and their bands, histories)
    !> when set, and by each file the scene names (road file or texture, receptance file, Green's
    !> matrix file): its name and
    !> every line of it. An edited road file so changes the key of every variant that reads it.
    !> With histories the key also holds k, which names the variant's files: a variant whose
    !> number an edit of the lists changed runs again and rewrites the files of its number.
    !> Each file's lines are hashed on their own too and kept in `files` with the first
    !> variant that read it: a file edited while the sweep runs (whose road data the sweep
    !> read once, its receptances read again) is refused for every later variant, with both
    !> hashes, so that no table mixes two versions of a file.
    subroutine content_key(plan, k, scene, files, key, error)
        !> The sweep.
        type(sweep_plan), intent(in) :: plan
        !> Variant number.
        integer, intent(in) :: k
        !> The variant's scene, as `read_variant` gave it.
        type(scene_type), intent(in) :: scene
        !> Files read by earlier variants, with their hashes; the files this one reads are added.
        type(scene_files), intent(inout) :: files
        !> The key (16 hexadecimal digits).
        character(len=16), intent(out) :: key
        !> Set (status 2) when a file differs from what an earlier variant read.
        type(error_type), allocatable, intent(out) :: error

        type(text_block) :: blocks(9)
        integer :: n, i

        blocks(1)%lines = variant_lines(plan, k)
        if (plan%spectra) call append_text(blocks(1)%lines, '&sweep spectra = .true., f_low = ' &
                                           //real_text(plan%f_low)//', f_high = '//real_text(plan%f_high)//' /')
        if (plan%histories) call append_text(blocks(1)%lines, '&sweep histories = .true. / ! variant '//int_text(k))
        n = 1
        if (allocated(scene%road_data%path)) call add_file(blocks, n, scene%road_data%path)
        if (allocated(scene%texture%path)) call add_file(blocks, n, scene%texture%path)
        if (allocated(scene%frf_file)) then
            if (len_trim(scene%frf_file) > 0) call add_file(blocks, n, scene%frf_file)
        end if
        if (allocated(scene%green_file)) then
            if (len_trim(scene%green_file) > 0) call add_file(blocks, n, scene%green_file)
        end if
        do i = 3, n, 2
            if (.not. allocated(error)) call check_print(plan, k, blocks(i - 1)%lines(1)%text(8:), &
                                                         block_key(blocks(i:i)), files, error)
        end do
        key = block_key(blocks(:n))
    end subroutine content_key

    !> Two 32-bit FNV-1a hashes (forwards and backwards) of blocks of lines, as 16 hexadecimal digits.
    function block_key(blocks) result(key)
        type(text_block), intent(in) :: blocks(:)
        character(len=16) :: key

        integer(int64) :: forward, backward
        integer :: i

        forward = 2166136261_int64
        backward = 3421674724_int64
        do i = 1, size(blocks)
            call hash_forward(blocks(i)%lines, forward)
        end do
        do i = size(blocks), 1, -1
            call hash_backward(blocks(i)%lines, backward)
        end do
        write (key, '(z8.8,z8.8)') forward, backward
    end function block_key

    !> Compare a file's hash with the one the first variant that read it got (kept in `files`);
    !> a file read for the first time is kept.
    subroutine check_print(plan, k, path, hash, files, error)
        type(sweep_plan), intent(in) :: plan
        integer, intent(in) :: k
        character(len=*), intent(in) :: path
        character(len=16), intent(in) :: hash
        type(scene_files), intent(inout) :: files
        type(error_type), allocatable, intent(out) :: error

        integer :: i

        if (.not. allocated(files%prints)) allocate (files%prints(0))
        do i = 1, size(files%prints)
            if (files%prints(i)%path /= path) cycle
            if (files%prints(i)%hash /= hash) call fatal_error(error, plan%file//' (variant '//int_text(k)//'): ' &
                //path//' changed while the sweep ran: expected its lines as variant '//int_text(files%prints(i)%variant) &
                //' read them (hash '//files%prints(i)%hash//'), found hash '//hash &
                //'; one table holds one version of each file: run the sweep again on the file as it is now')
            return
        end do
        files%prints = [files%prints, file_print(path, hash, k)]
    end subroutine check_print

    !> Add to the blocks of a key a file's name and its lines (or that it cannot be read).
    subroutine add_file(blocks, n, path)
        type(text_block), intent(inout) :: blocks(:)
        integer, intent(inout) :: n
        character(len=*), intent(in) :: path

        type(error_type), allocatable :: error

        allocate (blocks(n + 1)%lines(1))
        blocks(n + 1)%lines(1)%text = '! file '//path
        call read_text_lines(path, blocks(n + 2)%lines, error)
        if (allocated(error)) blocks(n + 2)%lines = [sweep_text('! unreadable')]
        n = n + 2
    end subroutine add_file

    !> Length of `outcome_text`'s text.
    pure integer function outcome_length(outcome)
        !> The outcome.
        type(variant_outcome), intent(in) :: outcome

        outcome_length = len(outcome%result) + len(outcome%cpu) + len(int_text(outcome%status)) &
                         + len(outcome%message) + 3
    end function outcome_length

    !> An outcome as one text (its record, and what an MPI rank sends): four lines.
    pure function outcome_text(outcome) result(text)
        !> The outcome.
        type(variant_outcome), intent(in) :: outcome
        !> Result, CPU times, status and message, a line each.
        character(len=outcome_length(outcome)) :: text

        text = outcome%result//new_line('a')//outcome%cpu//new_line('a')//int_text(outcome%status)//new_line('a') &
               //outcome%message
    end function outcome_text

    !> The outcome `outcome_text` wrote; `ok` is .false. when the text is not one.
    subroutine outcome_from_text(text, outcome, ok)
        !> The text.
        character(len=*), intent(in) :: text
        !> The outcome.
        type(variant_outcome), intent(out) :: outcome
        !> Whether the text held an outcome.
        logical, intent(out) :: ok

        integer :: a, b, c, stat

        a = index(text, new_line('a'))
        b = a + index(text(a + 1:), new_line('a'))
        c = b + index(text(b + 1:), new_line('a'))
        ok = a > 0 .and. b > a .and. c > b
        if (.not. ok) return
        outcome%result = text(:a - 1)
        outcome%cpu = text(a + 1:b - 1)
        read (text(b + 1:c - 1), *, iostat=stat) outcome%status
        ok = stat == 0
        outcome%message = text(c + 1:)
    end subroutine outcome_from_text

    !> Length of `record_directory`'s path.
    pure integer function directory_length(plan)
        type(sweep_plan), intent(in) :: plan

        directory_length = len(plan%output_dir) + len(plan%name) + len('/_sweep.d')
    end function directory_length

    !> Record a variant's outcome, atomically, under its content key (nothing when the
    !> outcome has none: the variant failed its check, a fixed file reruns it).
    subroutine save_record(plan, outcome, error)
        !> The sweep.
        type(sweep_plan), intent(in) :: plan
        !> The variant's outcome.
        type(variant_outcome), intent(in) :: outcome
        !> Set when the record cannot be written.
        type(error_type), allocatable, intent(out) :: error

        if (.not. allocated(outcome%key)) return
        call make_directory(record_directory(plan), error)
        if (allocated(error)) return
        call write_text(record_path(plan, outcome%key), outcome_text(outcome), error)
    end subroutine save_record

    !> The directory of the records of finished variants.
    pure function record_directory(plan) result(path)
        type(sweep_plan), intent(in) :: plan
        character(len=directory_length(plan)) :: path

        path = plan%output_dir//'/'//plan%name//'_sweep.d'
    end function record_directory

    !> The record of a variant, named by its content key.
    pure function record_path(plan, key) result(path)
        !> The sweep.
        type(sweep_plan), intent(in) :: plan
        !> The variant's content key (hex digits).
        character(len=*), intent(in) :: key
        !> `<output_dir>/<name>_sweep.d/<key>.rec`.
        character(len=directory_length(plan) + len(key) + len('/.rec')) :: path

        path = record_directory(plan)//'/'//key//'.rec'
    end function record_path

    !> Read a record; `found` is .false. when there is none (or it is not one).
    subroutine load_record(path, outcome, found)
        !> File of the record.
        character(len=*), intent(in) :: path
        !> The variant's outcome read from it.
        type(variant_outcome), intent(out) :: outcome
        !> Whether a whole record was read.
        logical, intent(out) :: found

        type(sweep_text), allocatable :: lines(:)
        type(error_type), allocatable :: error
        character(len=:), allocatable :: text
        integer :: i

        inquire (file=path, exist=found)
        if (.not. found) return
        call read_text_lines(path, lines, error)
        found = .not. allocated(error)
        if (.not. found) return
        found = size(lines) >= 3
        if (.not. found) return
        text = lines(1)%text
        do i = 2, size(lines)
            text = text//new_line('a')//lines(i)%text
        end do
        if (size(lines) == 3) text = text//new_line('a')
        call outcome_from_text(text, outcome, found)
    end subroutine load_record

end module greenconv_scene_sweep_record
