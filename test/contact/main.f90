!> The test suites of the contact layer (greenconv_contact_*): `fpm test` runs them with the other
!> layers', `fpm test -- SUITE [TEST]` one of them (test/support/src/testsuite_mod.f90, run_layer).
program greenconv_tests_contact
    use testsuite_mod, only: new_testsuite, run_layer
    use test_contact_mod, only: collect_contact
    use test_multicontact_mod, only: collect_multicontact
    use test_lowrank_mod, only: collect_lowrank
    use test_lowrankbits_mod, only: collect_lowrankbits
    use test_implicit_mod, only: collect_implicit
    use test_accuracy_mod, only: collect_accuracy
    use test_multiorder_mod, only: collect_multiorder
    use test_laws_mod, only: collect_laws
    implicit none

    call run_layer('contact', [ &
                    new_testsuite('contact', collect_contact), &
                    new_testsuite('multicontact', collect_multicontact), &
                    new_testsuite('lowrank', collect_lowrank), &
                    new_testsuite('lowrankbits', collect_lowrankbits), &
                    new_testsuite('implicit', collect_implicit), &
                    new_testsuite('accuracy', collect_accuracy), &
                    new_testsuite('multiorder', collect_multiorder), &
                    new_testsuite('laws', collect_laws)])
end program greenconv_tests_contact
