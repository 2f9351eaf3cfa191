# Warnings and sanitizers shared by every target of the project.
add_library(topple_options INTERFACE)
target_compile_options(topple_options INTERFACE -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wno-sign-conversion)
if(TOPPLE_SANITIZE)
  target_compile_options(topple_options INTERFACE -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined)
  target_link_options(topple_options INTERFACE -fsanitize=address,undefined)
endif()
