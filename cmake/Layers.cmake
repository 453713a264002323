# The library's layers, in order: a layer may include and call only itself and the layers before
# it in this list (docs/architecture.md). The build enforces it: each layer's sources compile as
# their own object library whose ONLY project include folder is a view of what that layer may see,
#   <build>/layer-views/<layer>/<lower layer>/  -> src/<lower layer>/        (internal headers)
#   <build>/layer-views/<layer>/skyspec/<h>     -> include/skyspec/<h>       (public headers of that
#                                                   layer and the ones below)
# so an upward #include is "No such file or directory" at compile time. The test `layering`
# (tests/layering/) checks every header as well, whichever file includes it, and proves that an
# upward include fails to compile. This file is the one place that says which layer a public
# header belongs to; a header in include/skyspec/ without a layer stops the configure step.
set(SKYSPEC_LAYERS base physics transport colour io scene render report job)

set(SKYSPEC_PUBLIC_HEADERS_base error.hpp units.hpp spectrum.hpp version.hpp vec3.hpp cancellation.hpp preparation_progress.hpp)
set(SKYSPEC_PUBLIC_HEADERS_physics aerosol_components.hpp atmosphere.hpp density_profile.hpp medium.hpp lorenz_mie.hpp phase_function.hpp rayleigh.hpp size_distribution.hpp sphere_ensemble.hpp tabulated_scattering.hpp vertical_cylinder.hpp water.hpp ice_crystals.hpp drop_optics.hpp
    refractive_index.hpp king_factor.hpp standard_atmosphere.hpp)
set(SKYSPEC_PUBLIC_HEADERS_transport geometry.hpp terrain.hpp)
set(SKYSPEC_PUBLIC_HEADERS_colour colour.hpp display.hpp)
set(SKYSPEC_PUBLIC_HEADERS_io)
set(SKYSPEC_PUBLIC_HEADERS_scene scene.hpp camera_spec.hpp)
set(SKYSPEC_PUBLIC_HEADERS_render camera.hpp render.hpp monte_carlo_reference.hpp aerial_perspective.hpp irradiance.hpp)
set(SKYSPEC_PUBLIC_HEADERS_report coefficient_report.hpp lee_diagram.hpp sky_comparison.hpp)
set(SKYSPEC_PUBLIC_HEADERS_job skyspec.hpp timelapse.hpp)

set(SKYSPEC_LAYER_VIEWS ${CMAKE_CURRENT_BINARY_DIR}/layer-views)

# Every public header has exactly one layer.
file(GLOB _public RELATIVE ${CMAKE_CURRENT_SOURCE_DIR}/include/skyspec CONFIGURE_DEPENDS
     ${CMAKE_CURRENT_SOURCE_DIR}/include/skyspec/*.hpp)
set(_assigned)
foreach(layer IN LISTS SKYSPEC_LAYERS)
  list(APPEND _assigned ${SKYSPEC_PUBLIC_HEADERS_${layer}})
endforeach()
foreach(h IN LISTS _public)
  list(FIND _assigned ${h} _at)
  if(_at EQUAL -1)
    message(FATAL_ERROR "include/skyspec/${h} has no layer: add it to a SKYSPEC_PUBLIC_HEADERS_<layer> list in cmake/Layers.cmake")
  endif()
endforeach()
foreach(h IN LISTS _assigned)
  if(NOT EXISTS ${CMAKE_CURRENT_SOURCE_DIR}/include/skyspec/${h})
    message(FATAL_ERROR "cmake/Layers.cmake names include/skyspec/${h}, which does not exist")
  endif()
endforeach()

# The views: rebuilt from scratch at each configure, so that a header moved to another layer
# leaves no stale link behind.
file(REMOVE_RECURSE ${SKYSPEC_LAYER_VIEWS})
set(_below)
foreach(layer IN LISTS SKYSPEC_LAYERS)
  list(APPEND _below ${layer})
  set(_view ${SKYSPEC_LAYER_VIEWS}/${layer})
  file(MAKE_DIRECTORY ${_view}/skyspec)
  foreach(visible IN LISTS _below)
    if(EXISTS ${CMAKE_CURRENT_SOURCE_DIR}/src/${visible})
      file(CREATE_LINK ${CMAKE_CURRENT_SOURCE_DIR}/src/${visible} ${_view}/${visible} SYMBOLIC)
    endif()
    foreach(h IN LISTS SKYSPEC_PUBLIC_HEADERS_${visible})
      file(CREATE_LINK ${CMAKE_CURRENT_SOURCE_DIR}/include/skyspec/${h} ${_view}/skyspec/${h} SYMBOLIC)
    endforeach()
  endforeach()
endforeach()

# skyspec_add_layer(LAYER SOURCES... [DEPENDS lower layers' targets]): the object library
# skyspec_<LAYER>, compiled with skyspec's warnings and flags, seeing only its view.
function(skyspec_add_layer layer)
  cmake_parse_arguments(ARG "" "" "SOURCES;LIBRARIES" ${ARGN})
  add_library(skyspec_${layer} OBJECT ${ARG_SOURCES})
  target_include_directories(skyspec_${layer} PRIVATE ${SKYSPEC_LAYER_VIEWS}/${layer})
  target_link_libraries(skyspec_${layer} PRIVATE ${ARG_LIBRARIES})
  skyspec_target_defaults(skyspec_${layer})
  # The library reads no errno from maths functions and enables no floating-point traps: telling
  # the compiler so lets it vectorise loops with square roots and selects (the sun table's
  # lookup_many). Neither flag changes a result's rounding.
  target_compile_options(skyspec_${layer} PRIVATE -fno-math-errno -fno-trapping-math)
  set_target_properties(skyspec_${layer} PROPERTIES POSITION_INDEPENDENT_CODE ON
                        UNITY_BUILD ${SKYSPEC_UNITY} UNITY_BUILD_BATCH_SIZE 8)
endfunction()
