# One INTERFACE target, vots_sanitize (alias vots::sanitize), carries the sanitizer flags for our targets only.
# VOTS_SANITIZE: ASan + UBSan (preset asan); VOTS_TSAN: ThreadSanitizer (preset tsan); VOTS_FUZZ: libFuzzer
# coverage hooks in every object of ours (preset fuzz; only tests/fuzz links libFuzzer's main).
# Every target of ours links it, so libraries built by this project are instrumented and nothing else is.
add_library(vots_sanitize INTERFACE)
add_library(vots::sanitize ALIAS vots_sanitize)

if(VOTS_SANITIZE AND VOTS_TSAN)
  message(FATAL_ERROR "VOTS_SANITIZE (ASan) and VOTS_TSAN (ThreadSanitizer) cannot be combined")
endif()
if(VOTS_SANITIZE)
  target_compile_options(vots_sanitize INTERFACE -fsanitize=address,undefined -fno-omit-frame-pointer
                                                 -fno-sanitize-recover=undefined)
  target_link_options(vots_sanitize INTERFACE -fsanitize=address,undefined)
endif()
if(VOTS_TSAN)
  target_compile_options(vots_sanitize INTERFACE -fsanitize=thread -fno-omit-frame-pointer)
  target_link_options(vots_sanitize INTERFACE -fsanitize=thread)
endif()
if(VOTS_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
    message(FATAL_ERROR "VOTS_FUZZ needs clang (cmake --preset fuzz sets CC=clang CXX=clang++)")
  endif()
  target_compile_options(vots_sanitize INTERFACE -fsanitize=fuzzer-no-link,address,undefined -fno-omit-frame-pointer
                                                 -fno-sanitize-recover=undefined)
  target_link_options(vots_sanitize INTERFACE -fsanitize=address,undefined)
endif()
