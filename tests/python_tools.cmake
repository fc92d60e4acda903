# A pytest file of tests/ as the test NAME: Python alone, no engine code, so nothing for a sanitizer
# to look at (label python, release only).
function(add_pytest name file)
  add_test(NAME ${name} COMMAND /usr/bin/python3 -m pytest -q -p no:cacheprovider
                                ${PROJECT_SOURCE_DIR}/tests/${file})
  set_tests_properties(${name} PROPERTIES LABELS python)
endfunction()

# A Python script of the tree (PATH from the source root) as the test NAME, passing when its output
# matches REGEX (its exit status is not looked at: the scripts print what they found either way).
function(add_python_check name path regex)
  add_test(NAME ${name} COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/${path})
  set_tests_properties(${name} PROPERTIES PASS_REGULAR_EXPRESSION "${regex}")
endfunction()

# The monopile post-processing tools on a synthetic run whose values are known exactly
# (tests/make_monopile_history.py): the tests check printed numbers and colours, not only that the
# tools ran.
set(synthetic_run ${CMAKE_CURRENT_BINARY_DIR}/synthetic_monopile)
add_test(NAME MonopileTools.MakeSyntheticRun
         COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/tests/make_monopile_history.py ${synthetic_run})
set_tests_properties(MonopileTools.MakeSyntheticRun PROPERTIES FIXTURES_SETUP synthetic_monopile)

# At 0.3 m (3 s into the installation): the forces of the synthetic history in kN/rad, F_y / F_r = 0.4
# and sqrt(F_y^2 + F_theta^2) / F_r = 0.5 on both shafts; 0.6 m is beyond the 0.5 m reached.
add_test(NAME PlotMonopile.TableAtPenetrations
         COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/tools/plot_monopile.py ${synthetic_run}
                 --out ${synthetic_run}/table_figures --table 0.3,0.6)
set_tests_properties(PlotMonopile.TableAtPenetrations PROPERTIES FIXTURES_REQUIRED synthetic_monopile
  PASS_REGULAR_EXPRESSION
  "\n\"synthetic monopile\" +0\\.3000 +3\\.0000 +6\\.000 +150\\.000 +-12\\.000 +-60\\.000 +24\\.000 +-18\\.000 +30\\.000 +12\\.000 +-9\\.000 +0\\.4000 +0\\.5000 +0\\.4000 +0\\.5000\n\"synthetic monopile\" +0\\.6000 +not reached\n")
add_test(NAME PlotMonopile.WritesFivePngs
         COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/tools/plot_monopile.py ${synthetic_run}:jacked
                 ${synthetic_run}:again --out ${synthetic_run}/figures --smooth 0.5)
set_tests_properties(PlotMonopile.WritesFivePngs PROPERTIES FIXTURES_REQUIRED synthetic_monopile
  PASS_REGULAR_EXPRESSION
  "/figures/fig3_radial_forces\\.png\n[^\n]*/figures/fig4_vertical_forces\\.png\n[^\n]*/figures/fig5_friction_ratio\\.png\n[^\n]*/figures/fig6_total_friction_ratio\\.png\n[^\n]*/figures/fig7_penetration\\.png\n")
# Figures 5 and 6 on the synthetic history, whose ratios lie on mu all along: the dashed mu line
# beneath the curves and lighter than black, each curve with its own markers, and the pixels along
# mu in the curve's colour (28 % with the black line drawn over it, as before).
add_test(NAME PlotMonopile.CurveOnTheFrictionLineStaysInView
         COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/tests/plot_monopile_test.py
                 ${CMAKE_CURRENT_BINARY_DIR}/plot_monopile)
set_tests_properties(PlotMonopile.CurveOnTheFrictionLineStaysInView PROPERTIES
                     PASS_REGULAR_EXPRESSION "\nall ok\n")

# tools/saturated_table.py at 0.3 m (3 s into the installation, t = 3.49 s) and at the 0.501 m where
# the synthetic run stops: its forces with the pore water's 3/4 of F_r and 1/2 of F_y in brackets,
# the friction over the effective F_r (0.5 / (1 - 3/4) = 2), the monitors' excess pore pressure
# compression positive, the last row's step and wall
# time; then the figure of the monitors' excess pore pressure against time.
add_test(NAME SaturatedTable.ForcesPorePartsAndExcessPressure
         COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/tools/saturated_table.py
                 ${synthetic_run}:synthetic --at 0.3,0.6 --figure ${synthetic_run}/excess_u.png)
set_tests_properties(SaturatedTable.ForcesPorePartsAndExcessPressure PROPERTIES
  FIXTURES_REQUIRED synthetic_monopile
  PASS_REGULAR_EXPRESSION
  "\\| synthetic \\| 5 500 \\| 55 \\| 0\\.3 m \\| 3\\.490 \\| 150\\.0 \\(75\\.0\\) \\| -60\\.0 \\(-45\\.0\\) \\| 30\\.0 \\(22\\.5\\) \\| 2\\.00 \\| 2\\.00 \\| 300 / 150 / 60 / 30 \\|\n[^\n]*0\\.501 m \\(stopped\\)[^\n]*\n[^\n]*/excess_u\\.png\n")

# The renderer on the synthetic snapshots: sigma_ry = 10 kPa/m * (r + y - 1 m) around a pile block
# (body 1) whose 1e9 Pa must stay off the range and the colours. Red at the maximum (top right), blue at
# the minimum (bottom left), so a wrong colour map, mirrored view or unfitted camera fails.
add_test(NAME RenderSigmaRy.MissingArrayNamesTheArrays
         COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/tools/render_sigma_ry.py
                 ${synthetic_run}/particles.pvd --out ${synthetic_run}/missing.png --array sigma_zz)
