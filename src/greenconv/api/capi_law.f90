!> The C interface's contact law, `gc_law` (include/greenconv.h): an opaque handle on a law of
!> the registry (greenconv_contact_laws) made by name and parameter values, freed by
!> gc_law_free, evaluated by gc_law_force and gc_law_compression, and given to the contact
!> doors (gc_run_contact_law, gc_contact_start_law, gc_contact_step_law, the multi-point
!> gc_multi_run_contact_law and gc_multi_contact_start_law). A `gc_law *` is the C address of
!> a `law_box`. The doors that take (k_c, p) are the law doors with a power law
!> (capi_aliases.c), which `greenconv_law_for_door` makes for them unchecked, so that the law
!> door checks it and its messages name the (k_c, p) door as before.
module greenconv_capi_law
    use, intrinsic :: iso_c_binding, only: c_int, c_double, c_size_t, c_ptr, c_null_ptr, c_associated, &
                                           c_f_pointer, c_loc
    use greenconv_core_kinds, only: dp
    use greenconv_core_error, only: error_type, fatal_error, stat_input
    use greenconv_core_text, only: int_text
    use greenconv_contact_laws, only: contact_law, power_law, new_law, new_laws, max_law_parameters
    use greenconv_api_doors, only: finish, from_c, put, need_pointer
    implicit none
    private

    public :: law_box, law_at, door_name, laws_at
    public :: gc_law_new, gc_law_free, gc_law_force, gc_law_compression, greenconv_law_for_door

    !> What a `gc_law *` points to.
    type :: law_box
        !> The law.
        class(contact_law), allocatable :: law
        !> The name a door's messages give instead of its own ('' for its own): the (k_c, p)
        !> door a power law was made for.
        character(len=:), allocatable :: door
    end type law_box

