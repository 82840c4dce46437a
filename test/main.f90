!> Runs every test suite of greenconv and ends with the line `N passed, N failed`;
!> exits with status 1 when a test failed.
program greenconv_tests
    use, intrinsic :: iso_fortran_env, only: output_unit
    use testsuite_mod, only: run_testsuite
    use test_sdof_mod, only: collect_sdof
    use test_convolution_mod, only: collect_convolution
    use test_contact_mod, only: collect_contact
    use test_lsce_mod, only: collect_lsce
    use test_random_mod, only: collect_random
    use test_scene_mod, only: collect_scene
    use test_engines_mod, only: collect_engines
    use test_fft_mod, only: collect_fft
    use test_multicontact_mod, only: collect_multicontact
    use test_implicit_mod, only: collect_implicit
    use test_accuracy_mod, only: collect_accuracy
    use test_library_mod, only: collect_library
    use test_input_mod, only: collect_input
    use test_longrun_mod, only: collect_longrun
    use test_mlfit_mod, only: collect_mlfit
    implicit none

    integer :: n_passed, n_failed

    n_passed = 0
    n_failed = 0
    call run_testsuite('sdof', collect_sdof, output_unit, n_passed, n_failed)
    call run_testsuite('convolution', collect_convolution, output_unit, n_passed, n_failed)
    call run_testsuite('contact', collect_contact, output_unit, n_passed, n_failed)
    call run_testsuite('random', collect_random, output_unit, n_passed, n_failed)
    call run_testsuite('lsce', collect_lsce, output_unit, n_passed, n_failed)
    call run_testsuite('scene', collect_scene, output_unit, n_passed, n_failed)
    call run_testsuite('engines', collect_engines, output_unit, n_passed, n_failed)
    call run_testsuite('fft', collect_fft, output_unit, n_passed, n_failed)
    call run_testsuite('multicontact', collect_multicontact, output_unit, n_passed, n_failed)
    call run_testsuite('implicit', collect_implicit, output_unit, n_passed, n_failed)
    call run_testsuite('accuracy', collect_accuracy, output_unit, n_passed, n_failed)
    call run_testsuite('library', collect_library, output_unit, n_passed, n_failed)
    call run_testsuite('input', collect_input, output_unit, n_passed, n_failed)
    call run_testsuite('longrun', collect_longrun, output_unit, n_passed, n_failed)
    call run_testsuite('mlfit', collect_mlfit, output_unit, n_passed, n_failed)
    write (output_unit, '(i0,a,i0,a)') n_passed, ' passed, ', n_failed, ' failed'
    if (n_failed > 0) stop 1, quiet=.true.
end program greenconv_tests
