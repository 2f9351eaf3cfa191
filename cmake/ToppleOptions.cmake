# Warnings and sanitizers shared by every target of the project.
# Precompiled headers for the test executables (tests/CMakeLists.txt): third-party and standard headers only; the
# library's sources have none (the Python package's build reuses their release objects through ccache,
# docs/performance.md). OFF to check that each test source includes what it uses.
option(TOPPLE_PRECOMPILE_HEADERS "Precompile the third-party headers of the test executables" ON)
add_library(topple_options INTERFACE)
target_compile_options(topple_options INTERFACE -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wno-sign-conversion)
if(TOPPLE_SANITIZE)
  target_compile_options(topple_options INTERFACE -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined)
  target_link_options(topple_options INTERFACE -fsanitize=address,undefined)
  # The `topple` command (target topple_cli) is argument parsing and printing, every computation a library call
  # (cli/CMakeLists.txt): under the sanitizers it compiles at -O0, the library at the preset's -O1. Optimisation and
  # code generation are most of an ASan compile (cli/cmd_info.cpp: 27 s of CPU at -O1, 18 s at -O0), and -O0 hides
  # no access from ASan. The test executables do the same for their own code (tests/CMakeLists.txt).
  target_compile_options(topple_options INTERFACE $<$<STREQUAL:$<TARGET_PROPERTY:NAME>,topple_cli>:-O0>)
endif()