set_tests_properties(RenderSigmaRy.MissingArrayNamesTheArrays PROPERTIES FIXTURES_REQUIRED synthetic_monopile
  PASS_REGULAR_EXPRESSION "particles_000001\\.vtu has no scalar point array sigma_zz; it has: sigma_ry, body, material")
# Drawn with matplotlib (Agg): no display needed. Each particle is painted over its own domain; the
# synthetic snapshots have no volumes, so every domain is the lattice's 0.02 m spacing.
add_test(NAME RenderSigmaRy.RangeAndColours
         COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/tools/render_sigma_ry.py
                 ${synthetic_run}/particles.pvd --out ${synthetic_run}/sigma_ry.png --pile-body 1
                 --check-pixel 0.95 0.95 --check-pixel 0.05 0.05 --check-pixel 0.05 0.95
                 --check-pixel 0.5 0.8 --coverage)
set_tests_properties(RenderSigmaRy.RangeAndColours PROPERTIES FIXTURES_REQUIRED synthetic_monopile
  PASS_REGULAR_EXPRESSION
  "sigma_ry in window: -9\\.8 to 9\\.8 kPa \\(2300 particles\\)\ncolour range: -9 to 9 kPa\ndomains: [^\n]*sides 0\\.02 to 0\\.02 m\npile tip at y = 0\\.6 m\npixel at \\(0\\.95, 0\\.95\\): red [^\n]*\npixel at \\(0\\.05, 0\\.05\\): blue [^\n]*\npixel at \\(0\\.05, 0\\.95\\): white [^\n]*\npixel at \\(0\\.5, 0\\.8\\): grey [^\n]*\nsoil coverage: 1\\.0000 of [0-9]+ pixels[^\n]*\n[^\n]*/sigma_ry\\.png\n")
# The first snapshot (half the field) picked by time, the top half of the domain, the pile left out.
add_test(NAME RenderSigmaRy.TimeWindowAndExcludedBody
         COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/tools/render_sigma_ry.py
                 ${synthetic_run}/particles.pvd --out ${synthetic_run}/sigma_ry_top.png --time 0.2
                 --window 0 1 0.5 1 --exclude-body 1 --check-pixel 0.95 0.95 --check-pixel 0.5 0.8)
set_tests_properties(RenderSigmaRy.TimeWindowAndExcludedBody PROPERTIES FIXTURES_REQUIRED synthetic_monopile
  PASS_REGULAR_EXPRESSION
  "sigma_ry in window: -2\\.4 to 4\\.9 kPa \\(1050 particles\\)\n[^\n]*\n[^\n]*\npixel at \\(0\\.95, 0\\.95\\): red [^\n]*\npixel at \\(0\\.5, 0\\.8\\): white \\(RGB 255 255 255\\)\n[^\n]*/sigma_ry_top\\.png\n")
# A graded snapshot (0.025 m particles beside 0.1 m and 0.1 by 0.05 m ones, a thin pile wall;
# volumes per radian): the soil's bounding box covered (> 99 % of its pixels coloured; points one
# spacing wide, as drawn before, covered 34 %), the axes labelled in m, the colour bar in kPa and
# symmetric, the pile grey and its tip marked; on a field beyond its colour range, the colour bar
# ends in arrows on the clipped sides only and its label gives the clipping and the field's range.
add_test(NAME RenderSigmaRy.GradedSoilCoveredWithLabelledAxes
         COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/tests/render_sigma_ry_test.py
                 ${CMAKE_CURRENT_BINARY_DIR}/render_sigma_ry)
set_tests_properties(RenderSigmaRy.GradedSoilCoveredWithLabelledAxes PROPERTIES
                     PASS_REGULAR_EXPRESSION "\nall ok\n")
find_program(XVFB_RUN xvfb-run)

# The accuracy tool on its V6 study: every run measured, the CSV written, and the observed orders
# printed. Run to the phase runner's equilibrium (out-of-balance force and kinetic energy ratios
# below 1e-9), the cap torque converges at second order in h whatever the option set: its errors
# quarter from 1.95e-3 with each halving of h (docs/accuracy.md). A tool that mislabels option
# sets, mixes up h or fits the wrong quantity prints other numbers.
add_test(NAME AccuracyTool.V6StudyOrders
         COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/tools/accuracy.py --studies V6
                 --mpile $<TARGET_FILE:mpile> --out ${CMAKE_CURRENT_BINARY_DIR}/accuracy_v6)
set_tests_properties(AccuracyTool.V6StudyOrders PROPERTIES
  PASS_REGULAR_EXPRESSION
  "MUSL, C = 0\\.8 +observed order in h: (1\\.9[5-9]|2\\.0[0-5])\n.*USL, C = 0\\.8 +observed order in h: (1\\.9[5-9]|2\\.0[0-5])\n.*table -> [^\n]*accuracy_v6/accuracy\\.csv")

# The stability tool on its Courant rows and the disc: each run's outcome read from its history.
# The bar is stable up to C = 0.95 and the Courant guard stops it at step 1 from C = 1.0 on; the
# disc's contact force must equal its weight to 0.1 % (docs/stability.md). A tool that mislabels
# settings, reads the wrong status or measures the wrong surface prints other rows.
add_test(NAME StabilityTool.CourantRowsAndDisc
         COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/tools/stability.py --rows courant disc
                 --no-docs --mpile $<TARGET_FILE:mpile> --out ${CMAKE_CURRENT_BINARY_DIR}/stability)
set_tests_properties(StabilityTool.CourantRowsAndDisc PROPERTIES
  PASS_REGULAR_EXPRESSION
  "C = 0\\.95 +stable[^\n]*\n[^\n]*C = 1\\.0 +stopped: step 1, t = [^\n]*Courant number reached 1\\.0[^\n]*\n[^\n]*C = 1\\.2 +stopped: step 1, [^\n]*Courant number reached 1\\.2[^\n]*\n.*E ratio 2\\.2e5 \\| stable \\|[^\n]*its weight 627\\.8, [+-]0\\.0[0-9] %")

