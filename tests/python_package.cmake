# The Python package (python/mpile) and the ParaView script's decisions: pytest on histories and
# snapshots whose values are known (the synthetic run, files written with h5py and VTK) and on a
# real run of V7 made by this build's mpile (MPILE). docs/python.md. Labelled python: under ASan it
# cost 36 s for its one run of V7, which VerificationFiles.V7BlockSlidesAsCoulombFrictionSays makes.
add_test(NAME PythonPackage.Pytest
         COMMAND /usr/bin/python3 -m pytest -q -p no:cacheprovider -m "not install"
                 ${PROJECT_SOURCE_DIR}/python/tests)
set_tests_properties(PythonPackage.Pytest PROPERTIES LABELS python
                     ENVIRONMENT "MPILE=$<TARGET_FILE:mpile>"
                     PASS_REGULAR_EXPRESSION " passed" FAIL_REGULAR_EXPRESSION " (failed|skipped|error)")

# pip install into a temporary virtual environment, offline, then `import mpile` from outside the
# repository (about 7 s).
add_test(NAME PythonPackage.PipInstallAndImport
         COMMAND /usr/bin/python3 -m pytest -q -p no:cacheprovider -m install
                 ${PROJECT_SOURCE_DIR}/python/tests)
set_tests_properties(PythonPackage.PipInstallAndImport PROPERTIES LABELS python
                     PASS_REGULAR_EXPRESSION "1 passed" FAIL_REGULAR_EXPRESSION " (failed|skipped|error)")

# tools/paraview_open_run.py under ParaView's own Python, where ParaView is installed: the pipeline
# on the synthetic run must show the 2300 soil particles (the pile block thresholded away), both
# snapshot times, and the range symmetric about zero (+/- 9 kPa).
find_program(PVPYTHON pvpython)
if(PVPYTHON)
  add_test(NAME PythonPackage.ParaViewOpensTheSyntheticRun
           COMMAND ${PVPYTHON} --force-offscreen-rendering ${PROJECT_SOURCE_DIR}/tools/paraview_open_run.py
                   ${synthetic_run} --pile-body 1 --screenshot ${synthetic_run}/paraview.png)
  set_tests_properties(PythonPackage.ParaViewOpensTheSyntheticRun PROPERTIES
    FIXTURES_REQUIRED synthetic_monopile
    PASS_REGULAR_EXPRESSION
    "paraview: 2 time steps from 0 to 2\\.5 s; 2300 particles shown at t = 2\\.5 s; colour range -9000 to 9000\n")
endif()
