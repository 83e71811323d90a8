# The reference experiments inside the FMUs (FMI-LS-REF, python/plateimpact/references.py):
# written by tools/write_references.py from the FMI 2.0 FMU as built (its spreads also from the
# FMI 3.0 one), then added to both FMUs and to their packaging stages (the dual-platform scripts
# zip those), so that every PlateImpact FMU carries the same extra/org.fmi-standard.fmi-ls-ref/
# and documentation/fmi-ls-ref.html. Needs the project's venv (scripts/setup.sh makes it before it
# builds): PLATEIMPACT_PYTHON, default <repo>/.venv/bin/python. Off in sanitizer and cross
# builds (their FMUs are not run by a plain Python) and with -DPLATEIMPACT_REFERENCES=OFF.
option(PLATEIMPACT_REFERENCES "Generate the FMI-LS-REF reference experiments into the FMUs" ON)
set(PLATEIMPACT_PYTHON "${CMAKE_SOURCE_DIR}/.venv/bin/python" CACHE FILEPATH "Python with fmpy and plateimpact")
if(PLATEIMPACT_REFERENCES AND NOT PLATEIMPACT_SANITIZE AND NOT CMAKE_CROSSCOMPILING)
  if(NOT EXISTS "${PLATEIMPACT_PYTHON}")
    message(FATAL_ERROR "PLATEIMPACT_PYTHON=${PLATEIMPACT_PYTHON} not found: run scripts/setup.sh, or "
                        "-DPLATEIMPACT_REFERENCES=OFF to build FMUs without reference experiments")
  endif()
  set(fmu2 "${CMAKE_BINARY_DIR}/PlateImpact.fmu")
  set(fmu3 "${CMAKE_BINARY_DIR}/fmi3/PlateImpact.fmu")
  set(tree "${CMAKE_BINARY_DIR}/references")
  set(stamp "${tree}.stamp")
  file(GLOB references_py CONFIGURE_DEPENDS "${CMAKE_SOURCE_DIR}/python/plateimpact/*.py")
  add_custom_command(
    OUTPUT "${stamp}"
    COMMAND "${CMAKE_COMMAND}" -E rm -rf "${tree}"
    COMMAND "${CMAKE_COMMAND}" -E env "PYTHONPATH=${CMAKE_SOURCE_DIR}/python" "${PLATEIMPACT_PYTHON}"
            "${CMAKE_SOURCE_DIR}/tools/write_references.py" "${fmu2}" "${tree}" --fmi3 "${fmu3}"
            --report "${tree}.json" --add-to "${fmu2}" "${fmu3}" "${CMAKE_CURRENT_BINARY_DIR}/PlateImpact.fmu.d"
            "${CMAKE_CURRENT_BINARY_DIR}/fmi3/PlateImpact.fmu.d"
    COMMAND "${CMAKE_COMMAND}" -E touch "${stamp}"
    DEPENDS PlateImpactFmu PlateImpactFmu3 "${fmu2}" "${fmu3}" ${references_py}
            "${CMAKE_SOURCE_DIR}/tools/write_references.py"
    WORKING_DIRECTORY "${CMAKE_SOURCE_DIR}/python"
    COMMENT "Generating the reference experiments (FMI-LS-REF) into both PlateImpact FMUs"
    VERBATIM)
  add_custom_target(PlateImpactReferences ALL DEPENDS "${stamp}")
endif()