# The two studies above run dozens of whole cases through the Python tools: minutes under the
# sanitizers for no code path the suite's own thread-identity and contact tests do not already
# exercise there. The sanitizer presets (CMakePresets.json) leave the label "study" out.
set_tests_properties(AccuracyTool.V6StudyOrders StabilityTool.CourantRowsAndDisc PROPERTIES
                     LABELS study)

# The CPT regression case (cases/cpt/cpt_coarse.toml, 2 cells per cone radius, jacked 0.15 m)
# through the CPT tool. Measured at this resolution (105305c, the tool's 0.025 m windows): q_c =
# 6.29 MPa at 0.10 m; 4 cells per radius give 5.58 there (docs/cpt.md). The band [5.9, 6.9] MPa
# holds round-off across compilers and halving the penetration rate (6.04), and leaves out a flat-
# ended rod (5.71 since tip corners are split over their surfaces; 5.28 before), a frictionless cone
# (4.13), a fully rough one (mu = tan phi': 7.47 at 71f97d1) and a lost surcharge (q_c grows with
# sigma'_v0 to a power of 0.5 or more). Commands: docs/cpt.md, "Factor by factor".
set(cpt_output ${CMAKE_CURRENT_BINARY_DIR}/cpt_coarse)
add_test(NAME CptTool.RunTheCoarseChamber
         COMMAND mpile run ${PROJECT_SOURCE_DIR}/cases/cpt/cpt_coarse.toml --out ${cpt_output})
set_tests_properties(CptTool.RunTheCoarseChamber PROPERTIES FIXTURES_SETUP cpt_coarse
                     LABELS study)
add_test(NAME CptTool.ConeResistanceAtTenCentimetres
         COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/tools/cpt.py ${cpt_output}/history.h5
                 --step 0.025 --expect-qc 0.10 5.9 6.9)
set_tests_properties(CptTool.ConeResistanceAtTenCentimetres PROPERTIES
                     FIXTURES_REQUIRED cpt_coarse LABELS study)
# [output.cpt]: the history's q_c, f_s and R_f against the standard cone's areas.
add_test(NAME CptTool.HistoryHoldsQcFsAndRfOverTheStandardAreas
         COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/tests/check_cpt_history.py
                 ${cpt_output}/history.h5)
set_tests_properties(CptTool.HistoryHoldsQcFsAndRfOverTheStandardAreas PROPERTIES
                     FIXTURES_REQUIRED cpt_coarse LABELS study PASS_REGULAR_EXPRESSION "\nok\n")

# The coarse chamber in the seed's sand in hypoplasticity (cases/cpt/cpt_coarse_hypoplastic.toml,
# XPIC(2)) jacked 3 cm (about 8 s on one thread). Under FLIP, whose particle velocity modes the grid
# does not see go unfiltered, q_c at 2.5 cm is 3.03 MPa; jacked on to 0.7 m it peaks at 5.8 MPa at
# 0.3 m and falls to 2.7 as the sand ahead of the cone densifies and loses its stress. Under XPIC(2) it is 6.15 MPa there (6.16 in the
# chamber jacked to 1.2 m, which levels off at 11.9 to 12.6 MPa from 0.4 m; docs/hypoplasticity.md,
# "The CPT chamber"). The band [5.0, 7.5] MPa leaves FLIP's value out by 40 %.
set(cpt_hypoplastic_output ${CMAKE_CURRENT_BINARY_DIR}/cpt_coarse_hypoplastic)
add_test(NAME CptTool.RunTheHypoplasticChamber
         COMMAND mpile run ${PROJECT_SOURCE_DIR}/cases/cpt/cpt_coarse_hypoplastic.toml --threads 1
                 --out ${cpt_hypoplastic_output} --set phases.1.stop_at.penetration=0.03
                 --set output.snapshot_penetrations=[])
set_tests_properties(CptTool.RunTheHypoplasticChamber PROPERTIES
                     FIXTURES_SETUP cpt_coarse_hypoplastic LABELS study)
add_test(NAME CptTool.HypoplasticConeResistanceAtTwoAndAHalfCentimetres
         COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/tools/cpt.py
                 ${cpt_hypoplastic_output}/history.h5 --step 0.005 --expect-qc 0.025 5.0 7.5)
set_tests_properties(CptTool.HypoplasticConeResistanceAtTwoAndAHalfCentimetres PROPERTIES
                     FIXTURES_REQUIRED cpt_coarse_hypoplastic LABELS study)

# The coarse chamber saturated (docs/saturated.md, "The cone at drained to undrained rates"),
# undrained and coupled at k = 1e-5 m/s (V = 0.55, about half of the change), pushed 1.25 cm
# (about 15 and 20 s), q_c within a quarter of the tool's 0.01 m windows of 1 cm. Measured at
# 781a95c, as the documented runs to 0.15 m give there: 0.369 and 0.751 MPa (0.754 since the
# particles' water and skeleton relax against each other); drained 1.73, k = 1e-4 1.41, k = 1e-6
# 0.414. The coupled band [0.65, 0.95] is where a factor of 2 either way in k (in
# c_v, or in the drag) would put it, interpolating those runs in log V; the undrained band [0.32,
# 0.41] keeps it below k = 1e-6's partial drainage and as far below.
set(cpt_saturated --set materials.sand.grain_density=2650.0 --set solver.implicit_pore_pressure=true
    --set solver.cell_mean_pore_pressure=true --set phases.1.mass_scaling=1.0
    --set phases.1.stop_at.penetration=0.0125 --set output.snapshot_penetrations=[])
