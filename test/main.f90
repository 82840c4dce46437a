!> Runs the test suites of greenconv and ends with the line `N passed, N failed`; exits with
!> status 1 when a test failed.
!>
!>     fpm test                          every suite
!>     fpm test -- SUITE                 one suite, e.g. `fpm test -- contact`
!>     fpm test -- SUITE 'TEST NAME'     one test of a suite, by its full name
!>
!> An unknown suite or test prints the valid names and exits with status 2.
program greenconv_tests
    use, intrinsic :: iso_fortran_env, only: output_unit
    use testsuite_mod, only: new_testsuite, run_selected
    use test_sdof_mod, only: collect_sdof
    use test_convolution_mod, only: collect_convolution
    use test_contact_mod, only: collect_contact
    use test_lsce_mod, only: collect_lsce
    use test_random_mod, only: collect_random
    use test_scene_mod, only: collect_scene
    use test_engines_mod, only: collect_engines
    use test_fft_mod, only: collect_fft
    use test_multicontact_mod, only: collect_multicontact
    use test_lowrank_mod, only: collect_lowrank
    use test_implicit_mod, only: collect_implicit
    use test_accuracy_mod, only: collect_accuracy
    use test_library_mod, only: collect_library
    use test_input_mod, only: collect_input
    use test_longrun_mod, only: collect_longrun
    use test_lapack_mod, only: collect_lapack
    use test_uff_mod, only: collect_uff
    use test_greenfft_mod, only: collect_greenfft
    use test_realtext_mod, only: collect_realtext
    use test_writer_mod, only: collect_writer
    use test_plate_mod, only: collect_plate
    use test_spectra_mod, only: collect_spectra
    use test_scenespectra_mod, only: collect_scenespectra
    use test_uffwrite_mod, only: collect_uffwrite
    use test_mlfit_mod, only: collect_mlfit
    use test_identgrid_mod, only: collect_identgrid
    use test_identreal_mod, only: collect_identreal
    use test_outofband_mod, only: collect_outofband
    use test_identdense_mod, only: collect_identdense
    use test_identsearch_mod, only: collect_identsearch
    use test_multidoors_mod, only: collect_multidoors
    use test_sweep_mod, only: collect_sweep
    use test_patch_mod, only: collect_patch
    use test_patchscene_mod, only: collect_patchscene
    use test_tyrepatch_mod, only: collect_tyrepatch
    use test_scaleoutput_mod, only: collect_scaleoutput
    use test_reliability_mod, only: collect_reliability
    use test_version_mod, only: collect_version
    use test_uffchecks_mod, only: collect_uffchecks
    use test_multiorder_mod, only: collect_multiorder
    use test_greenfiles_mod, only: collect_greenfiles
    use test_accuracystatus_mod, only: collect_accuracystatus
    use test_polyref_mod, only: collect_polyref
    use test_modesfile_mod, only: collect_modesfile
    use test_checkcost_mod, only: collect_checkcost
    use test_wheelrail_mod, only: collect_wheelrail
    use test_identnoise_mod, only: collect_identnoise
    use test_errorbudget_mod, only: collect_errorbudget
    use test_linearpatch_mod, only: collect_linearpatch
    use test_identcost_mod, only: collect_identcost
    use test_separable_mod, only: collect_separable
    implicit none

    integer :: n_passed, n_failed
    logical :: valid

    n_passed = 0
    n_failed = 0
    call run_selected([new_testsuite('sdof', collect_sdof), &
                       new_testsuite('convolution', collect_convolution), &
                       new_testsuite('contact', collect_contact), &
                       new_testsuite('random', collect_random), &
                       new_testsuite('lsce', collect_lsce), &
                       new_testsuite('scene', collect_scene), &
                       new_testsuite('engines', collect_engines), &
                       new_testsuite('fft', collect_fft), &
                       new_testsuite('multicontact', collect_multicontact), &
                       new_testsuite('lowrank', collect_lowrank), &
                       new_testsuite('implicit', collect_implicit), &
                       new_testsuite('accuracy', collect_accuracy), &
                       new_testsuite('library', collect_library), &
                       new_testsuite('input', collect_input), &
                       new_testsuite('lapack', collect_lapack), &
                       new_testsuite('uff', collect_uff), &
                       new_testsuite('greenfft', collect_greenfft), &
                       new_testsuite('realtext', collect_realtext), &
                       new_testsuite('writer', collect_writer), &
                       new_testsuite('plate', collect_plate), &
                       new_testsuite('spectra', collect_spectra), &
                       new_testsuite('scenespectra', collect_scenespectra), &
                       new_testsuite('uffwrite', collect_uffwrite), &
                       new_testsuite('mlfit', collect_mlfit), &
                       new_testsuite('identgrid', collect_identgrid), &
                       new_testsuite('identreal', collect_identreal), &
                       new_testsuite('outofband', collect_outofband), &
                       new_testsuite('identdense', collect_identdense), &
                       new_testsuite('identsearch', collect_identsearch), &
                       new_testsuite('multidoors', collect_multidoors), &
                       new_testsuite('sweep', collect_sweep), &
                       new_testsuite('patch', collect_patch), &
                       new_testsuite('patchscene', collect_patchscene), &
                       new_testsuite('tyrepatch', collect_tyrepatch), &
                       new_testsuite('greenfiles', collect_greenfiles), &
                       new_testsuite('polyref', collect_polyref), &
                       new_testsuite('reliability', collect_reliability), &
                       new_testsuite('version', collect_version), &
                       new_testsuite('uffchecks', collect_uffchecks), &
                       new_testsuite('multiorder', collect_multiorder), &
                       new_testsuite('accuracystatus', collect_accuracystatus), &
                       new_testsuite('modesfile', collect_modesfile), &
                       new_testsuite('longrun', collect_longrun), &
                       new_testsuite('checkcost', collect_checkcost), &
                       new_testsuite('scaleoutput', collect_scaleoutput), &
                       new_testsuite('wheelrail', collect_wheelrail), &
                       new_testsuite('identnoise', collect_identnoise), &
                       new_testsuite('errorbudget', collect_errorbudget), &
                       new_testsuite('linearpatch', collect_linearpatch), &
                       new_testsuite('identcost', collect_identcost), &
                       new_testsuite('separable', collect_separable)], output_unit, n_passed, n_failed, valid)
    if (.not. valid) stop 2, quiet=.true.
    write (output_unit, '(i0,a,i0,a)') n_passed, ' passed, ', n_failed, ' failed'
    if (n_failed > 0) stop 1, quiet=.true.
end program greenconv_tests
