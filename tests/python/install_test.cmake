# ctest PythonInstalled: installs the penumbra, reference and python components into a
# scratch prefix and runs the Python tests against the installed module
# alone (PYTHONPATH the prefix's dist-packages, no build tree on it).
# cmake -DBUILD_DIR=... -DSOURCE_DIR=... -DSCRATCH=... -DPYTHON=... -DPYTHON_DIR=... -P install_test.cmake
file(REMOVE_RECURSE ${SCRATCH})
set(prefix ${SCRATCH}/prefix)
include(${CMAKE_CURRENT_LIST_DIR}/../install_components.cmake)
install_components(${BUILD_DIR} ${prefix} penumbra reference python)
set(ENV{PYTHONPATH} ${prefix}/${PYTHON_DIR})
# Run from the scratch folder: `python -c` and `python -m` put the working
# directory first on sys.path, and ctest's is the build tree's python/.
execute_process(COMMAND ${PYTHON} -c "import penumbra; print(penumbra.__file__)" WORKING_DIRECTORY ${SCRATCH}
                OUTPUT_VARIABLE where OUTPUT_STRIP_TRAILING_WHITESPACE RESULT_VARIABLE rc)
if(rc OR NOT where MATCHES "^${prefix}/")
  message(FATAL_ERROR "the installed module does not import from ${prefix} (rc ${rc}): '${where}'")
endif()
execute_process(COMMAND ${PYTHON} -m pytest -q -p no:cacheprovider ${SOURCE_DIR}/tests/python
                WORKING_DIRECTORY ${SCRATCH} RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "the Python tests failed against the installed module: ${rc}")
endif()
file(REMOVE_RECURSE ${SCRATCH})
