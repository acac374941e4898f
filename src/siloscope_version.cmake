# Writes the version header at every build (not only when CMake configures), so that a binary's version names the
# commit it was built from: run by the siloscope_version target with -DSRC, -DIN, -DOUT and the values the
# configure step found (PROJECT_VERSION, CMAKE_BUILD_TYPE, SILOSCOPE_BOX2D_VERSION, SILOSCOPE_FONT). The header is
# replaced only when its text changes, so an unchanged commit rebuilds nothing.
execute_process(COMMAND git rev-parse --short=10 HEAD WORKING_DIRECTORY ${SRC}
                OUTPUT_VARIABLE SILOSCOPE_GIT OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
execute_process(COMMAND git status --porcelain --untracked-files=no WORKING_DIRECTORY ${SRC}
                OUTPUT_VARIABLE SILOSCOPE_DIRTY OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
if(NOT SILOSCOPE_GIT)
  set(SILOSCOPE_GIT "unknown")
elseif(SILOSCOPE_DIRTY)
  set(SILOSCOPE_GIT "${SILOSCOPE_GIT}-dirty")
endif()
configure_file(${IN} ${OUT}.tmp @ONLY)
execute_process(COMMAND ${CMAKE_COMMAND} -E copy_if_different ${OUT}.tmp ${OUT})
file(REMOVE ${OUT}.tmp)
