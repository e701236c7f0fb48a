# Project-wide warning set, applied per target by inet_stage_library / inet_stage_test.
function(inet_set_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wno-unused-parameter)
endfunction()