foreach(water undrained coupled)
  set(cpt_water_output ${CMAKE_CURRENT_BINARY_DIR}/cpt_coarse_${water})
  set(cpt_water --set materials.sand.drainage="${water}")
  set(cpt_band 0.01 0.32 0.41)
  if(water STREQUAL "coupled")
    list(APPEND cpt_water --set materials.sand.hydraulic_conductivity=1e-5)
    set(cpt_band 0.01 0.65 0.95)
  endif()
  add_test(NAME CptTool.RunTheSaturatedChamber_${water}
           COMMAND mpile run ${PROJECT_SOURCE_DIR}/cases/cpt/cpt_coarse.toml --threads 1
                   --out ${cpt_water_output} ${cpt_saturated} ${cpt_water})
  set_tests_properties(CptTool.RunTheSaturatedChamber_${water} PROPERTIES
                       FIXTURES_SETUP cpt_coarse_${water} LABELS study)
  add_test(NAME CptTool.SaturatedConeResistanceAtOneCentimetre_${water}
           COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/tools/cpt.py
                   ${cpt_water_output}/history.h5 --step 0.01 --expect-qc ${cpt_band})
  set_tests_properties(CptTool.SaturatedConeResistanceAtOneCentimetre_${water} PROPERTIES
                       FIXTURES_REQUIRED cpt_coarse_${water} LABELS study)
endforeach()

# The coarse chamber undrained and dilative (psi = 7.5 degrees) with the water cavitating at 100
# kPa, pushed 1.5 cm (about 30 s; docs/saturated.md, "The cut-off with the implicit pore
# pressure"). Its water cavitates in the cone's wall cells: capped only after a solve that left
# them free, the velocities took the suction the stress did not keep and the run went unstable at
# 1.0 cm (ledger 52 %, q_c 4.44 MPa at 1 cm and rising). The ledger must close within 2 % (held in
# the solve: 0.19 % at the end, 0.46 % peak, to 3 cm) and q_c at 1 cm lie in [3.1, 3.7] MPa: the
# three consistent treatments tried (held, held where in contact, clamped after the solve) gave
# 3.35 to 3.43, and the band leaves out the unstable run's 4.44.
set(cpt_cavitating_output ${CMAKE_CURRENT_BINARY_DIR}/cpt_coarse_cavitating)
add_test(NAME CptTool.RunTheDilativeUndrainedChamberCavitating
         COMMAND mpile run ${PROJECT_SOURCE_DIR}/cases/cpt/cpt_coarse.toml --threads 1
                 --out ${cpt_cavitating_output} ${cpt_saturated}
                 --set phases.1.stop_at.penetration=0.015 --set materials.sand.drainage="undrained"
                 --set materials.sand.dilatancy_angle=7.5 --set water.cavitation_stress=100e3)
set_tests_properties(CptTool.RunTheDilativeUndrainedChamberCavitating PROPERTIES
  FIXTURES_SETUP cpt_coarse_cavitating LABELS study
  PASS_REGULAR_EXPRESSION "done: [^\n]*energy residual [01]\\.[0-9]+ % at the end, peak [01]\\.[0-9]+ %")
add_test(NAME CptTool.DilativeUndrainedConeResistanceAtOneCentimetre
         COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/tools/cpt.py
                 ${cpt_cavitating_output}/history.h5 --step 0.005 --expect-qc 0.01 3.1 3.7)
set_tests_properties(CptTool.DilativeUndrainedConeResistanceAtOneCentimetre PROPERTIES
                     FIXTURES_REQUIRED cpt_coarse_cavitating LABELS study)

# tools/cpt_rate.py on those runs and the dry chamber's (mass-scaled: 1.88 MPa at 1 cm, a drained
# limit for the arithmetic): V = v d / (k E_oed / gamma_w) = 0.5 x 0.0357 / (1e-5 x 31.9e6 / 9810) =
# 0.549, q_c / q_c,d = 0.754 / 1.876 = 0.40, (0.754 - 0.369) / (1.876 - 0.369) = 0.26 (0.751 and
# 0.25 before the particles' water and skeleton relaxed against each other, momentum kept).
add_test(NAME CptTool.RateTableGivesVAndTheNormalisedResistance
         COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/tools/cpt_rate.py ${cpt_output}:drained
                 ${CMAKE_CURRENT_BINARY_DIR}/cpt_coarse_undrained:undrained
                 ${CMAKE_CURRENT_BINARY_DIR}/cpt_coarse_coupled:1e-5 --eoed 31.9e6 --velocity 0.5
                 --depth 0.01 --half-window 0.0025)
set_tests_properties(CptTool.RateTableGivesVAndTheNormalisedResistance PROPERTIES
                     FIXTURES_REQUIRED "cpt_coarse;cpt_coarse_undrained;cpt_coarse_coupled"
                     LABELS study
                     PASS_REGULAR_EXPRESSION "\\| 1e-05 \\| 0\\.549 \\| 0\\.75 \\| 0\\.40 \\| 0\\.26 \\|")

# The chamber's plane-strain strip (docs/cpt.md, "The pile tip against the cone"): written by
# make_cases.py, run 2 cm (about 4 s), held to its plane of symmetry, q over its half-width.
add_test(NAME CptTool.PlaneStrainStripStaysOnItsPlaneOfSymmetry
         COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/tests/check_plane_strain_strip.py
                 $<TARGET_FILE:mpile> ${CMAKE_CURRENT_BINARY_DIR}/plane_strain_strip)
set_tests_properties(CptTool.PlaneStrainStripStaysOnItsPlaneOfSymmetry PROPERTIES LABELS study)

# The convergence tool (Richardson extrapolation, observed order, error bands) on values whose
# limit and order are known exactly.
add_test(NAME Convergence.RecoversTheLimitAndOrderOfAKnownSeries
         COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/tests/convergence_test.py)
set_tests_properties(Convergence.RecoversTheLimitAndOrderOfAKnownSeries PROPERTIES
                     PASS_REGULAR_EXPRESSION "\nall ok\n")

