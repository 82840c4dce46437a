!> The test suites of the ident layer (greenconv_ident_*): `fpm test` runs them with the other
!> layers', `fpm test -- SUITE [TEST]` one of them (test/support/src/testsuite_mod.f90, run_layer).
program greenconv_tests_ident
    use testsuite_mod, only: new_testsuite, run_layer
    use test_lsce_mod, only: collect_lsce
    use test_mlfit_mod, only: collect_mlfit
    use test_identgrid_mod, only: collect_identgrid
    use test_identreal_mod, only: collect_identreal
    use test_outofband_mod, only: collect_outofband
    use test_identdense_mod, only: collect_identdense
    use test_identsearch_mod, only: collect_identsearch
    use test_polyref_mod, only: collect_polyref
    use test_identnoise_mod, only: collect_identnoise
    use test_identcost_mod, only: collect_identcost
    implicit none

    call run_layer('ident', [ &
                    new_testsuite('lsce', collect_lsce), &
                    new_testsuite('mlfit', collect_mlfit), &
                    new_testsuite('identgrid', collect_identgrid), &
                    new_testsuite('identreal', collect_identreal), &
                    new_testsuite('outofband', collect_outofband), &
                    new_testsuite('identdense', collect_identdense), &
                    new_testsuite('identsearch', collect_identsearch), &
                    new_testsuite('polyref', collect_polyref), &
                    new_testsuite('identnoise', collect_identnoise), &
                    new_testsuite('identcost', collect_identcost)])
end program greenconv_tests_ident
