!> The test suites of the io layer (greenconv_io_*): `fpm test` runs them with the other
!> layers', `fpm test -- SUITE [TEST]` one of them (test/support/src/testsuite_mod.f90, run_layer).
program greenconv_tests_io
    use testsuite_mod, only: new_testsuite, run_layer
    use test_uff_mod, only: collect_uff
    use test_uffwrite_mod, only: collect_uffwrite
    use test_spectra_mod, only: collect_spectra
    use test_writer_mod, only: collect_writer
    use test_columns_mod, only: collect_columns
    implicit none

    call run_layer('io', [ &
                    new_testsuite('uff', collect_uff), &
                    new_testsuite('uffwrite', collect_uffwrite), &
                    new_testsuite('spectra', collect_spectra), &
                    new_testsuite('writer', collect_writer), &
                    new_testsuite('columns', collect_columns)])
end program greenconv_tests_io
