# One INTERFACE target carries our warning flags, so third-party code is unaffected.
add_library(vots_warnings INTERFACE)
target_compile_options(vots_warnings INTERFACE -Wall -Wextra -Wpedantic -Wshadow)
if(VOTS_WERROR)
  target_compile_options(vots_warnings INTERFACE -Werror)
endif()
