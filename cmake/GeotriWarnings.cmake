# Warnings and strict floating point for geotri's own targets. Exact results must not change with the compiler's
# whims, so no -ffast-math and no fused multiply-add contraction. Nothing reads errno: without it a square root is one
# instruction, with no test and branch to the library for negative arguments (the result is the same, NaN).
function(geotri_target_defaults target)
  target_compile_features(${target} PUBLIC cxx_std_17)
  if(CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
    target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -ffp-contract=off -fno-math-errno)
  endif()
endfunction()