# fuzz_cases.py --first: a run from mutant N draws exactly the whole run's mutants from N on.
add_test(NAME Fuzz.FirstDrawsTheWholeRunsMutantsFromThere
         COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/tests/fuzz_first_test.py)
set_tests_properties(Fuzz.FirstDrawsTheWholeRunsMutantsFromThere PROPERTIES
                     PASS_REGULAR_EXPRESSION "^ok\n")

# Mutants of every shipped case file through `mpile check`: each accepted (exit 0) or refused with
# a message naming the file (exit 2) within 5 s of CPU time and 1 GiB of address space, none crashing
# (tools/fuzz_cases.py; docs/reliability.md). A fixed seed, so a failure replays. Under
# AddressSanitizer fewer mutants and no address-space bound (ASan reserves terabytes of it);
# ThreadSanitizer adds nothing to a single-threaded reader.
if(MPILE_SANITIZE STREQUAL "")
  add_test(NAME Fuzz.ShippedCaseMutantsAreAcceptedOrRefusedCleanly
           COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/tools/fuzz_cases.py
                   --mpile $<TARGET_FILE:mpile> --mutants 300 --seed 1 --jobs 1 --memory 1024
                   --timeout 5)
elseif(MPILE_SANITIZE STREQUAL "address")
  add_test(NAME Fuzz.ShippedCaseMutantsAreAcceptedOrRefusedCleanly
           COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/tools/fuzz_cases.py
                   --mpile $<TARGET_FILE:mpile> --mutants 120 --seed 1 --jobs 1 --memory 0
                   --budget 768 --timeout 120)
endif()
if(TEST Fuzz.ShippedCaseMutantsAreAcceptedOrRefusedCleanly)
  set_tests_properties(Fuzz.ShippedCaseMutantsAreAcceptedOrRefusedCleanly PROPERTIES TIMEOUT 600
                       PASS_REGULAR_EXPRESSION " 0 failures\n")
endif()

# Mutants of the element-test files through `mpile element-test`, which reads and runs each: as
# above, or stopped with exit 1 and a message naming the file where the material cannot follow the
# path (1 500 mutants at seed 1: 216 accepted, 1 280 refused, 4 stopped, none failed).
if(MPILE_SANITIZE STREQUAL "")
  add_test(NAME Fuzz.ElementTestMutantsAreAcceptedOrRefusedCleanly
           COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/tools/fuzz_cases.py --element-tests
                   --mpile $<TARGET_FILE:mpile> --mutants 200 --seed 1 --jobs 1 --memory 1024
                   --timeout 5)
elseif(MPILE_SANITIZE STREQUAL "address")
  add_test(NAME Fuzz.ElementTestMutantsAreAcceptedOrRefusedCleanly
           COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/tools/fuzz_cases.py --element-tests
                   --mpile $<TARGET_FILE:mpile> --mutants 40 --seed 1 --jobs 1 --memory 0
                   --timeout 120)
endif()
if(TEST Fuzz.ElementTestMutantsAreAcceptedOrRefusedCleanly)
  set_tests_properties(Fuzz.ElementTestMutantsAreAcceptedOrRefusedCleanly PROPERTIES TIMEOUT 600
                       PASS_REGULAR_EXPRESSION " 0 failures\n")
endif()

# The estimate table's tool on the single material point: the pilot runs the whole case, so the
# estimate is the measurement plus start-up; the row must carry both and their ratio, within the
# factor of 2 promised (measured 1.25: the check's start-up measured as the process's age is a
# little longer than a run's). A study: timing under a sanitizer means nothing.
add_test(NAME EstimateTable.PrintsTheEstimateTheRunAndTheirRatio
         COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/tools/estimate_table.py
                 ${PROJECT_SOURCE_DIR}/cases/verification/single_point.toml --pilot 5 --threads 1
                 --mpile $<TARGET_FILE:mpile> --out ${CMAKE_CURRENT_BINARY_DIR}/estimate_table)
# Alone (RUN_SERIAL): it times a 0.1 s run against its pilot, and a test running beside it on two
# cores made the run twice as long as the pilot said (0.49).
set_tests_properties(EstimateTable.PrintsTheEstimateTheRunAndTheirRatio PROPERTIES
  LABELS study RUN_SERIAL TRUE
  PASS_REGULAR_EXPRESSION "\n\\| `verification/single_point` \\| 5 \\| [0-9.e-]+ \\| [0-9.e-]+ \\| (0\\.[5-9][0-9]|1\\.[0-9][0-9]) \\|\n")

# tools/results_tables.py (docs/results.md's quick-case tables from the runs' histories) on a
# synthetic run whose forces are known, and its check of a page's tables against runs: a table
# edited by one digit reported, an unchanged one passed.
add_test(NAME ResultsTables.WritesTheSyntheticRunsNumbersAndFindsStaleTables
         COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/tests/results_tables_test.py)
set_tests_properties(ResultsTables.WritesTheSyntheticRunsNumbersAndFindsStaleTables PROPERTIES
                     PASS_REGULAR_EXPRESSION "\nall ok\n")
# docs/results.md's quick-case tables against the code as built: the four quick cases run afresh,
# one at a time on two threads (about 65 s on two idle cores), and every step count, end
# penetration, energy residual, time, force and friction ratio of the tables compared to its
# printed digits. The engine gives the same bits on any thread count, so only the rounding may
# differ: a change that moves a printed number fails here with the cells listed, until the tables
# are run and written again (docs/results.md). A study: whole runs, release only. PROCESSORS 2:
# its runs use two threads, which ctest -j counts.
add_test(NAME ResultsTables.PageTablesAgreeWithFreshQuickRuns
         COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/tools/results_tables.py check
                 --mpile $<TARGET_FILE:mpile> --threads 2
                 --out ${CMAKE_CURRENT_BINARY_DIR}/results_tables)
