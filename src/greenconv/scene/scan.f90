!> A first pass over a namelist file, before the compiler's namelist reads: it knows the
!> groups and variables a program reads and the kind of each value, so that every mistake
!> gets one line with its place instead of a run-time library message (or, worse, silence):
!>
!>     scene.nml:7: &structure stifness: expected a variable of &structure (model, mass, ...),
!>         found 'stifness'; did you mean 'stiffness'?
!>     scene.nml:3: &scene n_steps: expected an integer, found '2.5'
!>     scene.nml:12: &roads: expected a group &scene, &structure, ... or &convolution, found
!>         '&roads'; did you mean '&road'?
!>
!> (each one line; broken here for the width).
!>
!> What it reads: groups `&name ... /` (also closed by `&end`), `!` comments anywhere
!> outside quotes, assignments `name = value, value ...` whose values may span lines,
!> repeat counts `3*0.5` (and null values `3*`), array elements `methods(2) = 'fft'`,
!> texts in '...' or "..." with doubled quotes inside. What it refuses, with the line:
!> text outside any group, an unknown group or variable (with the closest name by edit
!> distance), a group given twice or not closed, a variable assigned twice in a group, a
!> missing value, too many values, and a value of the wrong kind: not a number, NaN or
!> Inf, a real beyond double precision (1e999), an integer beyond the default integer
!> range, a logical that is not .true./.false., a text without quotes.
!>
!> The scan keeps each group's and each assignment's line and first value, which the reader
!> uses for its range checks (`line_of`, `value_of`).
module greenconv_scene_scan
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type, fatal_error
    use greenconv_core_text, only: int_text, lower_text
    use greenconv_core_number_text, only: is_number, is_nan_or_inf, is_integer, read_real, read_integer
    implicit none
    private

    public :: value_real, value_integer, value_logical, value_text, value_text_list
    public :: namelist_variable, namelist_group, namelist_scan, scan_namelist

    !> Kind of a variable: a real (double precision, finite).
    integer, parameter :: value_real = 1
    !> Kind of a variable: a default integer.
    integer, parameter :: value_integer = 2
    !> Kind of a variable: a logical (.true. or .false.).
    integer, parameter :: value_logical = 3
    !> Kind of a variable: one text in quotes.
    integer, parameter :: value_text = 4
    !> Kind of a variable: a list of texts in quotes (an array; see `namelist_variable%size`).
    integer, parameter :: value_text_list = 5

    !> Longest group or variable name shown in a list.
    integer, parameter :: name_width = 32

    !> What a value of each kind is, for messages (`kind_text`).
    character(len=*), parameter :: kind_texts(value_real:value_text_list) = [character(len=17) :: &
        'a real number', 'an integer', '.true. or .false.', 'a text in quotes', 'a text in quotes']

    integer, parameter :: token_word = 1, token_text = 2, token_equals = 3, token_comma = 4, &
                          token_slash = 5, token_group = 6, token_end = 7

    !> A variable a group may set.
    type :: namelist_variable
        !> Name, in lower case.
        character(len=:), allocatable :: name
        !> Kind of its values: value_real, value_integer, value_logical, value_text or value_text_list.
        integer :: kind = value_real
        !> Number of elements: 1 for a scalar.
        integer :: size = 1
    end type namelist_variable

    !> A group a file may hold, with its variables.
    type :: namelist_group
        !> Name, in lower case, without the `&`.
        character(len=:), allocatable :: name
        !> Its variables.
        type(namelist_variable), allocatable :: variables(:)
    end type namelist_group

    !> A group or an assignment found in the file.
    type :: namelist_entry
        !> Group name.
        character(len=:), allocatable :: group
        !> Variable name without subscript; '' for the group itself.
        character(len=:), allocatable :: variable
        !> Variable name with its subscript, as compared for repeats.
        character(len=:), allocatable :: key
        !> Line of the group's `&name` or of the variable's name.
        integer :: line = 0
        !> First value (texts without their quotes); '' when none.
        character(len=:), allocatable :: value
    end type namelist_entry

    !> What the scan found: the groups and assignments of the file, with their lines.
    type :: namelist_scan
        !> The file scanned.
        character(len=:), allocatable :: file
        !> Groups and assignments in the order of the file.
        type(namelist_entry), allocatable :: entries(:)
    contains
        !> Line of a group (variable '') or of a variable's first assignment; 0 when absent.
        procedure :: line_of
        !> Whether the file assigns a variable of a group, or (variable '') holds the group.
        procedure :: has_value
        !> The first value given to a variable (a text without quotes); '' when absent.
        procedure :: value_of
    end type namelist_scan

    !> One token of the file.
    type :: token_type
        integer :: kind = token_end
        !> Text: a word as written, a group name in lower case, a text without its quotes.
        character(len=:), allocatable :: text
        integer :: line = 0
        !> For a text: whether its closing quote was found on the same line.
        logical :: closed = .true.
    end type token_type

    !> Where the scan is: the file, the group being read and the tokens.
    type :: scan_state
        character(len=:), allocatable :: path
        type(token_type), allocatable :: tokens(:)
        integer :: next = 1
    end type scan_state

