!> The noise model from the data, the modes the data determine, and the identification's
!> limits and messages (greenconv_ident_mlfit, greenconv_scene_run_report, the C and F77 doors).
!>
!> Synthetic receptances with known noise: 3 modes to 500 Hz on 1025 lines (xi 0.01 to 0.04,
!> modal constants of both signs: test_mlfit_mod's case (c)), complex Gaussian noise of standard
!> deviation level*|G| (relative), floor (the same on every line) or both. The reference is
!> the Cramér-Rao bound of the true noise model, computed by test_mlfit_mod's cramer_rao from
!> the true modes (central differences, not the fit's Jacobian); the fit is judged by
!> test_outofband_mod's judge_fit: every determined mode within 5 sigma_CRB of a distinct
!> true mode, none invented, none missed that the data determine (sigma_xi/xi < 0.3 at the bound).
module test_identnoise_mod
    use, intrinsic :: iso_fortran_env, only: dp => real64
    use, intrinsic :: iso_c_binding, only: c_char, c_int, c_double, c_size_t, c_loc, c_null_char
    use testsuite_mod, only: test_error, unittest_type, new_unittest, check, note
    use greenconv_core_error, only: error_type, stat_input
    use greenconv_core_text, only: int_text
    use greenconv_core_random, only: random_stream
    use greenconv_model_modal_set, only: modal_set
    use greenconv_model_frf, only: frf_type, frf_from_modes, add_relative_noise
    use greenconv_ident_mlfit, only: ml_options, ml_result, identify_ml, max_lines
    use greenconv_ident_noise_model, only: band_bounds
    use greenconv_scene_read_input, only: scene_type
    use greenconv_io_files, only: make_directory
    use greenconv_scene_models_structure, only: build_structure
    use greenconv_scene_run_report, only: write_identification
    use greenconv_ident_structure, only: structure_model
    use greenconv_capi, only: gc_identify_ml_file
    use greenconv_legacy, only: gcidml
    use scene_text_mod, only: read_scene_text
    use test_mlfit_mod, only: cramer_rao, structure
    use test_outofband_mod, only: judge_fit
    implicit none
    private

    public :: collect_identnoise

    real(dp), parameter :: two_pi = 2.0_dp*3.141592653589793238462643383279_dp
    character(len=*), parameter :: dir = 'build/test_scratch'

contains

    !> Tests of the noise-model choice, the determined flag and the identification's limits.
    subroutine collect_identnoise(testsuite)
        type(unittest_type), allocatable, intent(out) :: testsuite(:)

        testsuite = [new_unittest('auto: relative, floor, both: the model chosen, modes within 5 CRB sigma', &
                                  test_choice), &
                     new_unittest('modes file: the determined column and count as the result says', test_modes_file), &
                     new_unittest('doors: gcidml and gc_identify_ml_file give the modes and flags of identify_ml', &
                                  test_doors), &
                     new_unittest('constant receptance: refused as having no resonance, status 2, file named', &
                                  test_constant), &
                     new_unittest('size: bands of a million lines; more than max_lines refused in one line', &
                                  test_size)]
    end subroutine collect_identnoise

    !> The 3 modes of the header, 60 to 320 Hz of a 500 Hz band.
    function three_modes() result(modes)
        type(modal_set) :: modes

        modes = structure([60.0_dp, 180.0_dp, 320.0_dp], [0.02_dp, 0.01_dp, 0.04_dp], &
                          1.0e-6_dp*[1.0_dp, -0.7_dp, 1.5_dp])
    end function three_modes

    !> `clean` with complex Gaussian noise: level*|G_l| (seed) and floor [m/N] (seed + 500).
    function noisy_copy(clean, level, floor, seed) result(noisy)
        type(frf_type), intent(in) :: clean
        real(dp), intent(in) :: level, floor
        integer, intent(in) :: seed
        type(frf_type) :: noisy

        type(random_stream) :: stream
        real(dp) :: radius, angle
        integer :: l

        noisy = clean
        if (level > 0.0_dp) call add_relative_noise(noisy, level, seed)
        stream = random_stream(seed + 500)
        do l = 1, noisy%n_freq()
            radius = sqrt(-2.0_dp*log(1.0_dp - stream%uniform()))
            angle = two_pi*stream%uniform()
            noisy%receptance(l) = noisy%receptance(l) + floor*sqrt(0.5_dp)*cmplx(radius*cos(angle), &
                                                                                 radius*sin(angle), dp)
        end do
    end function noisy_copy

    !> noise_model = 'auto' on three kinds of noise, one draw each (four identifications per draw
    !> in the debug build; more draws and the 12-mode structure at 0.1 % plus the floor are
    !> measured in doc/identification.md): 1 % of |G| ('relative'), a floor of 1e-3 of the peak
    !> |G| alone ('absolute'), 1 % of |G| plus that floor ('floor'). The model chosen must be the true one (the simpler is kept
    !> within the margin: 'floor' with s = 0 is 'relative'), noise_choice must quote the others'
    !> criteria, and judge_fit must pass against the bound of the true noise.
    subroutine test_choice(error)
        type(test_error), allocatable, intent(out) :: error

        character(len=8), parameter :: expected(3) = [character(len=8) :: 'relative', 'absolute', 'floor']
        character(len=8), parameter :: models(4) = [character(len=8) :: 'relative', 'absolute', 'floor', 'band']
        real(dp), parameter :: level(3) = [1.0e-2_dp, 0.0_dp, 1.0e-2_dp], floor_part(3) = [0.0_dp, 1.0e-3_dp, 1.0e-3_dp]
        type(modal_set) :: truth
        type(frf_type) :: clean
        type(ml_options) :: options
        type(ml_result) :: result
        type(error_type), allocatable :: failure
        real(dp), allocatable :: sigma_f(:), sigma_xi(:)
        character(len=80) :: text
        real(dp) :: floor
        integer :: case, seed, m

        truth = three_modes()
        clean = frf_from_modes(truth, 500.0_dp, 1025)
        options%noise_model = 'auto'
        do case = 1, size(expected)
            floor = floor_part(case)*maxval(abs(clean%receptance))
            call cramer_rao(truth, clean, level(case), sigma_f, sigma_xi, error, floor)
            if (allocated(error)) return
            do seed = 1, 1
                call identify_ml(noisy_copy(clean, level(case), floor, 10*case + seed), options, result, failure)
                if (allocated(failure)) call check(error, .false., failure%message)
                if (allocated(error)) return
                write (text, '(a,a,i0,a,a)') trim(expected(case)), ' noise, seed ', seed, ': chose ', &
                    trim(result%noise_model)
                call note(trim(text)//', '//result%noise_choice, real(count(result%determined), dp))
                call check(error, result%noise_model == expected(case), trim(text)//' ('//result%noise_choice//')')
                if (allocated(error)) return
                call check(error, index(result%noise_choice, 'likelihood') > 0 .and. all([(index(result%noise_choice, &
                           ' '//trim(models(m))//' ') > 0 .neqv. models(m) == expected(case), m=1, size(models))]), &
                           trim(text)//': the choice quotes the other models: '//result%noise_choice)
                if (allocated(error)) return
                call judge_fit(error, trim(text), truth, sigma_f, sigma_xi, result, determined_only=.true.)
                if (allocated(error)) return
            end do
        end do
    end subroutine test_choice

    !> A scene identifies a receptance file (1 % of |G|, noise_model 'relative'); the modes file
    !> read back holds one row per pole, its last column the result's determined flag, its header
    !> the count and the noise model, and the diagram's order-0 rows flag 3 or 4 alike. One flag
    !> turned off by hand (a pole the data do not determine) is written as 0 and 4.
    subroutine test_modes_file(error)
        type(test_error), allocatable, intent(out) :: error

        type(modal_set) :: truth
        type(frf_type) :: noisy
        type(scene_type) :: scene
        type(structure_model) :: built
        type(error_type), allocatable :: failure
        real(dp), allocatable :: table(:, :), diagram(:, :)
        character(len=:), allocatable :: header
        integer :: n

        truth = three_modes()
        noisy = frf_from_modes(truth, 500.0_dp, 1025)
        noisy = noisy_copy(noisy, 1.0e-2_dp, 0.0_dp, 41)
        call write_receptance(dir//'/identnoise.frf', noisy)
        call read_scene_text(dir, 'identnoise.nml', "&scene task = 'identify', name = 'identnoise', output_dir = '" &
                             //dir//"' /"//new_line('a')//"&structure model = 'frf_file', frf_file = '"//dir &
                             //"/identnoise.frf' /"//new_line('a')//"&identification noise_model = 'relative' /", &
                             scene, failure)
        if (allocated(failure)) call check(error, .false., failure%message)
        if (allocated(error)) return
        call build_structure(scene, built, failure)
        if (allocated(failure)) call check(error, .false., failure%message)
        if (allocated(error)) return
        n = built%ml%modes%n_modes()
        call check_written(error, 'as fitted')
        if (allocated(error)) return
        built%ml%determined(1) = .false.
        call check_written(error, 'first flag off')
    contains
        subroutine check_written(error, label)
            type(test_error), allocatable, intent(out) :: error
            character(len=*), intent(in) :: label

            call write_identification(scene, built, failure)
            if (allocated(failure)) call check(error, .false., failure%message)
            if (allocated(error)) return
            call read_table(dir//'/identnoise_modes.dat', table, header)
            call check(error, size(table, 1) == n .and. size(table, 2) == 11, label//': one row of 11 columns per pole')
            if (allocated(error)) return
            call check(error, all(nint(table(:, 11)) == merge(1, 0, built%ml%determined)) .and. &
                       all(table(:, 11) == 0.0_dp .or. table(:, 11) == 1.0_dp), label//': the determined column')
            if (allocated(error)) return
            call check(error, index(header, ' determined'//new_line('a')) > 0 .and. index(header, &
                       int_text(count(built%ml%determined))//' of '//int_text(n)//' poles determined') > 0 &
                       .and. index(header, 'noise model relative') > 0, label//': header '//header)
            if (allocated(error)) return
            call read_table(dir//'/identnoise_diagram.dat', diagram, header)
            associate (chosen => pack(diagram(:, 4), diagram(:, 1) == 0.0_dp))
                call check(error, size(chosen) == n .and. all(nint(chosen) == merge(3, 4, built%ml%determined)), &
                           label//': the diagram flags 3 and 4')
            end associate
        end subroutine check_written
    end subroutine test_modes_file

    !> The same file through the F77 door gcidml and the C door gc_identify_ml_file (noise model
    !> 'relative', one identification per call): the modes, sigmas and flags identify_ml gives
    !> on the receptance read from it; capacity 0 is refused with the count still set.
    subroutine test_doors(error)
        type(test_error), allocatable, intent(out) :: error

        integer, parameter :: cap = 40
        type(modal_set) :: truth
        type(frf_type) :: noisy
        type(ml_options) :: options
        type(ml_result) :: result
        type(error_type), allocatable :: failure
        real(dp) :: polre(cap), polim(cap), resre(cap), resim(cap), sigf(cap), sigxi(cap)
        integer :: idet(cap), nmode, ndet, ierr, n
        real(c_double), target :: c_pole_re(cap), c_pole_im(cap), c_res_re(cap), c_res_im(cap), c_sf(cap), c_sx(cap)
        integer(c_int), target :: c_det(cap), c_n, c_ndet
        character(kind=c_char), target :: c_path(200), c_model(9), c_message(300)
        character(len=300) :: message
        character(len=:), allocatable :: path
        integer(c_int) :: status

        truth = three_modes()
        noisy = frf_from_modes(truth, 500.0_dp, 1025)
        noisy = noisy_copy(noisy, 1.0e-2_dp, 0.0_dp, 43)
        path = dir//'/identnoise_doors.frf'
        call write_receptance(path, noisy)
        options%noise_model = 'relative'
        call identify_ml(noisy, options, result, failure)
        if (allocated(failure)) call check(error, .false., failure%message)
        if (allocated(error)) return
        n = result%modes%n_modes()
        call gcidml(path, 'relative', 30, cap, nmode, ndet, polre, polim, resre, resim, sigf, sigxi, idet, ierr, message)
        call check(error, ierr == 0, 'gcidml: '//trim(message))
        if (allocated(error)) return
        call check(error, nmode == n .and. ndet == count(result%determined) .and. all(idet(:n) == merge(1, 0, &
                   result%determined)) .and. all(abs(cmplx(polre(:n), polim(:n), dp) - result%modes%pole) <= &
                   1.0e-9_dp*abs(result%modes%pole)) .and. all(sigf(:n) == result%sigma_frequency) .and. &
                   all(sigxi(:n) == result%sigma_damping), 'gcidml: the modes and flags of identify_ml')
        if (allocated(error)) return
        c_path = c_null_char
        c_path(:len(path)) = transfer(path, c_path(:len(path)))
        c_model = c_null_char
        c_model(:8) = transfer('relative', c_model(:8))
        status = gc_identify_ml_file(c_loc(c_path), c_loc(c_model), 30_c_int, int(cap, c_int), c_loc(c_n), &
                                     c_loc(c_ndet), c_loc(c_pole_re), c_loc(c_pole_im), c_loc(c_res_re), &
                                     c_loc(c_res_im), c_loc(c_sf), c_loc(c_sx), c_loc(c_det), c_loc(c_message), &
                                     int(size(c_message), c_size_t))
        call check(error, status == 0 .and. c_n == n .and. c_ndet == count(result%determined) .and. &
                   all(c_det(:n) == merge(1, 0, result%determined)) .and. all(c_res_re(:n) == resre(:n)) .and. &
                   all(c_res_im(:n) == resim(:n)) .and. all(c_sf(:n) == sigf(:n)), &
                   'gc_identify_ml_file: the modes and flags of gcidml')
        if (allocated(error)) return
        status = gc_identify_ml_file(c_loc(c_path), c_loc(c_model), 30_c_int, 0_c_int, c_loc(c_n), c_loc(c_ndet), &
                                     c_loc(c_pole_re), c_loc(c_pole_im), c_loc(c_res_re), c_loc(c_res_im), &
                                     c_loc(c_sf), c_loc(c_sx), c_loc(c_det), c_loc(c_message), &
                                     int(size(c_message), c_size_t))
        call check(error, status == stat_input .and. c_n == n, 'capacity 0: status 2, n_modes still set')
    end subroutine test_doors

    !> A constant G (1e-6 m/N on 1001 lines): identify_ml refuses it as holding no resonance
    !> (not as NaN or Inf), and a scene on such a file with status 2, the file and variable named.
    subroutine test_constant(error)
        type(test_error), allocatable, intent(out) :: error

        type(frf_type) :: frf
        type(ml_options) :: options
        type(ml_result) :: result
        type(scene_type) :: scene
        type(structure_model) :: built
        type(error_type), allocatable :: failure
        integer :: l

        frf%frequency = [(real(l, dp), l=0, 1000)]
        frf%receptance = [(cmplx(1.0e-6_dp, 0.0_dp, dp), l=0, 1000)]
        call identify_ml(frf, options, result, failure)
        call check(error, allocated(failure), 'a constant receptance is refused')
        if (allocated(error)) return
        call check(error, failure%stat == stat_input .and. index(failure%message, 'no resonance') > 0 .and. &
                   index(failure%message, 'NaN') == 0, 'status 2, no resonance: '//failure%message)
        if (allocated(error)) return
        call write_receptance(dir//'/identnoise_constant.frf', frf)
        call read_scene_text(dir, 'identnoise_constant.nml', "&scene task = 'identify', name = 'constant', " &
                             //"output_dir = '"//dir//"' /"//new_line('a')//"&structure model = 'frf_file', " &
                             //"frf_file = '"//dir//"/identnoise_constant.frf' /", scene, failure)
        if (allocated(failure)) call check(error, .false., failure%message)
        if (allocated(error)) return
        call build_structure(scene, built, failure)
        call check(error, allocated(failure), 'the scene is refused')
        if (allocated(error)) return
        call check(error, failure%stat == stat_input .and. index(failure%message, 'frf_file') > 0 .and. &
                   index(failure%message, 'identnoise_constant.frf') > 0 .and. index(failure%message, 'no resonance') &
                   > 0, 'status 2, the file and variable named: '//failure%message)
    end subroutine test_constant

    !> band_bounds on a million lines cut into bands of 32 (31,250 bands: b*n passes 2^31, which
    !> wrote the determined rule's band scale out of its array): the bands tile 1..n, each of 32;
    !> against 1 + (b - 1)*n/n_bands in real arithmetic. A receptance of max_lines + 1 lines is
    !> refused in one line naming its size and the limit.
    subroutine test_size(error)
        type(test_error), allocatable, intent(out) :: error

        integer, parameter :: n = 1000000, n_bands = n/32
        type(frf_type) :: frf
        type(ml_options) :: options
        type(ml_result) :: result
        type(error_type), allocatable :: failure
        integer :: b, first, last, previous
        logical :: tiled

        tiled = .true.
        previous = 0
        do b = 1, n_bands
            call band_bounds(b, n, n_bands, first, last)
            tiled = tiled .and. first == previous + 1 .and. last - first + 1 == 32 .and. &
                    first == 1 + int(real(b - 1, dp)*real(n, dp)/real(n_bands, dp))
            previous = last
        end do
        call check(error, tiled .and. previous == n, 'the bands tile a million lines, 32 each')
        if (allocated(error)) return
        frf = frf_from_modes(three_modes(), 500.0_dp, max_lines + 1)
        call identify_ml(frf, options, result, failure)
        call check(error, allocated(failure), 'max_lines + 1 lines refused')
        if (allocated(error)) return
        call check(error, failure%stat == stat_input .and. index(failure%message, int_text(max_lines + 1)) > 0 &
                   .and. index(failure%message, int_text(max_lines)//' it takes') > 0 .and. &
                   index(failure%message, new_line('a')) == 0, 'one line, the size and the limit: '//failure%message)
    end subroutine test_size

    ! ---- files -------------------------------------------------------------------------

    !> A receptance as a column file (f [Hz], Re G, Im G [m/N]).
    subroutine write_receptance(path, frf)
        character(len=*), intent(in) :: path
        type(frf_type), intent(in) :: frf

        type(error_type), allocatable :: failure
        integer :: unit, l

        call make_directory(dir, failure)
        open (newunit=unit, file=path, status='replace', action='write')
        write (unit, '(a)') '# f [Hz]  Re G [m/N]  Im G [m/N]'
        do l = 1, frf%n_freq()
            write (unit, '(3es25.16e3)') frf%frequency(l), frf%receptance(l)
        end do
        close (unit)
    end subroutine write_receptance

    !> The numbers of a column file (one row per data line) and its `#` lines joined by new lines.
    subroutine read_table(path, table, header)
        character(len=*), intent(in) :: path
        real(dp), allocatable, intent(out) :: table(:, :)
        character(len=:), allocatable, intent(out) :: header

        character(len=2000) :: line
        real(dp) :: values(40)
        integer :: unit, stat, columns, rows, pass

        header = ''
        columns = 0
        allocate (table(0, 0))
        open (newunit=unit, file=path, status='old', action='read', iostat=stat)
        if (stat /= 0) return
        do pass = 1, 2
            rows = 0
            do
                read (unit, '(a)', iostat=stat) line
                if (stat /= 0) exit
                if (line(1:1) == '#') then
                    if (pass == 1) header = header//trim(line)//new_line('a')
                    cycle
                end if
                if (columns == 0) then
                    do columns = size(values), 1, -1
                        read (line, *, iostat=stat) values(:columns)
                        if (stat == 0) exit
                    end do
                end if
                rows = rows + 1
                if (pass == 2) read (line, *) table(rows, :)
            end do
            if (pass == 1) then
                deallocate (table)
                allocate (table(rows, columns))
                rewind (unit)
            end if
        end do
        close (unit)
    end subroutine read_table

end module test_identnoise_mod
