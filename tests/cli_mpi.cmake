# cmake -DSPECTRACE=... -DCOMPARE=... -DMPIEXEC=... -DSCENE=... -DDIR=... -DDEVICE=cpu|gpu -P cli_mpi.cmake
# render --mpi under mpirun with 2 and 3 ranks (3 does not divide the beams)
# gives EXR pixels bit-identical to one process rendering all the beams on
# the same device, and a state holding exactly those beams; bad input and a
# failure on one rank end every rank with exit code 2 and 1, without a hang;
# ranks given different renders (scene, seed) are refused before tracing.
file(REMOVE_RECURSE ${DIR})
file(MAKE_DIRECTORY ${DIR})
# OpenMPI: more ranks than cores (CI machines are small), root in CI
# containers; one node, so no ssh is ever needed (plm_rsh_agent false); and
# shared-memory messages copied through a buffer, not cross-process memory
# access, which containers without ptrace rights refuse.
set(mpirun ${MPIEXEC} --oversubscribe --allow-run-as-root --mca plm_rsh_agent false
           --mca btl_vader_single_copy_mechanism none)
set(beams 1000001)
set(render render ${SCENE} --beams ${beams} --device ${DEVICE} --threads 1 -q --no-png)
include(${CMAKE_CURRENT_LIST_DIR}/cli_helpers.cmake)
# The command must end (no rank left waiting) with exit code `code` and
# print `regex` exactly once.
function(expect_failure code regex)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 120)
  if(NOT rc STREQUAL "${code}")
    message(FATAL_ERROR "expected exit code ${code}, got ${rc}: ${ARGN}\n${out}${err}")
  endif()
  string(REGEX MATCHALL "${regex}" hits "${err}")
  list(LENGTH hits n)
  if(NOT n EQUAL 1)
    message(FATAL_ERROR "expected \"${regex}\" once, found it ${n} times: ${ARGN}\n${err}")
  endif()
endfunction()

run(${SPECTRACE} ${render} -o ${DIR}/whole.exr)
foreach(ranks 2 3)
  run(${mpirun} -np ${ranks} ${SPECTRACE} ${render} --mpi -o ${DIR}/mpi${ranks}.exr --state ${DIR}/mpi${ranks}.state)
  expect_same(${DIR}/mpi${ranks}.exr ${DIR}/whole.exr)
endforeach()
# The state rank 0 wrote holds all the beams, [0, beams), and develops into
# the same image.
run(${SPECTRACE} merge ${DIR}/mpi3.state -o ${DIR}/from_state.exr --device ${DEVICE} -q --no-png)
expect_same(${DIR}/from_state.exr ${DIR}/whole.exr)
file(STRINGS ${DIR}/mpi3.state header LIMIT_INPUT 4096 REGEX "\"ranges\"")
if(NOT header MATCHES "\"ranges\":\\[\\[0,${beams}\\]\\]")
  message(FATAL_ERROR "the state of the 3-rank render does not cover [0, ${beams}) in one range:\n${header}")
endif()

# Bad input: every rank refuses it, the message is printed once (by rank 0).
expect_failure(2 "spectrace: error: [^\n]*no_such_scene.json"
  ${mpirun} -np 2 ${SPECTRACE} render ${DIR}/no_such_scene.json --mpi -q -o ${DIR}/bad.exr)
expect_failure(2 "spectrace: error: --mpi splits the beams over the ranks itself"
  ${mpirun} -np 2 ${SPECTRACE} ${render} --mpi --shard 0/2 -o ${DIR}/bad.exr)
# A failure on rank 1 alone must not leave rank 0 waiting for it: on gpu,
# rank 1 finds no Vulkan driver (run time, exit code 1); on cpu, rank 1 is
# given a scene it cannot read (bad input, exit code 2).
if(DEVICE STREQUAL "gpu")
  expect_failure(1 "spectrace: error: rank 1 of 2: --device gpu"
    ${mpirun} -np 1 ${SPECTRACE} ${render} --mpi -o ${DIR}/one_failed.exr
            : -np 1 env VK_DRIVER_FILES=${DIR}/no_such_driver.json VK_ICD_FILENAMES=${DIR}/no_such_driver.json
              ${SPECTRACE} ${render} --mpi -o ${DIR}/one_failed.exr)
else()
  expect_failure(2 "spectrace: error: rank 1 of 2: [^\n]*no_such_scene.json"
    ${mpirun} -np 1 ${SPECTRACE} ${render} --mpi -o ${DIR}/one_failed.exr
            : -np 1 ${SPECTRACE} render ${DIR}/no_such_scene.json --beams ${beams} --device cpu --mpi -q
              -o ${DIR}/one_failed.exr)
endif()
# Ranks given different renders (another scene, another seed) would have
# their films summed into a wrong image: each rank compares its film's
# fingerprint with rank 0's before tracing, and every rank exits 2, the rank
# that differs naming itself and the field. Rank 0 is not quiet here, so
# its "beams over" line would show that the ranks had started tracing.
file(READ ${SCENE} text)
string(REPLACE "\"power_w\": 1," "\"power_w\": 2," other "${text}")
if(other STREQUAL text)
  message(FATAL_ERROR "${SCENE} has no \"power_w\": 1, to change")
endif()
file(WRITE ${DIR}/other_scene.json "${other}")
set(rank1 ${SPECTRACE} render --beams ${beams} --device ${DEVICE} --threads 1 -q --no-png --mpi -o ${DIR}/differ.exr)
foreach(case "other_scene|scene_sha256: \"[0-9a-f]+\" against \"[0-9a-f]+\""
             "seed|seed: 2 against 1")
  string(REPLACE "|" ";" case "${case}")
  list(GET case 0 what)
  list(GET case 1 field)
  if(what STREQUAL "other_scene")
    set(second ${rank1} ${DIR}/other_scene.json)
    set(named "other_scene.json")
  else()
    set(second ${rank1} ${SCENE} --seed 2)
    set(named "pinhole_rect.json")
  endif()
  execute_process(COMMAND ${mpirun} -np 1 ${SPECTRACE} render ${SCENE} --beams ${beams} --device ${DEVICE}
                          --threads 1 --no-png --mpi -o ${DIR}/differ.exr : -np 1 ${second}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 120)
  if(NOT rc STREQUAL "2")
    message(FATAL_ERROR "${what}: expected exit code 2, got ${rc}\n${out}${err}")
  endif()
  set(regex "spectrace: error: rank 1 of 2: its render of [^\n]*${named} is not rank 0's render of [^\n]*pinhole_rect.json: they differ in ${field} \\(this rank's against rank 0's\\)")
  string(REGEX MATCHALL "${regex}" hits "${err}")
  list(LENGTH hits n)
  if(NOT n EQUAL 1)
    message(FATAL_ERROR "${what}: expected \"${regex}\" once, found it ${n} times:\n${err}")
  endif()
  if(err MATCHES "beams over")
    message(FATAL_ERROR "${what}: the ranks started tracing before refusing:\n${err}")
  endif()
endforeach()
if(EXISTS ${DIR}/one_failed.exr OR EXISTS ${DIR}/bad.exr OR EXISTS ${DIR}/differ.exr)
  message(FATAL_ERROR "a failed MPI render wrote an image")
endif()