set_tests_properties(ResultsTables.PageTablesAgreeWithFreshQuickRuns PROPERTIES
                     LABELS study TIMEOUT 600 PROCESSORS 2)

# Every tools/ script, cases/ file and mpile subcommand that README.md and docs/tutorial.md show
# exists.
add_test(NAME Docs.CommandsNameFilesAndSubcommandsThatExist
         COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/tests/doc_commands_test.py $<TARGET_FILE:mpile>)
set_tests_properties(Docs.CommandsNameFilesAndSubcommandsThatExist PROPERTIES
                     PASS_REGULAR_EXPRESSION "\nall ok\n")

# docs/tutorial.md's commands in order, the installations stopped at 0.02 m (tests/tutorial_run.py):
# about a minute on two cores. A study: whole runs, which the sanitizer builds need not repeat.
if(XVFB_RUN)
  add_test(NAME Docs.TutorialRunsCutShort
           COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/tests/tutorial_run.py $<TARGET_FILE:mpile>
                   ${CMAKE_CURRENT_BINARY_DIR}/tutorial)
  set_tests_properties(Docs.TutorialRunsCutShort PROPERTIES LABELS study TIMEOUT 600
                       RESOURCE_LOCK xvfb PASS_REGULAR_EXPRESSION "\ntutorial ok: ")
endif()

# The independent reference for the Hertz impact (tools/hertz_fe.py) on 4 mm elements, 2 s: the
# clipped and snapped mesh weighs the sphere's 0.66667 kg/rad to 0.03 %; central differences with a
# kinematic contact give back the kinetic energy of a purely elastic impact within 0.2 % (measured
# 0.9989); the contact lasts 44 to 50 ms, -10 % to +2 % of Hertz's 48.99 (measured -5.0 %; -5.9 %
# and -4.2 % on 2 and 1 mm, docs/verification.md): a wrong stiffness, mass or contact law leaves
# these.
add_test(NAME HertzFe.FourMillimetreElementsKeepMassEnergyAndNearlyHertzsTime
         COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/tools/hertz_fe.py --cell 4e-3)
set_tests_properties(HertzFe.FourMillimetreElementsKeepMassEnergyAndNearlyHertzsTime PROPERTIES
  PASS_REGULAR_EXPRESSION
  "mass 0\\.666[4-9][0-9] kg/rad[^\n]*\ncontact time 4[4-9]\\.[0-9]+ ms against Hertz's 48\\.986 [^\n]*kinetic energy back 0\\.99[89]")
# The same sphere quasi-static (tools/hertz_fe.py --quasi-static) on 1 mm elements, 2 s: no node
# passes the plane; at approaches of 0.05 and 0.1 of Hertz's delta_max, where the finite size
# matters least, the force is Hertz's within 5 % (measured +2.0 and +4.2 %; +2.3 and +3.8 % on
# 0.25 mm: the finite sphere's stiffening, +14 % at delta_max); the time integral gives Hertz's
# 2.9433 delta_max / v back from Hertz's F(delta) to 1e-6; the contact time is -4.40 to -4.79 % of
# Hertz's, 0.2 % about the measured -4.59 % (-4.63 and -4.60 % on 0.5 and 0.25 mm), which holds the
# converged value and not the dynamic model's -4.2 %. A wrong stiffness, mass, body force or
# contact fails.
add_test(NAME HertzFe.QuasiStaticMillimetreElementsFollowHertzsForceWhenShallowAndLastLess
         COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/tools/hertz_fe.py --cell 1e-3 --quasi-static)
set_tests_properties(HertzFe.QuasiStaticMillimetreElementsFollowHertzsForceWhenShallowAndLastLess PROPERTIES
  PASS_REGULAR_EXPRESSION
  "mass 0\\.6666[0-9] kg/rad; [0-9]+ nodes may touch; no node passes the plane [^\n]*\nF / Hertz's at delta / Hertz's delta_max = 0\\.05 (0\\.9[5-9]|1\\.0[0-4])[0-9]*, 0\\.1 (0\\.9[5-9]|1\\.0[0-4])[0-9]*,[^\n]*\nthe integral on Hertz's F\\(delta\\): 48\\.9859 ms against 48\\.9859\ncontact time 4[0-9.]+ ms against Hertz's 48\\.986 \\(-4\\.[4-7][0-9] %\\)")

# Hypoplasticity: the independent reference integrator against the model's closed forms (its own
# pytest), and the engine's element tests against it (docs/hypoplasticity.md).
add_pytest(HypoplasticReference.Pytest hypoplastic_reference_test.py)
# The seed sand's hypoplastic set (tools/calibrate_seed_sand.py): the case files and the page carry
# the shipped set, no fitted value moved by a little more than its rounding lowers the fit's
# objective, and the page's table is the tool's. About 10 s.
add_pytest(CalibrateSeedSand.Pytest calibrate_seed_sand_test.py)
add_test(NAME Hypoplastic.ElementTestsMeetTheIndependentIntegration
         COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/tests/hypoplastic_against_reference.py
                 $<TARGET_FILE:mpile> ${CMAKE_CURRENT_BINARY_DIR}/hypoplastic_reference)
# Long: 19 s under ASan, mostly the Python integrator's; CaseFiles.EveryElementTestFileRuns drives
# the engine's hypoplastic update through the same element tests there.
set_tests_properties(Hypoplastic.ElementTestsMeetTheIndependentIntegration PROPERTIES LABELS long
                     PASS_REGULAR_EXPRESSION "all within 0.0001\n")

