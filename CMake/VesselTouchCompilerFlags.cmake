# Warnings are errors on project code; sanitizers apply to the whole build when asked for.

function(vtouch_target_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Werror)
endfunction()

if(VESSELTOUCH_SANITIZER)
  string(REPLACE ";" "," _vtouch_san "${VESSELTOUCH_SANITIZER}")
  add_compile_options(-fsanitize=${_vtouch_san} -fno-omit-frame-pointer -fno-sanitize-recover=all)
  add_link_options(-fsanitize=${_vtouch_san})
  message(STATUS "VesselTouch: sanitizers ${_vtouch_san}")
endif()
