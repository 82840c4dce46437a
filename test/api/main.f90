!> The test suites of the api layer (greenconv_api_*): `fpm test` runs them with the other
!> layers', `fpm test -- SUITE [TEST]` one of them (test/support/src/testsuite_mod.f90, run_layer).
program greenconv_tests_api
    use testsuite_mod, only: new_testsuite, run_layer
    use test_library_mod, only: collect_library
    use test_multidoors_mod, only: collect_multidoors
    use test_reliability_mod, only: collect_reliability
    implicit none

    call run_layer('api', [ &
                    new_testsuite('library', collect_library), &
                    new_testsuite('multidoors', collect_multidoors), &
                    new_testsuite('reliability', collect_reliability)])
end program greenconv_tests_api