# Mandel's problem (docs/consolidation.md): the closed form against its Laplace
# transform inverted numerically (Python alone), and the two coarse cases against it (about 2 s
# each). The lid (the top grid line moved as the closed form's plate) meets it: measured at
# f3801ae, the centre's Mandel-Cryer peak 0.47 % low, |p - ref| <= 0.0054 p0 after the load's rise,
# the reaction within 0.75 % of F, the ledger within 1.3 %; the bounds are about twice those. The
# force-driven plate carries its load to 0.02 % (bound 0.1 %) and shows the rise. While the water
# was tied to the plate in both directions at its wall (no flow along its underside) the peak was
# 3.0 % low, the pressure lagged by up to 0.041 p0 and the ledger peaked at 3.6 %; with the water
# flowing along the wall, 2.86 %, 0.0338 p0 and 3.3 % (pure FLIP below: 0.90 %, 0.0129 p0, 1.29 %,
# were 3 %, 0.041 p0, 1.54 %). Bounds 0.04, 0.05 and 0.05 (FLIP: 0.02, 0.025, 0.03): the wall cells'
# soil, which the pressure moves and the contact corrects a step later, is what is left. The free
# face's u_x at T: +0.93 % (lid) and +0.55 % (plate) since the water takes PIC under XPIC (18 and 17 %
# short while its FLIP deviation, the transfer's smoothing of the Darcy flow at the face, was
# relaxed into the skeleton); bound 2 %, about twice the lid's.
add_pytest(Mandel.Pytest mandel_test.py)
foreach(lid_or_plate lid plate)
  set(mandel_output ${CMAKE_CURRENT_BINARY_DIR}/mandel_${lid_or_plate})
  add_test(NAME Mandel.Run_${lid_or_plate}
           COMMAND mpile run ${PROJECT_SOURCE_DIR}/cases/verification/mandel_${lid_or_plate}.toml
                   --threads 1 --out ${mandel_output})
  set_tests_properties(Mandel.Run_${lid_or_plate} PROPERTIES FIXTURES_SETUP mandel_${lid_or_plate}
                       LABELS study)
  if(lid_or_plate STREQUAL "lid")
    set(mandel_bounds --expect peak=0.01 --expect after_rise=0.01 --expect reaction=0.015
                      --expect residual=0.025 --expect free_face=0.02)
  else()
    set(mandel_bounds --expect peak=0.04 --expect after_rise=0.05 --expect reaction=0.001
                      --expect residual=0.05 --expect free_face=0.02)
  endif()
  add_test(NAME Mandel.MeetsTheClosedForm_${lid_or_plate}
           COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/tools/mandel.py --compare ${mandel_output}
                   ${mandel_bounds})
  set_tests_properties(Mandel.MeetsTheClosedForm_${lid_or_plate} PROPERTIES
                       FIXTURES_REQUIRED mandel_${lid_or_plate} LABELS study
                       PASS_REGULAR_EXPRESSION "mandel check: ok\n")
endforeach()
# The plate under pure FLIP at Courant 0.2 to 2 T (70 770 steps, about 13 s): implicit pore pressure
# with FLIP in slow consolidation went unstable after 10 000 to 35 000 steps while the projection
# booked its correction's kinetic energy as damping and moved the particles with the uncorrected
# velocity; at f3801ae it ran through, its ledger within 1.54 % (bound 3 %), the rest as above.
set(mandel_output ${CMAKE_CURRENT_BINARY_DIR}/mandel_plate_flip)
add_test(NAME Mandel.Run_plate_flip
         COMMAND mpile run ${PROJECT_SOURCE_DIR}/cases/verification/mandel_plate.toml --threads 1
                 --out ${mandel_output} --set solver.xpic_order=0 --set solver.courant_number=0.2
                 --set phases.0.duration=20.0)
set_tests_properties(Mandel.Run_plate_flip PROPERTIES FIXTURES_SETUP mandel_plate_flip LABELS study)
add_test(NAME Mandel.MeetsTheClosedForm_plate_flip
         COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/tools/mandel.py --compare ${mandel_output}
                 --expect peak=0.02 --expect after_rise=0.025 --expect reaction=0.001
                 --expect residual=0.03)
set_tests_properties(Mandel.MeetsTheClosedForm_plate_flip PROPERTIES
                     FIXTURES_REQUIRED mandel_plate_flip LABELS study
                     PASS_REGULAR_EXPRESSION "mandel check: ok\n")


# Barron's radial consolidation (docs/consolidation.md): the free strain series against a
# finite-volume solution, the short-time flux into a cylinder and equal strain (Python alone, 2 s).
add_pytest(Barron.Pytest barron_test.py)
# tools/step_levels.py (docs/performance.md, the fine band at its own step): levels and costs.
add_pytest(StepLevels.Pytest step_levels_test.py)

