# sysid_set_warnings(target): the project's warning policy, applied to every target we own.
function(sysid_set_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic)
  if(SYSID_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
  if(SYSID_SANITIZE)
    target_compile_options(${target} PRIVATE -fsanitize=address,undefined -fno-omit-frame-pointer
                                             -fno-sanitize-recover=undefined)
    target_link_options(${target} PRIVATE -fsanitize=address,undefined)
    # GCC's flow analysis is unreliable under -fsanitize: it reports maybe-uninitialized inside
    # libstdc++'s <regex> (reached through Catch2). The Release pass keeps the warning on.
    if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
      target_compile_options(${target} PRIVATE -Wno-maybe-uninitialized)
    endif()
  endif()
endfunction()
