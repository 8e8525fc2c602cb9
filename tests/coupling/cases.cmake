# Coupled cases, shortened: the sphere settles to the Schiller-Naumann terminal
# velocity within 2 % (its Allrun checks), on 1 and on 2 ranks with the same trajectory.
# It starts at z = 75 mm so that it crosses the ranks' boundary (z = 60 mm) on 2 ranks.
set(PYTHON /usr/bin/python3)
foreach(np 1 2)
  add_test(NAME sphereSettlingSmall_np${np}
    COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/runCase.sh ${PROJECT_SOURCE_DIR}/cases/sphereSettling
            ${COUPLING_WORK}/sphereSettling_np${np} ${np} 0.25
            constant/couplingProperties:demVariables/z0=0.075)
  set_tests_properties(sphereSettlingSmall_np${np} PROPERTIES
    FIXTURES_SETUP settling_np${np} TIMEOUT 300 PROCESSORS ${np}
    ENVIRONMENT "${FOAM_ENV};OMPI_MCA_mpi_yield_when_idle=1")
endforeach()
add_test(NAME sphereSettlingSmall_oneVsTwoRanks
  COMMAND ${PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/compareTrajectories.py
          ${COUPLING_WORK}/sphereSettling_np1 ${COUPLING_WORK}/sphereSettling_np2)
set_tests_properties(sphereSettlingSmall_oneVsTwoRanks PROPERTIES
  FIXTURES_REQUIRED "settling_np1;settling_np2")

# The way to terminal velocity, too: within 2 % of v_t of the ODE at every
# coupling step, without and with added mass (C_a = 0.5 changes the ODE's
# velocity by up to 7.6 % of v_t, so each check can fail).
add_test(NAME sphereSettlingSmall_transient
  COMMAND ${PYTHON} ${PROJECT_SOURCE_DIR}/cases/sphereSettling/compareWithOde.py
          ${COUPLING_WORK}/sphereSettling_np1 --max-deviation 0.02)
set_tests_properties(sphereSettlingSmall_transient PROPERTIES FIXTURES_REQUIRED settling_np1)
add_test(NAME sphereSettlingAddedMass
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/runCase.sh ${PROJECT_SOURCE_DIR}/cases/sphereSettling
          ${COUPLING_WORK}/sphereSettlingAddedMass 1 0.25
          constant/couplingProperties:addedMassCoefficient=0.5)
set_tests_properties(sphereSettlingAddedMass PROPERTIES
  FIXTURES_SETUP settlingAddedMass TIMEOUT 300 ENVIRONMENT "${FOAM_ENV}")
add_test(NAME sphereSettlingAddedMass_transient
  COMMAND ${PYTHON} ${PROJECT_SOURCE_DIR}/cases/sphereSettling/compareWithOde.py
          ${COUPLING_WORK}/sphereSettlingAddedMass --max-deviation 0.02)
set_tests_properties(sphereSettlingAddedMass_transient PROPERTIES FIXTURES_REQUIRED settlingAddedMass)

# Bad couplingProperties and controlDict entries: a clear message and a non-zero exit.
add_test(NAME iceFoam_badInput
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/badInput.sh ${PROJECT_SOURCE_DIR}/cases/sphereSettling
          ${COUPLING_WORK}/badInput $<TARGET_FILE:iceFoam>)
set_tests_properties(iceFoam_badInput PROPERTIES TIMEOUT 300 ENVIRONMENT "${FOAM_ENV}")

# Light particles (ice): explicit drag exchange diverges where the semi-implicit
# one relaxes, the stability check refuses it, and momentum is conserved.
add_test(NAME lightCloud_stabilityAndMomentum
  COMMAND ${PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/lightCloudStability.py
          ${CMAKE_CURRENT_SOURCE_DIR}/lightCloud ${COUPLING_WORK}/lightCloud $<TARGET_FILE:iceFoam>)
set_tests_properties(lightCloud_stabilityAndMomentum PROPERTIES TIMEOUT 300 ENVIRONMENT "${FOAM_ENV}")

# 1,728 particles in the periodic light cloud, moving across the boundary between
# the ranks and through the periodic faces: 1 and 2 ranks, same trajectories.
foreach(np 1 2)
  add_test(NAME lightCloud_np${np}
    COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/runIceFoam.sh $<TARGET_FILE:iceFoam>
            ${CMAKE_CURRENT_SOURCE_DIR}/lightCloud ${COUPLING_WORK}/lightCloud_np${np} ${np}
            system/controlDict:endTime=1.12)
  set_tests_properties(lightCloud_np${np} PROPERTIES
    FIXTURES_SETUP cloud_np${np} TIMEOUT 300 PROCESSORS ${np} ENVIRONMENT "${FOAM_ENV}")
endforeach()
add_test(NAME lightCloud_oneVsTwoRanks
  COMMAND ${PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/compareTrajectories.py
          ${COUPLING_WORK}/lightCloud_np1 ${COUPLING_WORK}/lightCloud_np2)
set_tests_properties(lightCloud_oneVsTwoRanks PROPERTIES FIXTURES_REQUIRED "cloud_np1;cloud_np2")
# ... and each rank held only the particles near its half of the mesh (about
# half of them, plus those whose spheres reach across the boundary).
add_test(NAME lightCloud_localExchange
  COMMAND ${PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/checkLocalExchange.py ${COUPLING_WORK}/lightCloud_np2/log.iceFoam)
set_tests_properties(lightCloud_localExchange PROPERTIES FIXTURES_REQUIRED cloud_np2)

# Floating ice at the water surface (waterLevel): the draft of a sphere.
add_test(NAME floatingSphere_run
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/runIceFoam.sh $<TARGET_FILE:iceFoam>
          ${CMAKE_CURRENT_SOURCE_DIR}/floatingSphere ${COUPLING_WORK}/floatingSphere 1)
set_tests_properties(floatingSphere_run PROPERTIES
  FIXTURES_SETUP floating TIMEOUT 300 ENVIRONMENT "${FOAM_ENV}")
add_test(NAME floatingSphere_draft
  COMMAND ${PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/checkFloating.py ${COUPLING_WORK}/floatingSphere)
set_tests_properties(floatingSphere_draft PROPERTIES FIXTURES_REQUIRED floating)

# Packed bed (cases/packedBed), small: 800 glass spheres settled and fixed in a
# 12 mm periodic column, water pushed through at Re_s = 1, 20 and 5: the
# pressure gradient inside the bed within 10 % of Ergun at the measured porosity.
add_test(NAME packedBedSmall_run
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/runIceFoam.sh $<TARGET_FILE:iceFoam>
          ${PROJECT_SOURCE_DIR}/cases/packedBed ${COUPLING_WORK}/packedBedSmall 1
          "system/blockMeshDict:vertices=((0 0 0) (12 0 0) (12 12 0) (0 12 0) (0 0 108) (12 0 108) (12 12 108) (0 12 108))"
          "system/blockMeshDict:blocks=(hex (0 1 2 3 4 5 6 7) (2 2 18) simpleGrading (1 1 1))"
          constant/couplingProperties:demVariables/width=0.012
          constant/couplingProperties:demVariables/particleCount=800
          system/controlDict:endTime=0.3)
set_tests_properties(packedBedSmall_run PROPERTIES
  FIXTURES_SETUP packedBedSmall TIMEOUT 300 ENVIRONMENT "${FOAM_ENV}")
add_test(NAME packedBedSmall_ergun
  COMMAND ${PYTHON} ${PROJECT_SOURCE_DIR}/cases/packedBed/ergun.py fixed ${COUPLING_WORK}/packedBedSmall
          --tolerance 0.1)
set_tests_properties(packedBedSmall_ergun PROPERTIES FIXTURES_REQUIRED packedBedSmall)

# settlingBedDEM (the benchmark's DEM-only runs): a level it does not run, and a
# case without couplingProperties, are refused with the entry named and exit 1.
add_test(NAME settlingBedDEM_badInput
  COMMAND sh -c "\"$1\" -hydrodynamics cfd > bad.log 2>&1; a=$?; grep -q \"'-hydrodynamics': 'cfd' is not one of: none hydrostatic\" bad.log || exit 2; \"$1\" -case /nonexistent -hydrodynamics none > bad.log 2>&1; b=$?; grep -q 'couplingProperties' bad.log && [ $a -eq 1 ] && [ $b -eq 1 ]"
          sh $<TARGET_FILE:settlingBedDEM>)
set_tests_properties(settlingBedDEM_badInput PROPERTIES TIMEOUT 60 WORKING_DIRECTORY ${COUPLING_WORK})

# Floating block of bonded ice spheres at the cfd level (cases/floatingBlock/cfd),
# small: 4 x 4 x 2 spheres released 1.6 cm above their draft, bonds and contacts
# 100 times softer (the equilibrium does not depend on the stiffness; the DEM
# step grows tenfold, which keeps the 2-rank run short on busy cores).
# Submerged volume fraction within 1 % of rho_i/rho_w, at rest (kinetic energy
# below 1e-6 M g H for the last second), no sideways drift, every bond intact;
# 1 and 2 ranks the same trajectories.
foreach(np 1 2)
  add_test(NAME floatingBlockCfdSmall_np${np}
    COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/runIceFoam.sh $<TARGET_FILE:iceFoam>
            ${PROJECT_SOURCE_DIR}/cases/floatingBlock/cfd ${COUPLING_WORK}/floatingBlockCfd_np${np} ${np}
            constant/couplingProperties:demVariables/spheresX=4
            constant/couplingProperties:demVariables/spheresY=4
            constant/couplingProperties:demVariables/layers=2
            constant/couplingProperties:demVariables/releaseDepth=0.08
            constant/couplingProperties:demVariables/demTimeStep=2.5e-4
            constant/couplingProperties:couplingInterval=20
            constant/iceProperties:material/youngsModulus=1.95e6
            constant/iceProperties:bondFamilies/ice/youngsModulus=1.95e6
            system/controlDict:endTime=4
            system/controlDict:writeInterval=4)
  set_tests_properties(floatingBlockCfdSmall_np${np} PROPERTIES
    FIXTURES_SETUP floatingBlockCfd_np${np} TIMEOUT 300 PROCESSORS ${np} ENVIRONMENT "${FOAM_ENV}")
endforeach()
foreach(np 1 2)
  add_test(NAME floatingBlockCfdSmall_draft_np${np}
    COMMAND ${PYTHON} ${PROJECT_SOURCE_DIR}/cases/floatingBlock/cfd/draftFromParticles.py
            ${COUPLING_WORK}/floatingBlockCfd_np${np} --ranks ${np} --check)
  set_tests_properties(floatingBlockCfdSmall_draft_np${np} PROPERTIES FIXTURES_REQUIRED floatingBlockCfd_np${np})
endforeach()
# Not to round-off: the decomposed fluid sums the particles' shares in another
# order, and the bonded block's dynamics (hysteretic damping's sign(v) of
# round-off-level velocities) amplifies that: measured 2.2e-8 m of 0.031 m
# travelled, 1.2e-6 of 0.15 m/s (cases/floatingBlock/README.md). Within 1e-4.
add_test(NAME floatingBlockCfdSmall_oneVsTwoRanks
  COMMAND ${PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/compareTrajectories.py
          ${COUPLING_WORK}/floatingBlockCfd_np1 ${COUPLING_WORK}/floatingBlockCfd_np2 --tolerance 1e-4)
set_tests_properties(floatingBlockCfdSmall_oneVsTwoRanks PROPERTIES
  FIXTURES_REQUIRED "floatingBlockCfd_np1;floatingBlockCfd_np2")
add_test(NAME floatingBlockCfd_badInput
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/badInput.sh ${PROJECT_SOURCE_DIR}/cases/floatingBlock/cfd
          ${COUPLING_WORK}/badIceInput $<TARGET_FILE:iceFoam> bondedIce)
set_tests_properties(floatingBlockCfd_badInput PROPERTIES TIMEOUT 300 ENVIRONMENT "${FOAM_ENV}")

# The same small, soft block at the vof level (cases/floatingBlock/vof,
# iceInterFoam): water and air, the surface free to move. The same checks
# (the level now that of the columns no particle reaches), 1 and 2 ranks the
# same trajectories (measured 1.2e-7 m of 0.025 m travelled).
foreach(np 1 2)
  add_test(NAME floatingBlockVofSmall_np${np}
    COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/runIceFoam.sh $<TARGET_FILE:iceInterFoam>
            ${PROJECT_SOURCE_DIR}/cases/floatingBlock/vof ${COUPLING_WORK}/floatingBlockVof_np${np} ${np}
            constant/couplingProperties:demVariables/spheresX=4
            constant/couplingProperties:demVariables/spheresY=4
            constant/couplingProperties:demVariables/layers=2
            constant/couplingProperties:demVariables/releaseDepth=0.08
            constant/couplingProperties:demVariables/demTimeStep=2.5e-4
            constant/couplingProperties:couplingInterval=20
            constant/iceProperties:material/youngsModulus=1.95e6
            constant/iceProperties:bondFamilies/ice/youngsModulus=1.95e6
            system/controlDict:endTime=4
            system/controlDict:writeInterval=4)
  set_tests_properties(floatingBlockVofSmall_np${np} PROPERTIES
    FIXTURES_SETUP floatingBlockVof_np${np} TIMEOUT 300 PROCESSORS ${np} ENVIRONMENT "${FOAM_ENV}")
  add_test(NAME floatingBlockVofSmall_draft_np${np}
    COMMAND ${PYTHON} ${PROJECT_SOURCE_DIR}/cases/floatingBlock/cfd/draftFromParticles.py
            ${COUPLING_WORK}/floatingBlockVof_np${np} --ranks ${np} --check)
  set_tests_properties(floatingBlockVofSmall_draft_np${np} PROPERTIES FIXTURES_REQUIRED floatingBlockVof_np${np})
endforeach()
add_test(NAME floatingBlockVofSmall_oneVsTwoRanks
  COMMAND ${PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/compareTrajectories.py
          ${COUPLING_WORK}/floatingBlockVof_np1 ${COUPLING_WORK}/floatingBlockVof_np2 --tolerance 1e-4)
set_tests_properties(floatingBlockVofSmall_oneVsTwoRanks PROPERTIES
  FIXTURES_REQUIRED "floatingBlockVof_np1;floatingBlockVof_np2")
# Closed tank: the whole block pushed down from above the water at 0.2 m/s
# until its top is 14 cm under and held there (vof/tankCheck.py): the level
# rises by the ice's volume over the tank's area (within 2 %), the pressure
# force on the ice equals its buoyancy (within 1 %); 1 and 2 ranks.
foreach(np 1 2)
  add_test(NAME floatingBlockVofTank_np${np}
    COMMAND sh -c "\"$0\" \"$@\" && ${PYTHON} ${PROJECT_SOURCE_DIR}/cases/floatingBlock/vof/tankCheck.py ${COUPLING_WORK}/floatingBlockVofTank_np${np} --check"
            ${CMAKE_CURRENT_SOURCE_DIR}/runIceFoam.sh $<TARGET_FILE:iceInterFoam>
            ${PROJECT_SOURCE_DIR}/cases/floatingBlock/vof ${COUPLING_WORK}/floatingBlockVofTank_np${np} ${np}
            constant/couplingProperties:vof/initialLevel=-0.05
            constant/couplingProperties:demVariables/pushDepth=0.4
            constant/couplingProperties:demVariables/pushSpeed=0.2
            system/controlDict:endTime=4
            system/controlDict:writeInterval=4)
  set_tests_properties(floatingBlockVofTank_np${np} PROPERTIES TIMEOUT 300 PROCESSORS ${np} ENVIRONMENT "${FOAM_ENV}")
endforeach()
add_test(NAME floatingBlockVof_badInput
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/badInput.sh ${PROJECT_SOURCE_DIR}/cases/floatingBlock/vof
          ${COUPLING_WORK}/badVofInput $<TARGET_FILE:iceInterFoam> vof)
set_tests_properties(floatingBlockVof_badInput PROPERTIES TIMEOUT 300 ENVIRONMENT "${FOAM_ENV}")
