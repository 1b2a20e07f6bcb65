# Included by the top-level CMakeLists.txt when DAYLIT_FUZZ is on, before the libraries are
# added: everything compiled from here on carries libFuzzer's coverage hooks and AddressSanitizer
# and UndefinedBehaviorSanitizer (any UB report aborts, so the fuzzer sees it as a crash). The
# fuzz targets themselves add -fsanitize=fuzzer at link time (fuzz/CMakeLists.txt). (Under clang
# the kernels escalate to long double but not to __float128: illumination/real_vector.hpp.)
if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
  message(FATAL_ERROR "DAYLIT_FUZZ needs clang (libFuzzer): configure with -DCMAKE_CXX_COMPILER=clang++-14")
endif()
set(daylit_fuzz_sanitizers -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer)
# -O1 and assertions on: the fuzzers should see every precondition the code states.
add_compile_options(-fsanitize=fuzzer-no-link ${daylit_fuzz_sanitizers} -O1 -gline-tables-only -UNDEBUG)
add_link_options(-fsanitize=address,undefined)
# The visibility routine's exact shortcuts (shadow_clipping.hpp) are checked against the exact
# signs they stand for whenever the rational path takes one.
add_compile_definitions(DAYLIT_CHECK_SYMBOLIC)

