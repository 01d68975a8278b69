# install_components(BUILD_DIR PREFIX COMPONENT...): `cmake --install` of each
# component into PREFIX, stopping the script on the first that fails. Shared
# by the install tests (tests/install_test.cmake, tests/python/install_test.cmake).
function(install_components build_dir prefix)
  foreach(component IN LISTS ARGN)
    execute_process(COMMAND ${CMAKE_COMMAND} --install ${build_dir} --prefix ${prefix} --component ${component}
                    RESULT_VARIABLE rc OUTPUT_QUIET)
    if(rc)
      message(FATAL_ERROR "installing component ${component} failed: ${rc}")
    endif()
  endforeach()
endfunction()