contains

    !> Scan a namelist file, read into memory, against the groups and variables it may hold.
    subroutine scan_namelist(path, lines, groups, scan, error)
        !> The file (for messages).
        character(len=*), intent(in) :: path
        !> Its lines (greenconv_io_columns's read_lines).
        character(len=*), intent(in) :: lines(:)
        !> The groups a file may hold.
        type(namelist_group), intent(in) :: groups(:)
        !> The groups and assignments found, with their lines.
        type(namelist_scan), intent(out) :: scan
        !> Set (one line: file, line, group, variable, expected and found) at the first mistake.
        type(error_type), allocatable, intent(out) :: error

        type(scan_state) :: state
        integer :: g

        scan%file = path
        allocate (scan%entries(0))
        state%path = path
        call tokenise(lines, state%tokens)
        do
            associate (token => state%tokens(state%next))
                select case (token%kind)
                case (token_end)
                    return
                case (token_group)
                    call open_group(state, groups, scan, g, error)
                    if (.not. allocated(error)) call scan_group(state, groups(g), scan, error)
                case default
                    call fatal_error(error, state%path//':'//int_text(token%line) &
                                     //": expected a group '&name ... /' or a comment '! ...', found '" &
                                     //shown(token)//"'")
                end select
            end associate
            if (allocated(error)) return
        end do
    end subroutine scan_namelist

    !> The `&name` token: a known group, not seen before.
    subroutine open_group(state, groups, scan, g, error)
        type(scan_state), intent(inout) :: state
        type(namelist_group), intent(in) :: groups(:)
        type(namelist_scan), intent(inout) :: scan
        integer, intent(out) :: g
        type(error_type), allocatable, intent(out) :: error

        character(len=name_width) :: names(size(groups))
        type(namelist_entry) :: entry
        integer :: i

        associate (token => state%tokens(state%next))
            g = 0
            do i = 1, size(groups)
                names(i) = groups(i)%name
                if (groups(i)%name == token%text) g = i
            end do
            if (g == 0) then
                call fatal_error(error, state%path//':'//int_text(token%line)//': &'//token%text &
                                 //': expected a group '//listed(names, '&')//", found '&"//token%text//"'" &
                                 //suggestion(token%text, names, '&'))
                return
            end if
            if (scan%has_value(token%text, '')) then
                call fatal_error(error, state%path//':'//int_text(token%line)//': &'//token%text &
                                 //': expected each group once, found it again (first on line ' &
                                 //int_text(scan%line_of(token%text, ''))//')')
                return
            end if
            entry%group = token%text
            entry%line = token%line
        end associate
        entry%variable = ''
        entry%key = ''
        entry%value = ''
        call add_entry(scan, entry)
        state%next = state%next + 1
    end subroutine open_group

    !> The body of a group, up to and including its `/`.
    subroutine scan_group(state, group, scan, error)
        type(scan_state), intent(inout) :: state
        type(namelist_group), intent(in) :: group
        type(namelist_scan), intent(inout) :: scan
        type(error_type), allocatable, intent(out) :: error

        character(len=:), allocatable :: where

        where = state%path//':'//int_text(scan%line_of(group%name, ''))//': &'//group%name
        do
            associate (token => state%tokens(state%next), after => state%tokens(state%next + 1))
                select case (token%kind)
                case (token_slash)
                    state%next = state%next + 1
                    return
                case (token_group)
                    if (token%text == 'end') then
                        state%next = state%next + 1
                        return
                    end if
                    call fatal_error(error, where//": expected '/' to close the group, found '&"//token%text &
                                     //"' on line "//int_text(token%line))
                case (token_end)
                    call fatal_error(error, where//": expected '/' to close the group, found the end of the file")
                case (token_comma)
                    state%next = state%next + 1
                case (token_word)
                    if (after%kind == token_equals) then
                        call scan_assignment(state, group, scan, error)
                    else
                        call fatal_error(error, state%path//':'//int_text(token%line)//': &'//group%name//' ' &
                                         //token%text//": expected 'variable = value', found '"//token%text//"'")
                    end if
                case default
                    call fatal_error(error, state%path//':'//int_text(token%line)//': &'//group%name &
                                     //": expected a variable name, found '"//shown(token)//"'")
                end select
            end associate
            if (allocated(error)) return
        end do
    end subroutine scan_group

    !> `name[(index)] = values`: a known variable, assigned once, with values of its kind.
    subroutine scan_assignment(state, group, scan, error)
        type(scan_state), intent(inout) :: state
        type(namelist_group), intent(in) :: group
        type(namelist_scan), intent(inout) :: scan
        type(error_type), allocatable, intent(out) :: error

        type(namelist_entry) :: entry
        character(len=:), allocatable :: where
        integer :: v, first_index, n_values

        associate (name => state%tokens(state%next))
            entry%group = group%name
            entry%line = name%line
            entry%key = lower_text(name%text)
            entry%variable = entry%key
            if (index(entry%key, '(') > 0) entry%variable = entry%key(:index(entry%key, '(') - 1)
            where = state%path//':'//int_text(name%line)//': &'//group%name//' '//entry%variable//': '
        end associate
        v = variable_index(group, entry%variable)
        if (v == 0) then
            call unknown_variable(where, group, entry%variable, error)
            return
        end if
        call element_index(where, group%variables(v), entry%key, first_index, error)
        if (allocated(error)) return
        call check_repeat(where, scan, entry, error)
        if (allocated(error)) return
        state%next = state%next + 2
        call scan_values(state, group, group%variables(v), entry, n_values, error)
        if (allocated(error)) return
        if (n_values == 0) then
            call fatal_error(error, where//'expected '//kind_text(group%variables(v)%kind)//', found no value')
        else if (first_index + n_values - 1 > group%variables(v)%size) then
            if (group%variables(v)%size == 1) then
                call fatal_error(error, where//'expected one value, found '//int_text(n_values))
            else
                call fatal_error(error, where//'expected at most '//int_text(group%variables(v)%size) &
                                 //' values, found '//int_text(first_index + n_values - 1))
            end if
        end if
        if (.not. allocated(error)) call add_entry(scan, entry)
    end subroutine scan_assignment

    !> The values of one assignment, up to the next `name =`, `/`, `&` or the end; each
    !> checked against the variable's kind. The first is kept in entry%value.
    subroutine scan_values(state, group, variable, entry, n_values, error)
        type(scan_state), intent(inout) :: state
        type(namelist_group), intent(in) :: group
        type(namelist_variable), intent(in) :: variable
        type(namelist_entry), intent(inout) :: entry
        integer, intent(out) :: n_values
        type(error_type), allocatable, intent(out) :: error

        character(len=:), allocatable :: problem
        type(token_type) :: value
        integer :: repeat

        n_values = 0
        entry%value = ''
        do
            if (.not. is_value(state, state%next)) then
                if (state%tokens(state%next)%kind /= token_comma) return
                state%next = state%next + 1
                cycle
            end if
            call repeated_value(state, value, repeat, problem)
            if (len(problem) == 0 .and. value%kind /= token_end) call kind_problem(variable%kind, value, problem)
            if (len(problem) > 0) then
                call fatal_error(error, state%path//':'//int_text(value%line)//': &'//group%name//' ' &
                                 //variable%name//': '//problem)
                return
            end if
            if (n_values == 0 .and. value%kind /= token_end) entry%value = value%text
            n_values = n_values + repeat
        end do
    end subroutine scan_values

    !> The value at state%next, with its repeat count `r*value` (r = 1 when none); a null
    !> value `r*` comes back as a token of kind token_end. Advances past it.
    subroutine repeated_value(state, value, repeat, problem)
        type(scan_state), intent(inout) :: state
        type(token_type), intent(out) :: value
        integer, intent(out) :: repeat
        character(len=:), allocatable, intent(out) :: problem

        integer :: star
        logical :: ok

        problem = ''
        repeat = 1
        value = state%tokens(state%next)
        state%next = state%next + 1
        if (value%kind /= token_word) return
        star = index(value%text, '*')
        if (star < 2) return
        if (.not. is_integer(value%text(:star - 1))) return
        call read_integer(value%text(:star - 1), repeat, ok)
        if (.not. ok .or. repeat < 1) then
            problem = "expected a repeat count >= 1 before '*', found '"//value%text//"'"
            return
        end if
        if (star < len(value%text)) then
            value%text = value%text(star + 1:)
        else if (is_value(state, state%next) .and. state%tokens(state%next)%line == value%line) then
            value = state%tokens(state%next)
            state%next = state%next + 1
        else
            value%kind = token_end
        end if
    end subroutine repeated_value

    !> Whether the token at position i is a value: a text, or a word not followed by `=`.
    pure logical function is_value(state, i)
        type(scan_state), intent(in) :: state
        integer, intent(in) :: i

        is_value = state%tokens(i)%kind == token_text
        if (state%tokens(i)%kind == token_word) is_value = state%tokens(i + 1)%kind /= token_equals
    end function is_value

    !> What is wrong with a value for a variable of this kind; '' when it fits.
    subroutine kind_problem(kind, value, problem)
        integer, intent(in) :: kind
        type(token_type), intent(in) :: value
        character(len=:), allocatable, intent(out) :: problem

        problem = ''
        if (value%kind == token_text .and. .not. value%closed) then
            problem = 'expected a closing quote on the same line, found '//value%text
        else if (kind == value_text .or. kind == value_text_list) then
            if (value%kind /= token_text) problem = "expected a text in quotes, found '"//value%text &
                                                    //"' without quotes"
        else if (value%kind == token_text) then
            problem = 'expected '//kind_text(kind)//", found the text '"//value%text//"'"
        else if (kind == value_real .or. kind == value_integer) then
            call number_problem(kind, value%text, problem)
        else if (.not. is_logical(value%text)) then
            problem = "expected .true. or .false., found '"//value%text//"'"
        end if
    end subroutine kind_problem

    !> What is wrong with a word given as a real (a finite double) or an integer (a default
    !> integer); '' when it fits.
    subroutine number_problem(kind, word, problem)
        integer, intent(in) :: kind
        character(len=*), intent(in) :: word
        character(len=:), allocatable, intent(out) :: problem

        real(dp) :: real_value
        integer :: integer_value
        logical :: ok

        problem = ''
        if (kind == value_real) then
            if (is_nan_or_inf(word)) then
                problem = "expected a finite real number, found '"//word//"'"
            else if (.not. is_number(word)) then
                problem = "expected a real number, found '"//word//"'"
            else
                call read_real(word, real_value, ok)
                if (.not. ok) problem = 'expected a real number within double precision (|x| < 1.8e308), ' &
                                        //"found '"//word//"'"
            end if
        else if (.not. is_integer(word)) then
            problem = "expected an integer, found '"//word//"'"
        else
            call read_integer(word, integer_value, ok)
            if (.not. ok) problem = 'expected an integer within +-'//int_text(huge(integer_value))//", found '" &
                                    //word//"'"
        end if
    end subroutine number_problem

    !> Whether a word is a logical value: t, f, true, false, with or without periods.
    pure logical function is_logical(word)
        character(len=*), intent(in) :: word

        character(len=8), parameter :: spellings(8) = [character(len=8) :: 't', 'f', '.t.', '.f.', 'true', &
                                                       'false', '.true.', '.false.']

        is_logical = any(lower_text(word) == spellings)
    end function is_logical

    !> What a value of this kind is, for messages.
    pure function kind_text(kind) result(text)
        integer, intent(in) :: kind
        character(len=len_trim(kind_texts(kind))) :: text

        text = kind_texts(kind)
    end function kind_text

    !> The index of `name(i)` (1 without a subscript): a scalar takes none, an array 1..size.
    subroutine element_index(where, variable, key, first, error)
        character(len=*), intent(in) :: where, key
        type(namelist_variable), intent(in) :: variable
        integer, intent(out) :: first
        type(error_type), allocatable, intent(out) :: error

        character(len=:), allocatable :: subscript
        logical :: ok

        first = 1
        if (index(key, '(') == 0) return
        subscript = key(index(key, '(') + 1:)
        if (index(subscript, ')') == len(subscript)) subscript = subscript(:len(subscript) - 1)
        subscript = trim(adjustl(subscript))
        if (variable%size == 1) then
            call fatal_error(error, where//"expected a scalar without a subscript, found '"//key//"'")
            return
        end if
        ok = is_integer(subscript)
        if (ok) call read_integer(subscript, first, ok)
        if (.not. ok .or. first < 1 .or. first > variable%size) then
            call fatal_error(error, where//'expected an index from 1 to '//int_text(variable%size)//", found '" &
                             //key//"'")
        end if
    end subroutine element_index

    !> A variable (or element) assigned a second time in one group is refused.
    subroutine check_repeat(where, scan, entry, error)
        character(len=*), intent(in) :: where
        type(namelist_scan), intent(in) :: scan
        type(namelist_entry), intent(in) :: entry
        type(error_type), allocatable, intent(out) :: error

        integer :: i

        do i = 1, size(scan%entries)
            if (scan%entries(i)%group == entry%group .and. scan%entries(i)%key == entry%key) then
                call fatal_error(error, where//'expected one assignment per group, found a second (first on line ' &
                                 //int_text(scan%entries(i)%line)//')')
                return
            end if
        end do
    end subroutine check_repeat

    !> An unknown variable: list the group's, and suggest the closest.
    subroutine unknown_variable(where, group, name, error)
        character(len=*), intent(in) :: where, name
        type(namelist_group), intent(in) :: group
        type(error_type), allocatable, intent(out) :: error

        character(len=name_width) :: names(size(group%variables))
        integer :: i

        do i = 1, size(group%variables)
            names(i) = group%variables(i)%name
        end do
        call fatal_error(error, where//'expected a variable of &'//group%name//' ('//listed(names, '')//"), found '" &
                         //name//"'"//suggestion(name, names, ''))
    end subroutine unknown_variable

    !> Position of a variable in its group; 0 when unknown.
    pure integer function variable_index(group, name)
        type(namelist_group), intent(in) :: group
        character(len=*), intent(in) :: name

        integer :: i

        variable_index = 0
        do i = 1, size(group%variables)
            if (group%variables(i)%name == name) variable_index = i
        end do
    end function variable_index

    !> `a, b, c or d` (each name after `prefix`), or `a, b, c` without a prefix.
    pure function listed(names, prefix) result(text)
        character(len=*), intent(in) :: names(:), prefix
        character(len=size(names)*len(prefix) + sum(len_trim(names)) + 2*(size(names) - 1) &
                      + merge(2, 0, size(names) > 1 .and. len(prefix) > 0)) :: text

        integer :: i, n

        text = prefix//trim(names(1))
        n = len(prefix) + len_trim(names(1))
        do i = 2, size(names)
            if (i == size(names) .and. len(prefix) > 0) then
                text(n + 1:) = ' or '//prefix//trim(names(i))
                n = n + 4
            else
                text(n + 1:) = ', '//prefix//trim(names(i))
                n = n + 2
            end if
            n = n + len(prefix) + len_trim(names(i))
        end do
    end function listed

    !> The index of the name closest to `name` by edit distance when close enough (at most 2
    !> edits, or a third of the name); 0 otherwise.
    pure integer function closest_name(name, names)
        character(len=*), intent(in) :: name, names(:)

        integer :: i, best, distance, best_distance

        best = 0
        best_distance = huge(best)
        do i = 1, size(names)
            distance = edit_distance(name, trim(names(i)))
            if (distance < best_distance) then
                best = i
                best_distance = distance
            end if
        end do
        closest_name = 0
        if (best > 0 .and. best_distance <= max(2, len(name)/3)) closest_name = best
    end function closest_name

    !> Length of `suggestion(name, names, prefix)`: 0 when no name is close enough.
    pure integer function suggestion_length(name, names, prefix)
        character(len=*), intent(in) :: name, names(:), prefix

        integer :: best

        suggestion_length = 0
        best = closest_name(name, names)
        if (best > 0) suggestion_length = 18 + len(prefix) + len_trim(names(best))
    end function suggestion_length

    !> `; did you mean 'x'?` for the name closest to `name` by edit distance, when close
    !> enough (at most 2 edits, or a third of the name); '' otherwise.
    pure function suggestion(name, names, prefix) result(text)
        character(len=*), intent(in) :: name, names(:), prefix
        character(len=suggestion_length(name, names, prefix)) :: text

        integer :: best

        best = closest_name(name, names)
        if (best > 0) text = "; did you mean '"//prefix//trim(names(best))//"'?"
    end function suggestion

    !> Levenshtein distance: the fewest insertions, deletions and substitutions from a to b.
    pure integer function edit_distance(a, b)
        character(len=*), intent(in) :: a, b

        integer :: row(0:len(b)), diagonal, above, i, j

        row = [(j, j=0, len(b))]
        do i = 1, len(a)
            diagonal = row(0)
            row(0) = i
            do j = 1, len(b)
                above = row(j)
                row(j) = min(row(j) + 1, row(j - 1) + 1, diagonal + merge(0, 1, a(i:i) == b(j:j)))
                diagonal = above
            end do
        end do
        edit_distance = row(len(b))
    end function edit_distance

    !> Length of `shown(token)`.
    pure integer function shown_length(token)
        type(token_type), intent(in) :: token

        select case (token%kind)
        case (token_text)
            shown_length = len(token%text) + 2
        case (token_equals, token_comma, token_slash)
            shown_length = 1
        case (token_group)
            shown_length = len(token%text) + 1
        case default
            shown_length = len(token%text)
        end select
    end function shown_length

    !> A token as the user wrote it, for messages.
    pure function shown(token) result(text)
        type(token_type), intent(in) :: token
        character(len=shown_length(token)) :: text

        select case (token%kind)
        case (token_text)
            text = '"'//token%text//'"'
        case (token_equals)
            text = '='
        case (token_comma)
            text = ','
        case (token_slash)
            text = '/'
        case (token_group)
            text = '&'//token%text
        case default
            text = token%text
        end select
    end function shown

    !> Append an entry.
    pure subroutine add_entry(scan, entry)
        type(namelist_scan), intent(inout) :: scan
        type(namelist_entry), intent(in) :: entry

        type(namelist_entry), allocatable :: longer(:)
        integer :: n

        n = size(scan%entries)
        allocate (longer(n + 1))
        longer(1:n) = scan%entries
        longer(n + 1) = entry
        call move_alloc(longer, scan%entries)
    end subroutine add_entry

    !> Split the lines of a file into tokens, ending with one token_end (and a spare one for
    !> look-ahead).
    pure subroutine tokenise(lines, tokens)
        character(len=*), intent(in) :: lines(:)
        type(token_type), allocatable, intent(out) :: tokens(:)

        integer :: line_number, n

        allocate (tokens(64))
        n = 0
        do line_number = 1, size(lines)
            call tokenise_line(trim(lines(line_number)), line_number, tokens, n)
        end do
        call push(tokens, n, token_type(kind=token_end, text='', line=size(lines)))
        call push(tokens, n, token_type(kind=token_end, text='', line=size(lines)))
        tokens = tokens(1:n)
    end subroutine tokenise

    !> Append the tokens of one line.
    pure subroutine tokenise_line(line, line_number, tokens, n)
        character(len=*), intent(in) :: line
        integer, intent(in) :: line_number
        type(token_type), allocatable, intent(inout) :: tokens(:)
        integer, intent(inout) :: n

        character(len=*), parameter :: blanks = ' '//achar(9)//achar(13)
        type(token_type) :: token
        integer :: i, last

        i = 1
        do while (i <= len(line))
            if (index(blanks, line(i:i)) > 0) then
                i = i + 1
                cycle
            end if
            if (line(i:i) == '!') exit
            token = token_type(kind=token_word, text='', line=line_number)
            select case (line(i:i))
            case ('=')
                token%kind = token_equals
                last = i
            case (',', ';')
                token%kind = token_comma
                last = i
            case ('/')
                token%kind = token_slash
                last = i
            case ('&', '$')
                token%kind = token_group
                last = name_end(line, i + 1)
                token%text = lower_text(line(i + 1:last))
            case ('''', '"')
                call quoted(line, i, token, last)
            case default
                last = word_end(line, i)
                token%text = line(i:last)
            end select
            call push(tokens, n, token)
            i = last + 1
        end do
    end subroutine tokenise_line

    !> Last position of a name (letters, digits, underscores) starting at `first`.
    pure integer function name_end(line, first)
        character(len=*), intent(in) :: line
        integer, intent(in) :: first

        name_end = first - 1
        do while (name_end < len(line))
            if (verify(line(name_end + 1:name_end + 1), &
                       'abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_') /= 0) exit
            name_end = name_end + 1
        end do
    end function name_end

    !> Last position of a word starting at `first`: up to a blank, separator, `=`, `/`, `!`,
    !> quote or `&`, taking a parenthesised subscript whole.
    pure integer function word_end(line, first)
        character(len=*), intent(in) :: line
        integer, intent(in) :: first

        character(len=*), parameter :: stops = ' ,;=/!''"&'//achar(9)//achar(13)
        integer :: depth

        depth = 0
        word_end = first - 1
        do while (word_end < len(line))
            associate (c => line(word_end + 1:word_end + 1))
                if (depth == 0 .and. index(stops, c) > 0) exit
                if (c == '(') depth = depth + 1
                if (c == ')') depth = max(0, depth - 1)
            end associate
            word_end = word_end + 1
        end do
    end function word_end

    !> A text starting with the quote at `first`: up to the matching quote, a doubled quote
    !> standing for one; not closed when the line ends first.
    pure subroutine quoted(line, first, token, last)
        character(len=*), intent(in) :: line
        integer, intent(in) :: first
        type(token_type), intent(inout) :: token
        integer, intent(out) :: last

        character :: quote
        integer :: i

        quote = line(first:first)
        token%kind = token_text
        token%text = ''
        i = first + 1
        do while (i <= len(line))
            if (line(i:i) == quote) then
                if (i == len(line)) exit
                if (line(i + 1:i + 1) /= quote) exit
                i = i + 1
            end if
            token%text = token%text//line(i:i)
            i = i + 1
        end do
        token%closed = i <= len(line)
        if (.not. token%closed) token%text = line(first:)
        last = min(i, len(line))
    end subroutine quoted

    !> Append a token, growing the storage by doubling.
    pure subroutine push(tokens, n, token)
        type(token_type), allocatable, intent(inout) :: tokens(:)
        integer, intent(inout) :: n
        type(token_type), intent(in) :: token

        type(token_type), allocatable :: longer(:)

        if (n == size(tokens)) then
            allocate (longer(2*n))
            longer(1:n) = tokens
            call move_alloc(longer, tokens)
        end if
        n = n + 1
        tokens(n) = token
    end subroutine push

    !> Line of a group (variable '') or of a variable's first assignment; 0 when absent.
    pure integer function line_of(self, group, variable)
        !> The scan.
        class(namelist_scan), intent(in) :: self
        !> Group name, lower case.
        character(len=*), intent(in) :: group
        !> Variable name, lower case, without subscript; '' for the group.
        character(len=*), intent(in) :: variable

        integer :: i

        line_of = 0
        i = first_entry(self, group, variable)
        if (i > 0) line_of = self%entries(i)%line
    end function line_of

    !> Whether the file assigns a variable of a group, or, for variable '', holds the group.
    pure logical function has_value(self, group, variable)
        !> The scan.
        class(namelist_scan), intent(in) :: self
        !> Group name, lower case.
        character(len=*), intent(in) :: group
        !> Variable name, lower case; '' for the group itself.
        character(len=*), intent(in) :: variable

        has_value = self%line_of(group, variable) > 0
    end function has_value

    !> Index of the first entry giving a value to `group`'s `variable`; 0 when none does.
    pure integer function first_entry(self, group, variable)
        class(namelist_scan), intent(in) :: self
        character(len=*), intent(in) :: group, variable

        integer :: i

        first_entry = 0
        if (.not. allocated(self%entries)) return
        do i = 1, size(self%entries)
            if (self%entries(i)%group == group .and. self%entries(i)%variable == variable) then
                first_entry = i
                return
            end if
        end do
    end function first_entry

    !> Length of `value_of(self, group, variable)`.
    pure integer function value_length(self, group, variable)
        class(namelist_scan), intent(in) :: self
        character(len=*), intent(in) :: group, variable

        integer :: i

        value_length = 0
        i = first_entry(self, group, variable)
        if (i > 0) value_length = len_trim(adjustl(self%entries(i)%value))
    end function value_length

    !> The first value given to a variable, a text without its quotes, trimmed; '' when absent.
    pure function value_of(self, group, variable) result(value)
        !> The scan.
        class(namelist_scan), intent(in) :: self
        !> Group name, lower case.
        character(len=*), intent(in) :: group
        !> Variable name, lower case.
        character(len=*), intent(in) :: variable
        character(len=value_length(self, group, variable)) :: value

        integer :: i

        i = first_entry(self, group, variable)
        if (i > 0) value = adjustl(self%entries(i)%value)
    end function value_of

end module greenconv_scene_scan
