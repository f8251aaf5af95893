# geodual_target_defaults(<target>): warnings (errors when GEODUAL_WERROR) and
# sanitizers for geodual's own code. Third-party headers are included as SYSTEM
# through their imported targets, so their warnings never fail our build.
function(geodual_target_defaults target)
  target_compile_features(${target} PUBLIC cxx_std_20)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wconversion
                                           -Wno-sign-conversion)
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND CMAKE_CXX_COMPILER_VERSION VERSION_LESS 14)
    # GCC 12/13 report false positives from inlined standard-library code at
    # -O2 and above (GCC bugs 105329, 105651, 106199: "restrict" overlaps and
    # "stringop-overflow" in std::string / std::vector growth). They are not
    # about our code, so they must not fail the build.
    target_compile_options(${target} PRIVATE -Wno-restrict -Wno-stringop-overflow -Wno-array-bounds)
  endif()
  if(GEODUAL_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()

if(GEODUAL_SANITIZE)
  add_compile_options(-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined)
  add_link_options(-fsanitize=address,undefined)
endif()
