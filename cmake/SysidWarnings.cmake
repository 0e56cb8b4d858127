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
  endif()
endfunction()
