!> The test suites of the model layer (greenconv_model_*): `fpm test` runs them with the other
!> layers', `fpm test -- SUITE [TEST]` one of them (test/support/src/testsuite_mod.f90, run_layer).
program greenconv_tests_model
    use testsuite_mod, only: new_testsuite, run_layer
    use test_plate_mod, only: collect_plate
    use test_patch_mod, only: collect_patch
    use test_modesfile_mod, only: collect_modesfile
    use test_linearpatch_mod, only: collect_linearpatch
    use test_sdof_mod, only: collect_sdof
    use test_uffchecks_mod, only: collect_uffchecks
    implicit none

    call run_layer('model', [ &
                    new_testsuite('plate', collect_plate), &
                    new_testsuite('patch', collect_patch), &
                    new_testsuite('modesfile', collect_modesfile), &
                    new_testsuite('linearpatch', collect_linearpatch), &
                    new_testsuite('sdof', collect_sdof), &
                    new_testsuite('uffchecks', collect_uffchecks)])
end program greenconv_tests_model
