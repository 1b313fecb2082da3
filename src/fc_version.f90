!> The package's version and the build that made it: printed by `fastcontact --version`,
!! written into every JSON summary (`"version"`) and returned by the flat API's
!! `fc_get_version`, so that a result can be traced to the code that produced it.
!! Semantic versioning; the number is the `version` of fpm.toml (test `driver ::
!! version_matches_manifest` keeps the two equal).
module fc_version
    use, intrinsic :: iso_fortran_env, only: compiler_version
    implicit none
    private

    integer, parameter, public :: fc_version_major = 0   !! incompatible changes of the API or outputs
    integer, parameter, public :: fc_version_minor = 1   !! compatible additions
    integer, parameter, public :: fc_version_patch = 0   !! fixes
    character(len=*), parameter, public :: fc_version_string = '0.1.0'  !! "major.minor.patch"

    public :: fc_build_info

contains

    !> One line: package, version and the compiler that built it, e.g.
    !! "fastcontact 0.1.0 (GCC version 12.2.0)".
    function fc_build_info() result(text)
        character(len=:), allocatable :: text
        text = 'fastcontact '//fc_version_string//' ('//compiler_version()//')'
    end function fc_build_info

end module fc_version