# The coarse cell (18 x 2 cells) under the lid moved as the series settles, to t = 1.4 s (the
# series' U = 0.5 at 1.35 s), explicitly at Courant 0.8 and 0.4 and with the implicit pore
# pressure: a drain that restarted its water's velocity from the particles' each step passed 0.6
# of its Darcy flux, less as the step shrank, and the runs lagged the series by 0.070 / 0.074 in U
# at U = 0.2 (implicit 0.055) and by 0.042 at U = 0.5. With the drain's velocity kept (Grid::
# drain_water_velocity) they lag by 0.0177 / 0.0160 / 0.025 and 0.0108 / 0.0097 / 0.0148 (the
# grid's own finite-volume scheme: 0.030, 0.020), ledgers peaking at 2.6 / 3.1 / 3.1 % in the
# load's rise (measured on the whole run to 5 s). Bounds 0.03 and 0.02 hold the error of these
# 18 cells with the margin that halving the cells takes away (0.0037 then), and fail the old
# drain; the ledger's 5 % is the run's warning level, which the old drain's 6.8 % crossed.
# The plate variant: the cell under its rigid frictionless plate (force-driven), to t = 1.4 s.
# While the water was tied to the plate's underside in both directions (no flow along the wall,
# physics.md 9b) it lagged the series by 0.069 at U = 0.2 and 0.168 at U = 0.5 (b907032); flowing along the wall
# (update_water_velocities' split after the contact) it lags by 0.0046 and 0.0079, within the grid's
# own scheme's 0.0077 and 0.0131, the ledger at most 1.1 %. Bounds 0.015, 0.02 and 5 % as the lid's.
foreach(variant c08 c04 implicit plate)
  set(barron_output ${CMAKE_CURRENT_BINARY_DIR}/barron_${variant})
  set(barron_case radial_consolidation)
  set(barron_settings --set phases.0.duration=1.4)
  set(barron_u02 0.03)
  if(variant STREQUAL "c04")
    list(APPEND barron_settings --set solver.courant_number=0.4)
  elseif(variant STREQUAL "implicit")
    list(APPEND barron_settings --set solver.implicit_pore_pressure=true
         --set solver.cell_mean_pore_pressure=true)
  elseif(variant STREQUAL "plate")
    set(barron_case radial_consolidation_plate)
    set(barron_u02 0.015)
  endif()
  add_test(NAME Barron.Run_${variant}
           COMMAND mpile run ${PROJECT_SOURCE_DIR}/cases/verification/${barron_case}.toml
                   --threads 1 --out ${barron_output} ${barron_settings})
  set_tests_properties(Barron.Run_${variant} PROPERTIES FIXTURES_SETUP barron_${variant}
                       LABELS study)
  add_test(NAME Barron.MeetsTheSeries_${variant}
           COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/tools/barron.py --compare ${barron_output}
                   --no-profile --expect U0.2=${barron_u02} --expect U0.5=0.02
                   --expect residual=0.05)
  set_tests_properties(Barron.MeetsTheSeries_${variant} PROPERTIES
                       FIXTURES_REQUIRED barron_${variant} LABELS study
                       PASS_REGULAR_EXPRESSION "barron check: ok\n")
endforeach()

# The cyclic installation's regression (tests/check_friction_fatigue.py, docs/results.md "Friction
# fatigue"): five of GDP's torque cycles at 3 m on the quick mesh, Hardening Soil and the
# hypoplastic sand (about 35 and 60 s on one thread): the hypoplastic sand beside the shaft keeps
# 0.67 / 0.55 / 0.51 of its radial effective stress at 1.5 / 2.0 / 2.5 m, Hardening Soil 1.06 /
# 0.99 / 1.12; the bounds and why in the script. It guards the cases as shipped, under FLIP: under
# XPIC(2) the hypoplastic sand keeps its grip over five cycles (docs/results.md), so the loss is
# FLIP's noise working through the model, and this is a regression check, not a physical claim.
foreach(model hardening_soil hypoplastic)
  if(model STREQUAL "hypoplastic")
    set(cycles_case gdp_cycles_quick_hypoplastic)
  else()
    set(cycles_case gdp_cycles_quick)
  endif()
  add_test(NAME FrictionFatigue.Run_${model}
           COMMAND mpile run ${PROJECT_SOURCE_DIR}/cases/monopile/${cycles_case}.toml --threads 1
                   --out ${CMAKE_CURRENT_BINARY_DIR}/fatigue_${model} --set phases.1.duration=0.085)
  set_tests_properties(FrictionFatigue.Run_${model} PROPERTIES FIXTURES_SETUP fatigue_${model}
                       LABELS study)
endforeach()
add_test(NAME FrictionFatigue.TheHypoplasticSandLosesItsGripInFiveCyclesHardeningSoilDoesNot
         COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/tests/check_friction_fatigue.py
                 ${CMAKE_CURRENT_BINARY_DIR}/fatigue_hardening_soil
                 ${CMAKE_CURRENT_BINARY_DIR}/fatigue_hypoplastic)
set_tests_properties(FrictionFatigue.TheHypoplasticSandLosesItsGripInFiveCyclesHardeningSoilDoesNot
                     PROPERTIES FIXTURES_REQUIRED "fatigue_hardening_soil;fatigue_hypoplastic"
                     LABELS study PASS_REGULAR_EXPRESSION "friction fatigue check: ok\n")

# The vibratory model test, coarse (docs/vibratory-model-test.md): jacked to 0.15 m, then half a
# second of the 25 Hz drive (about 36 000 steps, a minute on one thread). After 0.5 s the pile has
# sunk 17.1 mm against the measured 21.4 (5796479: the water starts from its own field under XPIC;
# 23.2 while its FLIP deviation was relaxed into the skeleton, 19.8 before 1d287a4). The whole run
# is 0.68 to 0.80 of the measurement from 0.5 to 3 s; the band 0.25 holds that agreement at 0.5 s
# and fails a pile that does not sink (Karlsruhe fine sand's reading gives -2.8 mm there).
add_test(NAME VibratoryModelTest.Run_coarse
         COMMAND mpile run ${PROJECT_SOURCE_DIR}/cases/model_tests/vibratory_vogelsang.toml
                 --threads 1 --out ${CMAKE_CURRENT_BINARY_DIR}/vibratory_coarse
                 --set phases.2.duration=0.53)
set_tests_properties(VibratoryModelTest.Run_coarse PROPERTIES FIXTURES_SETUP vibratory_coarse
                     LABELS study)
add_test(NAME VibratoryModelTest.SinksAsTheMeasuredPileDidInItsFirstHalfSecond
         COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/tools/vibratory_compare.py
                 ${CMAKE_CURRENT_BINARY_DIR}/vibratory_coarse --expect 0.5=0.25)
set_tests_properties(VibratoryModelTest.SinksAsTheMeasuredPileDidInItsFirstHalfSecond PROPERTIES
                     FIXTURES_REQUIRED vibratory_coarse LABELS study
                     PASS_REGULAR_EXPRESSION "vibratory check: ok\n")
