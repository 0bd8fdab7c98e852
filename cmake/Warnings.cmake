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
endif()
