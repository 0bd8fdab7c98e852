# One warning policy for every target of the project. (-Wnull-dereference is left
# out: GCC 12 reports it falsely inside libstdc++ at -O2.)
add_library(tankfsi_warnings INTERFACE)
target_compile_options(tankfsi_warnings INTERFACE
  -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor -Wold-style-cast
  -Wcast-align -Woverloaded-virtual -Wdouble-promotion
  -Wimplicit-fallthrough)
if(TANKFSI_WERROR)
  target_compile_options(tankfsi_warnings INTERFACE -Werror)
endif()
if(TANKFSI_SANITIZE)
  target_compile_options(tankfsi_warnings INTERFACE
    -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined)
  target_link_options(tankfsi_warnings INTERFACE -fsanitize=address,undefined)
  # GCC 12's -Wmaybe-uninitialized misfires on ASan-instrumented libstdc++ code
  # (std::function inside std::regex, reached from Catch2), which -Werror would
  # turn into a failed build; the release build keeps the warning.
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    target_compile_options(tankfsi_warnings INTERFACE -Wno-maybe-uninitialized)
  endif()
endif()
# Coverage instrumentation for libFuzzer in every library the fuzz targets link.
if(TANKFSI_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "TANKFSI_FUZZ needs clang (the fuzz preset), not ${CMAKE_CXX_COMPILER_ID}")
  endif()
  target_compile_options(tankfsi_warnings INTERFACE -fsanitize=fuzzer-no-link)
endif()
