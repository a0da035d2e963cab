# ASan + UBSan for the whole build when VOTS_SANITIZE is on (preset "asan").
if(VOTS_SANITIZE)
  add_compile_options(-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined)
  add_link_options(-fsanitize=address,undefined)
endif()
