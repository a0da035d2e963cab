# One INTERFACE target, vots_warnings (alias vots::warnings), carries our warning flags, so third-party code is unaffected.
add_library(vots_warnings INTERFACE)
add_library(vots::warnings ALIAS vots_warnings)
target_compile_options(vots_warnings INTERFACE -Wall -Wextra -Wpedantic -Wshadow)
if(VOTS_WERROR)
  target_compile_options(vots_warnings INTERFACE -Werror)
endif()
