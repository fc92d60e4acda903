# Warnings for the project's own targets; every target links mpile_warnings.
add_library(mpile_warnings INTERFACE)
target_compile_options(mpile_warnings INTERFACE
  -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor -Wold-style-cast -Wcast-align
  -Woverloaded-virtual -Wnull-dereference -Wformat=2 -Wimplicit-fallthrough -Wmisleading-indentation)
option(MPILE_WERROR "Treat warnings as errors" ON)
if(MPILE_WERROR)
  target_compile_options(mpile_warnings INTERFACE -Werror)
endif()
if(NOT MPILE_SANITIZE STREQUAL "")
  # GCC 12's flow analysis reports false "maybe-uninitialized" and "null-dereference" warnings
  # inside std::variant, std::vector and std::string once sanitizer instrumentation is added;
  # release builds keep both warnings.
  target_compile_options(mpile_warnings INTERFACE -Wno-maybe-uninitialized -Wno-null-dereference)
endif()