contains

    !> The box behind a `gc_law *` (null for NULL).
    function law_at(handle) result(box)
        !> A `gc_law *`, or NULL.
        type(c_ptr), intent(in) :: handle
        !> Its box.
        type(law_box), pointer :: box

        box => null()
        if (c_associated(handle)) call c_f_pointer(handle, box)
    end function law_at

    !> The name a door's messages give: the door a law was made for, else the door's own (a
    !> subroutine: a deferred-length function result would keep its length in static storage).
    subroutine door_name(box, own, name)
        !> The law's box, or null.
        type(law_box), pointer, intent(in) :: box
        !> The door's own name.
        character(len=*), intent(in) :: own
        !> The name.
        character(len=:), allocatable, intent(out) :: name

        name = own
        if (associated(box)) then
            if (allocated(box%door)) name = box%door
        end if
    end subroutine door_name

    !> The laws of n points from a C array of n `gc_law *` (one law, parameters free per point),
    !> an array of one dynamic type as the steppers take it, and the name the door's messages
    !> give; status 2 naming the point for a NULL handle or a law other than the first point's.
    !> Power laws made for a (k_c, p) door (`greenconv_law_for_door`) stay unchecked, the door's
    !> own check of each point's law then speaking as the (k_c, p) door always has.
    subroutine laws_at(caller, handles, n, laws, name, error)
        !> Name of the door, first word of a message.
        character(len=*), intent(in) :: caller
        !> The C array `const gc_law *const *laws` (checked not NULL by the caller).
        type(c_ptr), intent(in) :: handles
        !> Number of points.
        integer, intent(in) :: n
        !> The laws; unallocated on error.
        class(contact_law), allocatable, intent(out) :: laws(:)
        !> The name the door's messages give: the (k_c, p) door the laws were made for, else `caller`.
        character(len=:), allocatable, intent(out) :: name
        !> Set for a NULL handle or mixed laws.
        type(error_type), allocatable, intent(out) :: error

        type(c_ptr), pointer :: addresses(:)
        type(law_box), pointer :: box
        character(len=:), allocatable :: law_name
        real(dp), allocatable :: values(:, :)
        real(dp), allocatable :: point_values(:)
        integer :: i

        name = caller
        law_name = ''
        call c_f_pointer(handles, addresses, [n])
        do i = 1, n
            box => law_at(addresses(i))
            if (.not. associated(box)) then
                call fatal_error(error, caller//': laws['//int_text(i - 1)//'] is NULL: pass a law made by ' &
                                 //'gc_law_new for every point')
                return
            end if
            if (i == 1) then
                call door_name(box, caller, name)
                law_name = trim(box%law%name())
                point_values = box%law%parameters()
                allocate (values(size(point_values), n))
            else if (box%law%name() /= law_name) then
                call fatal_error(error, caller//': laws['//int_text(i - 1)//"] is a law '"//trim(box%law%name()) &
                                 //"', laws[0] a law '"//law_name//"': give every point the same law (its " &
                                 //'parameters may differ)')
                return
            end if
            values(:, i) = box%law%parameters()
        end do
        if (name /= caller) then
            allocate (laws, source=contact_law(values(1, :), values(2, :)))
            return
        end if
        call new_laws(law_name, values, laws, error)
        if (allocated(error)) error%message = caller//': '//error%message
    end subroutine laws_at

    !> int gc_law_new(const char *name, const double *parameters, int n_parameters,
    !> gc_law **law, char *errmsg, size_t errmsg_len): a contact law of the registry by name
    !> ("power": k_c [N/m^p], p; "exponential": F_s [N], delta_s [m]); status 2 naming the
    !> parameter, its unit and range for a bad value, *law then NULL.
    function gc_law_new(name, parameters, n_parameters, law, errmsg, errmsg_len) bind(c, name='gc_law_new') &
        result(status)
        !> The law's name, NUL-terminated.
        type(c_ptr), value, intent(in) :: name
        !> Its parameter values, n_parameters of them, in the registry's order and SI units.
        type(c_ptr), value, intent(in) :: parameters
        !> Number of parameter values.
        integer(c_int), value, intent(in) :: n_parameters
        !> Where the new `gc_law *` goes (NULL on failure).
        type(c_ptr), value, intent(in) :: law
        !> Message buffer, or NULL.
        type(c_ptr), value, intent(in) :: errmsg
        !> Size of the message buffer [bytes].
        integer(c_size_t), value, intent(in) :: errmsg_len
        integer(c_int) :: status

        character(len=*), parameter :: caller = 'gc_law_new'
        type(error_type), allocatable :: error
        type(c_ptr), pointer :: handle
        real(c_double), pointer :: values(:)
        type(law_box), pointer :: box

        call need_pointer(caller, law, 'law', 'pass the address of a gc_law *', error)
        if (.not. allocated(error)) then
            call c_f_pointer(law, handle)
            handle = c_null_ptr
        end if
        call need_pointer(caller, name, 'name', 'pass a law''s name, e.g. "power"', error)
        if (.not. allocated(error) .and. (n_parameters < 0 .or. n_parameters > max_law_parameters)) then
            call fatal_error(error, caller//': n_parameters = '//int_text(int(n_parameters))//': give 0 to ' &
                             //int_text(max_law_parameters)//' values')
        end if
        if (n_parameters > 0) call need_pointer(caller, parameters, 'parameters', 'pass n_parameters values', error)
        if (allocated(error)) then
            status = finish(error, errmsg, errmsg_len)
            return
        end if
        allocate (box)
        if (n_parameters > 0) then
            call c_f_pointer(parameters, values, [n_parameters])
            call new_law(from_c(name), values, box%law, error)
        else
            call new_law(from_c(name), [real(dp) ::], box%law, error)
        end if
        if (allocated(error)) then
            error%message = caller//': '//error%message
            deallocate (box)
        else
            handle = c_loc(box)
        end if
        status = finish(error, errmsg, errmsg_len)
    end function gc_law_new

    !> void gc_law_free(gc_law *law): free a law (NULL: nothing).
    subroutine gc_law_free(law) bind(c, name='gc_law_free')
        !> The law, or NULL.
        type(c_ptr), value, intent(in) :: law

        type(law_box), pointer :: box

        box => law_at(law)
        if (associated(box)) deallocate (box)
    end subroutine gc_law_free

    !> int gc_law_force(const gc_law *law, double compression, double *force): the force
    !> F(delta) [N] at a compression delta [m] (0 for delta <= 0); status 2 for NULL.
    function gc_law_force(law, compression, force) bind(c, name='gc_law_force') result(status)
        !> The law.
        type(c_ptr), value, intent(in) :: law
        !> Compression delta [m].
        real(c_double), value, intent(in) :: compression
        !> Where F [N] goes.
        type(c_ptr), value, intent(in) :: force
        integer(c_int) :: status

        status = evaluate(law, compression, force, .false.)
    end function gc_law_force

    !> int gc_law_compression(const gc_law *law, double force, double *compression): the
    !> compression delta [m] that carries a force F >= 0 [N] (the static compression under a
    !> preload); status 2 for NULL or F < 0.
    function gc_law_compression(law, force, compression) bind(c, name='gc_law_compression') result(status)
        !> The law.
        type(c_ptr), value, intent(in) :: law
        !> Force F [N], >= 0.
        real(c_double), value, intent(in) :: force
        !> Where delta [m] goes.
        type(c_ptr), value, intent(in) :: compression
        integer(c_int) :: status

        status = evaluate(law, force, compression, .true.)
    end function gc_law_compression

    !> A law's force at a compression, or (`inverse`) its compression under a force >= 0, stored
    !> at a C `double *`: 0, or 2 for a NULL law or output or a negative force.
    function evaluate(law, given, result_address, inverse) result(status)
        !> The law, a `const gc_law *`.
        type(c_ptr), intent(in) :: law
        !> The compression delta [m], or (`inverse`) the force F [N].
        real(c_double), intent(in) :: given
        !> Where F [N], or (`inverse`) delta [m], goes.
        type(c_ptr), intent(in) :: result_address
        !> Whether the law is inverted: delta(F) instead of F(delta).
        logical, intent(in) :: inverse
        integer(c_int) :: status

        type(law_box), pointer :: box

        box => law_at(law)
        status = stat_input
        if (.not. (associated(box) .and. c_associated(result_address))) return
        if (inverse) then
            if (.not. (given >= 0.0_c_double)) return
            call put(result_address, box%law%compression(real(given, dp)))
        else
            call put(result_address, box%law%force(real(given, dp)))
        end if
        status = 0
    end function evaluate

    !> int greenconv_law_for_door(const char *door, double k_c, double p, gc_law **law): the
    !> power law (k_c, p), unchecked, whose contact door names itself `door` in its messages:
    !> what the (k_c, p) doors of capi_aliases.c give their law door. Not in the header.
    function greenconv_law_for_door(door, k_c, p, law) bind(c, name='greenconv_law_for_door') result(status)
        !> The name of the (k_c, p) door, NUL-terminated.
        type(c_ptr), value, intent(in) :: door
        !> Contact stiffness k_c [N/m^p].
        real(c_double), value, intent(in) :: k_c
        !> Contact exponent p.
        real(c_double), value, intent(in) :: p
        !> Where the new `gc_law *` goes.
        type(c_ptr), value, intent(in) :: law
        integer(c_int) :: status

        type(c_ptr), pointer :: handle
        type(law_box), pointer :: box

        status = stat_input
        if (.not. (c_associated(law) .and. c_associated(door))) return
        call c_f_pointer(law, handle)
        allocate (box)
        allocate (box%law, source=power_law(stiffness=k_c, exponent=p))
        box%door = from_c(door)
        handle = c_loc(box)
        status = 0
    end function greenconv_law_for_door

end module greenconv_capi_law
