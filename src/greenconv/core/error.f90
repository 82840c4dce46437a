!> Error reporting without `stop`: library procedures return an allocated
!> `error_type` when they fail, and the caller tests `allocated(error)`.
module greenconv_core_error
    implicit none
    private

    public :: error_type, fatal_error
    public :: stat_input, stat_numerical, stat_accuracy

    !> Status code of a bad input (file, namelist, value): the driver exits with it.
    integer, parameter :: stat_input = 2
    !> Status code of a numerical failure (overflow, divergence, failed fit).
    integer, parameter :: stat_numerical = 3
    !> Status code of a run that ended and wrote all its output, but with a method whose own
    !> accuracy estimate exceeds the accuracy asked (a scene's `&convolution accuracy`): the
    !> results are there, and the summary says how far off they may be. Statuses 2 and 3 win
    !> over it.
    integer, parameter :: stat_accuracy = 4

    !> What went wrong: a status code and one line of text for the user.
    type :: error_type
        !> Status code, `stat_input`, `stat_numerical` or `stat_accuracy`.
        integer :: stat = stat_input
        !> One line naming the file, group or variable, what was expected and what was found.
        character(len=:), allocatable :: message
    end type error_type

contains

    !> Allocate `error` with a message and a status code (default `stat_input`).
    pure subroutine fatal_error(error, message, stat)
        !> The error to create; allocated on return.
        type(error_type), allocatable, intent(out) :: error
        !> The message for the user.
        character(len=*), intent(in) :: message
        !> Status code; `stat_input` when absent.
        integer, intent(in), optional :: stat

        allocate (error)
        error%message = message
        if (present(stat)) error%stat = stat
    end subroutine fatal_error

end module greenconv_core_error
