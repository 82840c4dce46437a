#ifndef GREENCONV_VERSION
#error "GREENCONV_VERSION is not defined: build with fpm, or with -DGREENCONV_VERSION=x.y.z taken from fpm.toml"
#endif
! The macro is a bare x.y.z. gfortran's traditional preprocessor replaces a macro argument
! inside quotes, so the first form makes the continued literal "&<newline>&x.y.z"; a standard
! preprocessor quotes it with #.
#ifdef __GFORTRAN__
#define GC_QUOTED_START(X) "&
#define GC_QUOTED_END(X) &X"
#else
#define GC_QUOTED(X) #X
#define GC_QUOTED_START(X) &
#define GC_QUOTED_END(X) GC_QUOTED(X)
#endif
!> The version of greenconv, "major.minor.patch", as fpm.toml states it (`version = "..."`):
!> what `greenconv --version` prints and what the library's callers ask for
!> (`greenconv_version()`, C `gc_version`, Fortran 77 `GCVERS`).
!>
!> fpm.toml is the only place the number is written. fpm passes it to this file as the
!> preprocessor macro GREENCONV_VERSION (`[preprocess.cpp]`, `{version}`); the Makefile
!> reads the same line of fpm.toml and passes -DGREENCONV_VERSION=x.y.z. A build without
!> the macro stops at the `#error` at the top of this file instead of guessing a number.
module greenconv_core_version
    implicit none
    private

    public :: greenconv_version

    !> The version as fpm.toml gives it.
    character(len=*), parameter :: version_text = GC_QUOTED_START(GREENCONV_VERSION)
GC_QUOTED_END(GREENCONV_VERSION)

contains

    !> greenconv's version, "major.minor.patch" as fpm.toml states it (for example "0.1.0").
    pure function greenconv_version() result(text)
        !> The version text, without blanks.
        character(len=len(version_text)) :: text

        text = version_text
    end function greenconv_version

end module greenconv_core_version
