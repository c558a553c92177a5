# Strict warnings on our own targets only; third-party headers come from
# /usr/include and are treated as system headers.
function(animorph_target_defaults target)
  # -Wno-restrict: GCC 12 reports false positives inside std::string's
  # operator+ at -O3 (GCC bug 105329).
  target_compile_options(${target} PRIVATE -Wall -Wextra -Werror)
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    target_compile_options(${target} PRIVATE -Wno-restrict)
  endif()
  if(ANIMORPH_SANITIZE AND CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    # Sanitizer instrumentation makes GCC 12 report false maybe-uninitialized
    # warnings in third-party headers (Catch2's regex use, std::optional).
    target_compile_options(${target} PRIVATE -Wno-maybe-uninitialized)
  endif()
  target_compile_features(${target} PUBLIC cxx_std_20)
endfunction()
