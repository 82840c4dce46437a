!> The test suites of the core layer (greenconv_core_*): `fpm test` runs them with the other
!> layers', `fpm test -- SUITE [TEST]` one of them (test/support/src/testsuite_mod.f90, run_layer).
program greenconv_tests_core
    use testsuite_mod, only: new_testsuite, run_layer
    use test_random_mod, only: collect_random
    use test_realtext_mod, only: collect_realtext
    use test_lapack_mod, only: collect_lapack
    use test_version_mod, only: collect_version
    use test_sorting_mod, only: collect_sorting
    use test_text_mod, only: collect_text
    implicit none

    call run_layer('core', [ &
                    new_testsuite('random', collect_random), &
                    new_testsuite('realtext', collect_realtext), &
                    new_testsuite('lapack', collect_lapack), &
                    new_testsuite('version', collect_version), &
                    new_testsuite('sorting', collect_sorting), &
                    new_testsuite('text', collect_text)])
end program greenconv_tests_core
