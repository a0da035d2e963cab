# ASan + UBSan for the whole build when VOTS_SANITIZE is on (preset "asan"); libFuzzer coverage with VOTS_FUZZ.
if(VOTS_SANITIZE)
  add_compile_options(-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined)
  add_link_options(-fsanitize=address,undefined)
endif()
# VOTS_FUZZ (preset "fuzz"): every object gets fuzzer coverage hooks; only tests/fuzz links libFuzzer's main.
if(VOTS_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
    message(FATAL_ERROR "VOTS_FUZZ needs clang (cmake --preset fuzz sets CC=clang CXX=clang++)")
  endif()
  add_compile_options(-fsanitize=fuzzer-no-link,address,undefined -fno-omit-frame-pointer
                      -fno-sanitize-recover=undefined)
  add_link_options(-fsanitize=address,undefined)
endif()
