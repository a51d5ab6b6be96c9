# Build-time shader headers (docs/design.md, section 4).
#
# Runs the freshly built spiralgen to write, into ${SPIRAL_GENERATED_DIR}:
#   ao_taps.glsl         spiralgen header --pass ao --taps ${AO_TAPS} [--tau ${AO_TAU}]
#                        [--denominator ${AO_TURN_DENOMINATOR}] (likewise radiosity)
#   radiosity_taps.glsl  spiralgen header --pass radiosity --taps ${RADIOSITY_TAPS} [--tau ...]
#   blur_kernel.glsl     spiralgen blur --radius ${BLUR_RADIUS} [--sigma ${BLUR_SIGMA}]
#   tau_table.glsl       spiralgen table --format glsl --max-n ${SPIRAL_TAU_TABLE_MAX_N}
#   tau_table.hpp        spiralgen table --format cpp  --max-n ${SPIRAL_TAU_TABLE_MAX_N}
#
# Each header depends on the spiralgen executable and on a small file holding
# its own arguments. That file is rewritten at configure time only when the
# arguments change, so changing one cache variable regenerates only the headers
# that use it (with any generator, not just those that track command lines),
# and a rebuild with nothing changed regenerates nothing. The optimizer runs
# only for the tap counts a header needs.
#
# Consumers: shaders #include the .glsl files (the runtime's loader searches
# ${SPIRAL_GENERATED_DIR}); C++ links spiral::generated_headers to get the
# include directory for tau_table.hpp and the build-order dependency.

set(AO_TAPS 11 CACHE STRING "Taps of the deep SAO gather (ao_taps.glsl)")
set(AO_TAU "" CACHE STRING "Spiral turns of the SAO gather; empty = the optimum")
set(AO_TURN_DENOMINATOR 1 CACHE STRING "Turns of the SAO gather are p / this; 1 = integer turns (AO_TAU is then p)")
set(RADIOSITY_TAPS 19 CACHE STRING "Taps of the deep radiosity gather (radiosity_taps.glsl)")
set(RADIOSITY_TAU "" CACHE STRING "Spiral turns of the radiosity gather; empty = the optimum")
set(RADIOSITY_TURN_DENOMINATOR 1 CACHE STRING "Turns of the radiosity gather are p / this; 1 = integer turns")
set(BLUR_RADIUS 4 CACHE STRING "Radius in pixels of the bilateral blur kernel (blur_kernel.glsl)")
set(BLUR_SIGMA "" CACHE STRING "Standard deviation of the blur kernel in pixels; empty = BLUR_RADIUS / 2")
set(SPIRAL_TAU_TABLE_MAX_N 128 CACHE STRING "Largest tap count in tau_table.glsl / tau_table.hpp")

set(SPIRAL_GENERATED_DIR ${CMAKE_BINARY_DIR}/generated)
set(_spiral_arguments_dir ${CMAKE_BINARY_DIR}/generated_arguments)
file(MAKE_DIRECTORY ${SPIRAL_GENERATED_DIR} ${_spiral_arguments_dir})

# A bad value fails at configure time with the variable's name, not halfway
# through a build.
foreach(_variable AO_TAPS RADIOSITY_TAPS SPIRAL_TAU_TABLE_MAX_N AO_TURN_DENOMINATOR RADIOSITY_TURN_DENOMINATOR)
  if(NOT "${${_variable}}" MATCHES "^[1-9][0-9]*$")
    message(FATAL_ERROR "${_variable} must be a positive integer, got '${${_variable}}'")
  endif()
endforeach()
foreach(_variable AO_TAU RADIOSITY_TAU)
  if(NOT "${${_variable}}" STREQUAL "" AND NOT "${${_variable}}" MATCHES "^[1-9][0-9]*$")
    message(FATAL_ERROR "${_variable} must be empty or a positive integer, got '${${_variable}}'")
  endif()
endforeach()
if(NOT "${BLUR_RADIUS}" MATCHES "^(0|[1-9][0-9]*)$")
  message(FATAL_ERROR "BLUR_RADIUS must be a non-negative integer, got '${BLUR_RADIUS}'")
endif()
# Upper limits (taps, blur radius, denominators) have one owner each in
# codegen/optimizer; spiralgen checks them when the build runs it and names
# the limit in its one-line error, so they are not repeated here.
if(NOT "${BLUR_SIGMA}" STREQUAL "" AND NOT "${BLUR_SIGMA}" MATCHES "^([0-9]+\\.?[0-9]*|\\.[0-9]+)([eE][-+]?[0-9]+)?$")
  message(FATAL_ERROR "BLUR_SIGMA must be empty or a positive number, got '${BLUR_SIGMA}'")
endif()

set(_spiral_generated_outputs "")

# spiral_generate_header(<file> <spiralgen arguments...>)
function(spiral_generate_header file)
  set(output ${SPIRAL_GENERATED_DIR}/${file})
  set(arguments_file ${_spiral_arguments_dir}/${file}.args)
  string(JOIN " " arguments_text ${ARGN})
  # Touched only when the text differs, which is what makes the rule rerun.
  file(CONFIGURE OUTPUT ${arguments_file} CONTENT "${arguments_text}\n")
  add_custom_command(
    OUTPUT ${output}
    COMMAND spiralgen ${ARGN} --out ${output}
    DEPENDS spiralgen ${arguments_file}
    COMMENT "Generating ${file} (spiralgen ${arguments_text})"
    VERBATIM)
  set(_spiral_generated_outputs ${_spiral_generated_outputs} ${output} PARENT_SCOPE)
endfunction()

set(_ao_arguments header --pass ao --taps ${AO_TAPS})
if(NOT AO_TAU STREQUAL "")
  list(APPEND _ao_arguments --tau ${AO_TAU})
endif()
# Denominator 1 is left off the command line, so integer headers keep their
# bytes and their arguments files.
if(NOT AO_TURN_DENOMINATOR EQUAL 1)
  list(APPEND _ao_arguments --denominator ${AO_TURN_DENOMINATOR})
endif()
set(_radiosity_arguments header --pass radiosity --taps ${RADIOSITY_TAPS})
if(NOT RADIOSITY_TAU STREQUAL "")
  list(APPEND _radiosity_arguments --tau ${RADIOSITY_TAU})
endif()
if(NOT RADIOSITY_TURN_DENOMINATOR EQUAL 1)
  list(APPEND _radiosity_arguments --denominator ${RADIOSITY_TURN_DENOMINATOR})
endif()
set(_blur_arguments blur --radius ${BLUR_RADIUS})
if(NOT BLUR_SIGMA STREQUAL "")
  list(APPEND _blur_arguments --sigma ${BLUR_SIGMA})
endif()

spiral_generate_header(ao_taps.glsl ${_ao_arguments})
spiral_generate_header(radiosity_taps.glsl ${_radiosity_arguments})
spiral_generate_header(blur_kernel.glsl ${_blur_arguments})
spiral_generate_header(tau_table.glsl table --min-n 1 --max-n ${SPIRAL_TAU_TABLE_MAX_N} --format glsl)
spiral_generate_header(tau_table.hpp table --min-n 1 --max-n ${SPIRAL_TAU_TABLE_MAX_N} --format cpp)

add_custom_target(spiral_generated_headers ALL DEPENDS ${_spiral_generated_outputs})

add_library(spiral_generated_headers_interface INTERFACE)
add_library(spiral::generated_headers ALIAS spiral_generated_headers_interface)
target_include_directories(spiral_generated_headers_interface INTERFACE ${SPIRAL_GENERATED_DIR})
add_dependencies(spiral_generated_headers_interface spiral_generated_headers)
