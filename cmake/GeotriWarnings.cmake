# Warnings and strict floating point for geotri's own targets. Exact results must not change with the compiler's
# whims, so no -ffast-math and no fused multiply-add contraction.
function(geotri_target_defaults target)
  target_compile_features(${target} PUBLIC cxx_std_17)
  if(CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
    target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -ffp-contract=off)
  endif()
endfunction()
