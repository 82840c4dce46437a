!> The test suites of the conv layer (greenconv_conv_*): `fpm test` runs them with the other
!> layers', `fpm test -- SUITE [TEST]` one of them (test/support/src/testsuite_mod.f90, run_layer).
program greenconv_tests_conv
    use testsuite_mod, only: new_testsuite, run_layer
    use test_convolution_mod, only: collect_convolution
    use test_engines_mod, only: collect_engines
    use test_fft_mod, only: collect_fft
    use test_greenfft_mod, only: collect_greenfft
    use test_greenfiles_mod, only: collect_greenfiles
    use test_separable_mod, only: collect_separable
    implicit none

    call run_layer('conv', [ &
                    new_testsuite('convolution', collect_convolution), &
                    new_testsuite('engines', collect_engines), &
                    new_testsuite('fft', collect_fft), &
                    new_testsuite('greenfft', collect_greenfft), &
                    new_testsuite('greenfiles', collect_greenfiles), &
                    new_testsuite('separable', collect_separable)])
end program greenconv_tests_conv
