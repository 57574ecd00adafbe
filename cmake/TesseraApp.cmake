# tessera_add_app(<target> SOURCES ...)
# Natively an application is a module that soc_sim dlopens; the GL ES and
# EGL entry points are left undefined and resolved in soc_sim at load time,
# so there is no GL library to link. With the ARM922T toolchain, when the
# package has defined tessera::arm922t_runtime, it is an executable,
# <target>.elf, for soc_sim's ISS: the application linked with the driver,
# the back ends and the bare-metal runtime, which calls tessera_app_main
# or main. Used by the installed package (tesseraConfig) and, in the build
# tree, by the tests' own applications, so that both are built the same
# way. Needs the target tessera::sdk (the SDK's headers).
function(tessera_add_app target)
  cmake_parse_arguments(PARSE_ARGV 1 APP "" "" "SOURCES")
  if(APP_UNPARSED_ARGUMENTS OR NOT APP_SOURCES)
    message(FATAL_ERROR "usage: tessera_add_app(<target> SOURCES <source> ...)")
  endif()
  if(TARGET tessera::arm922t_runtime)
    add_executable(${target} ${APP_SOURCES})
    set_target_properties(${target} PROPERTIES SUFFIX .elf)
    target_link_libraries(${target} PRIVATE tessera::sdk tessera::arm922t_runtime)
  else()
    add_library(${target} MODULE ${APP_SOURCES})
    target_link_libraries(${target} PRIVATE tessera::sdk)
    # A toolchain that links with -z defs would reject the undefined GL calls.
    target_link_options(${target} PRIVATE LINKER:-z,undefs)
  endif()
  # soc_sim ends the application's endless frame loop by throwing a C++
  # exception out of eglSwapBuffers; C frames need unwind tables for it to
  # pass through them on every architecture (on the ARM, unwinding stops
  # at a function without an entry in the unwind table, and the program
  # ends with status 1).
  target_compile_options(${target} PRIVATE $<$<COMPILE_LANG_AND_ID:C,GNU,Clang>:-fexceptions>)
endfunction()
