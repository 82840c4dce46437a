!> The index of every test suite by the layer of the library it tests, bottom layer first:
!> each layer's program (test/<layer>/main.f90) checks its suites against it, and it lets
!> `fpm test -- SUITE` tell a suite of another layer from a name no layer holds.
module suite_index_mod
    implicit none
    private

    public :: suite_index, index_layer, index_name

    !> One row a suite: the layer (8 characters) then the suite's name.
    character(len=24), parameter :: suite_index(*) = [ &
        'core    random          ', &
        'core    realtext        ', &
        'core    lapack          ', &
        'core    version         ', &
        'core    sorting         ', &
        'core    text            ', &
        'io      uff             ', &
        'io      uffwrite        ', &
        'io      spectra         ', &
        'io      writer          ', &
        'io      columns         ', &
        'model   plate           ', &
        'model   patch           ', &
        'model   modesfile       ', &
        'model   linearpatch     ', &
        'model   sdof            ', &
        'model   uffchecks       ', &
        'ident   lsce            ', &
        'ident   mlfit           ', &
        'ident   identgrid       ', &
        'ident   identreal       ', &
        'ident   outofband       ', &
        'ident   identdense      ', &
        'ident   identsearch     ', &
        'ident   polyref         ', &
        'ident   identnoise      ', &
        'ident   identcost       ', &
        'conv    convolution     ', &
        'conv    engines         ', &
        'conv    fft             ', &
        'conv    greenfft        ', &
        'conv    greenfiles      ', &
        'conv    separable       ', &
        'contact contact         ', &
        'contact multicontact    ', &
        'contact lowrank         ', &
        'contact lowrankbits     ', &
        'contact implicit        ', &
        'contact accuracy        ', &
        'contact multiorder      ', &
        'contact laws            ', &
        'scene   scene           ', &
        'scene   input           ', &
        'scene   scenespectra    ', &
        'scene   sweep           ', &
        'scene   patchscene      ', &
        'scene   tyrepatch       ', &
        'scene   accuracystatus  ', &
        'scene   longrun         ', &
        'scene   checkcost       ', &
        'scene   scaleoutput     ', &
        'scene   wheelrail       ', &
        'scene   errorbudget     ', &
        'api     library         ', &
        'api     multidoors      ', &
        'api     reliability     ']

contains

    !> The layer of row i.
    function index_layer(i) result(layer)
        integer, intent(in) :: i
        character(len=:), allocatable :: layer

        layer = trim(suite_index(i)(1:8))
    end function index_layer

    !> The suite's name of row i.
    function index_name(i) result(name)
        integer, intent(in) :: i
        character(len=:), allocatable :: name

        name = trim(suite_index(i)(9:))
    end function index_name
end module suite_index_mod
