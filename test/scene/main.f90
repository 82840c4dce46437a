!> The test suites of the scene layer (greenconv_scene_*): `fpm test` runs them with the other
!> layers', `fpm test -- SUITE [TEST]` one of them (test/support/src/testsuite_mod.f90, run_layer).
program greenconv_tests_scene
    use testsuite_mod, only: new_testsuite, run_layer
    use test_scene_mod, only: collect_scene
    use test_input_mod, only: collect_input
    use test_scenespectra_mod, only: collect_scenespectra
    use test_sweep_mod, only: collect_sweep
    use test_patchscene_mod, only: collect_patchscene
    use test_tyrepatch_mod, only: collect_tyrepatch
    use test_accuracystatus_mod, only: collect_accuracystatus
    use test_longrun_mod, only: collect_longrun
    use test_checkcost_mod, only: collect_checkcost
    use test_scaleoutput_mod, only: collect_scaleoutput
    use test_wheelrail_mod, only: collect_wheelrail
    use test_errorbudget_mod, only: collect_errorbudget
    implicit none

    call run_layer('scene', [ &
                    new_testsuite('scene', collect_scene), &
                    new_testsuite('input', collect_input), &
                    new_testsuite('scenespectra', collect_scenespectra), &
                    new_testsuite('sweep', collect_sweep), &
                    new_testsuite('patchscene', collect_patchscene), &
                    new_testsuite('tyrepatch', collect_tyrepatch), &
                    new_testsuite('accuracystatus', collect_accuracystatus), &
                    new_testsuite('longrun', collect_longrun), &
                    new_testsuite('checkcost', collect_checkcost), &
                    new_testsuite('scaleoutput', collect_scaleoutput), &
                    new_testsuite('wheelrail', collect_wheelrail), &
                    new_testsuite('errorbudget', collect_errorbudget)])
end program greenconv_tests_scene
